#!/usr/bin/env python3
"""A GL context that cannot start is one error line and exit 1 on every backend, with nothing left behind.

Cases, for one GPU stage: GALLIUM_DRIVER=bogus (Mesa then crashes inside OSMesaCreateContextAttribs: the stage
probes it in a child process) with --backend auto, egl and osmesa; and a missing libOSMesa (RT_OSMESA_LIBRARY names a
file that does not exist) with --backend osmesa. Each run must exit 1 with exactly one line "<stage>: error: ...",
leave the file that was at --out untouched and leave no temporary.

usage: broken_driver.py --bin-dir DIR --stage STAGE --work DIR
"""
import os
import subprocess
import sys

import stage_script

PREVIOUS = b"the user's previous image\n"


def main():
    exe, work, stage = stage_script.setup(__doc__)
    cases = [(f"GALLIUM_DRIVER=bogus --backend {b}", {"GALLIUM_DRIVER": "bogus"}, b) for b in ("auto", "egl", "osmesa")]
    cases.append(("missing libOSMesa --backend osmesa", {"RT_OSMESA_LIBRARY": "/nonexistent/libOSMesa.so.8"}, "osmesa"))
    failed = 0
    for name, env, backend in cases:
        target = os.path.join(work, "o.png")
        with open(target, "wb") as f:
            f.write(PREVIOUS)
        r = subprocess.run([exe, "--scene", "builtin:whitted", "--width", "16", "--height", "12", "--backend", backend,
                            "--out", "o.png", "--quiet"], cwd=work, env=dict(os.environ, **env),
                           capture_output=True, text=True, timeout=120)
        problems = []
        if r.returncode != 1:
            problems.append(f"exit {r.returncode}, expected 1")
        lines = r.stderr.splitlines()
        if len(lines) != 1 or not lines[0].startswith(f"{stage}: error: "):
            problems.append(f"not one error line: {r.stderr!r}")
        with open(target, "rb") as f:
            if f.read() != PREVIOUS:
                problems.append("o.png was changed")
        left = sorted(set(os.listdir(work)) - {"o.png"})
        if left:
            problems.append(f"left behind: {left}")
        print(("FAIL " if problems else "ok   ") + name + (": " + "; ".join(problems) if problems else ": " + lines[0]))
        failed += bool(problems)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
