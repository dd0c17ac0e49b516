#!/usr/bin/env python3
"""Walks through `dynrad view`'s page in headless Chromium with real input events.

Chromium is driven over the DevTools protocol on a pipe (--remote-debugging-pipe: JSON
messages ending in NUL on file descriptors 3 and 4), so nothing beyond Python's standard
library is needed. Keys, drags and the wheel go in as the browser's own input events; the
page reports where its camera is on <body data-camera="x,y,z,heading,pitch">.

The room is tests/data/lamp_room (as in tests/browser_view_test.cpp): 8 x 3 x 2.7 m, lit
near its x = 0 end; its camera "wall" stands at (4, 0.3, 1.35) looking along +y, which in
the glTF's axes (y up) is (4, 1.35, -0.3) looking along -z.

usage: browser_walk_test.py DYNRAD LAMP_ROOM_SCENE WORK_DIR
"""
import json
import math
import os
import shutil
import subprocess
import sys
import time

failures = []


def check(condition, what):
    print(("ok    " if condition else "FAIL  ") + what)
    if not condition:
        failures.append(what)


class Browser:
    """Headless Chromium and one page, spoken to over the DevTools pipe."""

    def __init__(self, profile):
        to_browser_r, self.to_browser = os.pipe()
        self.from_browser, from_browser_w = os.pipe()

        def descriptors():
            # Through free descriptors first: os.pipe() may have returned 3 or 4 itself,
            # and dup2 onto the same number would leave it closed on exec.
            read_end, write_end = os.dup(to_browser_r), os.dup(from_browser_w)
            os.dup2(read_end, 3)
            os.dup2(write_end, 4)
            os.set_inheritable(3, True)
            os.set_inheritable(4, True)

        self.process = subprocess.Popen(
            ["chromium", "--headless", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
             "--hide-scrollbars", "--no-first-run", "--user-data-dir=" + profile, "--window-size=800,600",
             "--remote-debugging-pipe"],
            preexec_fn=descriptors, close_fds=False, stdout=subprocess.DEVNULL, stderr=open(profile + ".log", "w"))
        os.close(to_browser_r)
        os.close(from_browser_w)
        self.buffer = b""
        self.next_id = 0
        self.session = None
        self.console_errors = []  # what the DevTools console would show in red

    def send(self, method, params=None, session=True):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            message["sessionId"] = self.session
        os.write(self.to_browser, json.dumps(message).encode() + b"\0")
        while True:
            while b"\0" not in self.buffer:
                chunk = os.read(self.from_browser, 1 << 16)
                if not chunk:
                    raise RuntimeError("Chromium closed the pipe")
                self.buffer += chunk
            raw, self.buffer = self.buffer.split(b"\0", 1)
            reply = json.loads(raw)
            self.note(reply)
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RuntimeError(method + ": " + json.dumps(reply["error"]))
                return reply.get("result", {})

    def note(self, event):
        method, params = event.get("method"), event.get("params", {})
        if method == "Runtime.exceptionThrown":
            self.console_errors.append(params["exceptionDetails"].get("text", "exception"))
        elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            self.console_errors.append(" ".join(str(a.get("value", a.get("description"))) for a in params["args"]))
        elif method == "Log.entryAdded" and params["entry"].get("level") == "error":
            self.console_errors.append(params["entry"].get("text", ""))

    def open(self, url):
        target = self.send("Target.createTarget", {"url": url}, session=False)["targetId"]
        self.session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True},
                                 session=False)["sessionId"]
        self.send("Runtime.enable")
        self.send("Log.enable")
        # The page was created before the domains were on: load it again to see it all.
        self.send("Page.reload")

    def evaluate(self, expression):
        return self.send("Runtime.evaluate", {"expression": expression, "returnByValue": True})["result"].get("value")

    def body(self, name):
        return self.evaluate("document.body.dataset.%s" % name)

    def wait_for(self, condition, seconds=60):
        end = time.time() + seconds
        while time.time() < end:
            if condition():
                return True
            time.sleep(0.1)
        return False

    def key(self, key, code, vk, hold=0.0):
        common = {"key": key, "code": code, "windowsVirtualKeyCode": vk, "nativeVirtualKeyCode": vk}
        self.send("Input.dispatchKeyEvent", dict(common, type="rawKeyDown"))
        if len(key) == 1:
            self.send("Input.dispatchKeyEvent", dict(common, type="char", text=key))
        time.sleep(hold)
        self.send("Input.dispatchKeyEvent", dict(common, type="keyUp"))

    def drag(self, x0, y0, x1, y1, steps=10):
        self.send("Input.dispatchMouseEvent", {"type": "mousePressed", "x": x0, "y": y0, "button": "left",
                                               "buttons": 1, "clickCount": 1})
        for k in range(1, steps + 1):
            x = x0 + (x1 - x0) * k / steps
            y = y0 + (y1 - y0) * k / steps
            self.send("Input.dispatchMouseEvent", {"type": "mouseMoved", "x": x, "y": y, "button": "left",
                                                   "buttons": 1})
        self.send("Input.dispatchMouseEvent", {"type": "mouseReleased", "x": x1, "y": y1, "button": "left",
                                               "buttons": 0, "clickCount": 1})

    def wheel(self, delta_y):
        self.send("Input.dispatchMouseEvent", {"type": "mouseWheel", "x": 400, "y": 300, "deltaX": 0,
                                               "deltaY": delta_y})

    def close(self):
        try:
            self.send("Browser.close", session=False)
        except RuntimeError:
            pass
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()


