#!/usr/bin/env python3
"""Runs a command and prefixes every line it prints (stdout and stderr) with the seconds
since it started and the resident memory of it and its children (MiB, sampled every
0.2 s); the last line gives the sampled peak. For profiles of long runs by phase:

    scripts/phases.py build/plugin/dynrad solve office1.json -o office1.ply
"""
import subprocess
import sys
import threading
import time


def resident_mib(pid):
    """Resident memory of pid and its children, MiB (0 when it has gone)."""
    total = 0.0
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    total += int(line.split()[1]) / 1024
        with open(f"/proc/{pid}/task/{pid}/children") as children:
            for child in children.read().split():
                total += resident_mib(int(child))
    except OSError:
        pass
    return total


def main():
    if len(sys.argv) < 2:
        sys.exit("usage: phases.py COMMAND [ARGUMENTS...]")
    start = time.time()
    process = subprocess.Popen(sys.argv[1:], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1)
    now = [0.0]
    peak = [0.0]

    def sample():
        while process.poll() is None:
            now[0] = resident_mib(process.pid)
            peak[0] = max(peak[0], now[0])
            time.sleep(0.2)

    threading.Thread(target=sample, daemon=True).start()
    for line in process.stdout:
        sys.stdout.write(f"[{time.time() - start:8.1f} s {now[0]:7.0f} MiB] {line}")
        sys.stdout.flush()
    process.wait()
    print(f"[{time.time() - start:8.1f} s] exit {process.returncode}, peak {peak[0]:.0f} MiB (sampled)")
    sys.exit(process.returncode)


if __name__ == "__main__":
    main()
