"""The add-on's interactive path: the operator invoked from a 3D view solves in a worker
thread (the interface stays live), and the cancel flag Esc sets stops the solve at the
next shot boundary, keeping the solution so far. Needs a window, so ctest runs it under
xvfb-run:
  blender --factory-startup --python tests/blender_modal_test.py -- ADDON_DIR LIBDYNRAD SAMPLES_DIR
Exit status 0 when every check holds."""

import os
import sys

import bpy

ADDON_DIR, LIBRARY, SAMPLES = sys.argv[sys.argv.index("--") + 1:]
os.environ["DYNRAD_LIBRARY"] = LIBRARY
sys.path.insert(0, ADDON_DIR)
import dynrad_blender  # noqa: E402

dynrad_blender.register()
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
bpy.ops.import_scene.obj(filepath=os.path.join(SAMPLES, "cornell_box.obj"))
for obj in bpy.data.objects:
    obj.select_set(True)
settings = bpy.context.scene.dynrad
settings.method, settings.patch_size, settings.converge = "progressive", 40.0, 1e-6  # far longer than the test
state = {"ticks": 0, "operator": None, "failures": []}


def finish(failures):
    print("blender_modal_test: %s" % ("; ".join(failures) if failures else "all checks passed"), flush=True)
    os._exit(1 if failures else 0)


def start():
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    with bpy.context.temp_override(window=window, area=area):
        outcome = bpy.ops.object.dynrad_light("INVOKE_DEFAULT")
    if outcome != {"RUNNING_MODAL"}:
        finish(["invoke returned %s, not RUNNING_MODAL" % outcome])


def watch():
    state["ticks"] += 1
    if state["ticks"] == 4:  # two seconds in: still solving, the interface still runs timers
        import gc

        def solving(operator):
            try:
                return operator._thread is not None and operator._thread.is_alive()
            except ReferenceError:  # an operator instance Blender has freed
                return False

        running = [o for o in gc.get_objects() if isinstance(o, dynrad_blender.DYNRAD_OT_light) and solving(o)]
        if len(running) != 1:
            finish(["no solve running two seconds after invoke"])
        shot, _ = running[0].progress
        if shot == 0:
            state["failures"].append("no progress reported while solving")
        running[0].cancel.value = 1  # what Esc does
    lit = [o for o in bpy.data.objects if o.name.endswith("_radiosity")]
    if lit:
        obj = lit[0]
        failures = state["failures"]
        if obj["dynrad_stopped_by"] != "cancelled":
            failures.append("stopped by %s, not cancelled" % obj["dynrad_stopped_by"])
        if not obj["dynrad_unshot_fraction"] > 1e-6:
            failures.append("unshot %g: the solve was not stopped early" % obj["dynrad_unshot_fraction"])
        if obj.data.color_attributes.get("radiosity") is None or len(obj.data.vertices) == 0:
            failures.append("the stopped solve left no lit mesh")
        finish(failures)
    if state["ticks"] > 240:
        finish(["the solve did not stop within two minutes of the cancel flag"])
    return 0.5


def guarded(function):
    def run():
        try:
            return function()
        except Exception as error:  # a failing timer would leave Blender running
            import traceback

            traceback.print_exc()
            finish(["%s: %s" % (function.__name__, error)])

    return run


bpy.app.timers.register(guarded(start), first_interval=0.5)
bpy.app.timers.register(guarded(watch), first_interval=1.0)