def camera(browser):
    return [float(v) for v in browser.body("camera").split(",")]


def settle(browser):
    """Waits until the camera has stopped moving (two equal readings 0.3 s apart)."""
    last = None
    for _ in range(50):
        now = browser.body("camera")
        if now == last:
            return camera(browser)
        last = now
        time.sleep(0.3)
    return camera(browser)


def main():
    dynrad, scene, work = sys.argv[1], sys.argv[2], sys.argv[3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    glb, page = os.path.join(work, "room.glb"), os.path.join(work, "room.html")
    subprocess.run([dynrad, "solve", scene, "-o", glb, "--quality", "draft"], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([dynrad, "view", glb, "-o", page], check=True, stdout=subprocess.DEVNULL)

    browser = Browser(os.path.join(work, "profile"))
    try:
        browser.open("file://" + page + "#view=wall")
        check(browser.wait_for(lambda: browser.body("state") in ("ready", "error")), "the page loads")
        check(browser.body("state") == "ready", "the page is ready, not in error")
        check(browser.body("view") == "wall", "it opens at the view the address names")
        start = settle(browser)
        # The declared camera: eye (4, 0.3, 1.35) in dynrad's axes is (4, 1.35, -0.3) in
        # glTF's; looking along dynrad's +y is glTF's -z: heading 0, pitch 0.
        check(all(abs(a - b) < 1e-3 for a, b in zip(start[:3], [4, 1.35, -0.3])), "camera at %s" % start[:3])
        check(abs(start[3]) < 0.01 and abs(start[4]) < 0.01, "heading and pitch 0, got %s" % start[3:])

        # W held for a second walks forward (-z) at the model's pace: min(1.4, diagonal / 8)
        # = 1.12 m/s for the 8 x 3 x 2.7 m room (less the first frame's time).
        browser.key("w", "KeyW", 87, hold=1.0)
        walked = settle(browser)
        dz, dx, dy = walked[2] - start[2], walked[0] - start[0], walked[1] - start[1]
        check(-1.5 < dz < -0.6, "W walks forward: dz = %.3f m" % dz)
        check(abs(dx) < 1e-3 and abs(dy) < 1e-3, "and straight: dx = %.4f, dy = %.4f" % (dx, dy))

        # D walks right (+x, with the camera looking along -z); E rises.
        browser.key("d", "KeyD", 68, hold=0.5)
        right = settle(browser)
        check(right[0] - walked[0] > 0.1 and abs(right[2] - walked[2]) < 1e-3, "D steps right: dx = %.3f"
              % (right[0] - walked[0]))
        browser.key("e", "KeyE", 69, hold=0.5)
        up = settle(browser)
        check(up[1] - right[1] > 0.1, "E rises: dy = %.3f" % (up[1] - right[1]))

        # Dragging 100 pixels to the right turns by 100 pixels' share of the 60-degree
        # field of view over the canvas's height (the view is dragged like a picture, so
        # the heading turns left, positive).
        height = browser.evaluate("document.getElementById('view').clientHeight")
        browser.drag(400, 200, 500, 200)
        turned = settle(browser)
        check(abs((turned[3] - up[3]) - 100 * 60 / height) < 0.3,
              "a 100-pixel drag turns %.2f degrees: %.2f" % (100 * 60 / height, turned[3] - up[3]))
        check(all(abs(a - b) < 1e-6 for a, b in zip(turned[:3], up[:3])), "and does not move the camera")

        # The wheel steps along the view.
        browser.wheel(-100)
        stepped = settle(browser)
        moved = math.dist(stepped[:3], turned[:3])
        check(0.2 < moved < 0.4, "a wheel notch steps a quarter of the pace: %.3f m" % moved)

        # F toggles false colour, + raises the exposure, 1 and Home go to the views.
        browser.key("f", "KeyF", 70)
        check(browser.wait_for(lambda: browser.body("mode") == "false", 10), "F shows false colour")
        browser.key("f", "KeyF", 70)
        check(browser.wait_for(lambda: browser.body("mode") == "colour", 10), "F again, true colour")
        browser.key("+", "Equal", 187)
        check(browser.wait_for(lambda: browser.body("ev") == "0.5", 10), "+ raises the exposure half a stop")
        names = browser.evaluate("Array.from(document.getElementById('views').options).map(o => o.value)")
        browser.key("Home", "Home", 36)
        check(browser.wait_for(lambda: browser.body("view") == names[0], 10), "Home goes to the first view, %s"
              % names[0])
        index = names.index("wall") + 1
        browser.key(str(index), "Digit%d" % index, 48 + index)
        check(browser.wait_for(lambda: browser.body("view") == "wall", 10), "%d goes back to 'wall'" % index)
        back = settle(browser)
        check(all(abs(a - b) < 1e-3 for a, b in zip(back, start)), "exactly where it began")

        # At rest, the address holds the place; opening it again puts the camera there.
        browser.key("a", "KeyA", 65, hold=0.4)
        here = settle(browser)
        # The page rewrites the address a moment after the camera comes to rest; the hash
        # already held an earlier place, so wait for this one (under load the rewrite can
        # come after settle() returns).
        def address_camera():
            text = browser.evaluate("location.hash") or ""
            for part in text.lstrip("#").split("&"):
                if part.startswith("camera="):
                    try:
                        return [float(v) for v in part[len("camera="):].split(",")]
                    except ValueError:
                        return None
            return None

        def address_is_here():
            at = address_camera()
            return at is not None and len(at) == 5 and all(abs(a - b) < 2e-3 for a, b in zip(at[:3], here[:3]))

        check(browser.wait_for(address_is_here, 10), "the address follows the camera: %s, %s"
              % (address_camera(), here))
        address = browser.evaluate("location.href")
        check(browser.body("errors") == "0", "no script error in the walk")
        check(not browser.console_errors, "nothing in red on the console: %s" % browser.console_errors)
    finally:
        browser.close()

    again = Browser(os.path.join(work, "profile2"))
    try:
        again.open(address)
        check(again.wait_for(lambda: again.body("state") == "ready"), "the bookmarked address loads")
        there = settle(again)
        check(all(abs(a - b) < 2e-3 for a, b in zip(there[:3], here[:3])) and
              all(abs(a - b) < 0.02 for a, b in zip(there[3:], here[3:])),
              "and shows the same place: %s, %s" % (there, here))
        check(again.body("errors") == "0", "no script error")
        check(not again.console_errors, "nothing in red on the console: %s" % again.console_errors)
    finally:
        again.close()

    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
