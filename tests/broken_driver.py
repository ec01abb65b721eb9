#!/usr/bin/env python3
"""A GL context that cannot start is one error line and exit 1 on every backend, with nothing left behind.

Cases, for one GPU stage: GALLIUM_DRIVER=bogus (Mesa then crashes inside OSMesaCreateContextAttribs: the stage
probes it in a child process) with --backend auto, egl and osmesa; a missing libOSMesa (RT_OSMESA_LIBRARY names a
file that does not exist) with --backend osmesa; a missing libEGL (RT_EGL_LIBRARY likewise) with --backend egl; and
both missing with --backend auto. Each run must exit 1 with exactly one line "<stage>: error: ...", leave the file
that was at --out untouched and leave no temporary.

Two checks that a missing library cannot stop the stage before main: neither libEGL nor libOSMesa (nor libGL or
libOpenGL) is among the libraries loaded at start (ldd's closure), since the dynamic loader refuses to start a program
one of whose libraries is missing (exit 127, with its own message); and with libEGL missing, --backend auto
renders through OSMesa (exit 0, a PNG written).

usage: broken_driver.py --bin-dir DIR --stage STAGE --work DIR
"""
import os
import re
import subprocess
import sys

import stage_script

PREVIOUS = b"the user's previous image\n"


def main():
    exe, work, stage = stage_script.setup(__doc__)
    cases = [(f"GALLIUM_DRIVER=bogus --backend {b}", {"GALLIUM_DRIVER": "bogus"}, b) for b in ("auto", "egl", "osmesa")]
    no_osmesa = {"RT_OSMESA_LIBRARY": "/nonexistent/libOSMesa.so.8"}
    no_egl = {"RT_EGL_LIBRARY": "/nonexistent/libEGL.so.1"}
    cases.append(("missing libOSMesa --backend osmesa", no_osmesa, "osmesa"))
    cases.append(("missing libEGL --backend egl", no_egl, "egl"))
    cases.append(("missing libEGL and libOSMesa --backend auto", dict(no_egl, **no_osmesa), "auto"))
    failed = 0

    closure = subprocess.run(["ldd", exe], capture_output=True, text=True, check=True).stdout
    # (libGLX and libGLdispatch may be there: Debian's OpenCV, under OpenImageIO, links them. Not ours to drop.)
    gl_family = sorted(set(re.findall(r"^\s*(lib(?:EGL|GL|OpenGL|OSMesa)\.\S*)", closure, re.M)))
    print(("FAIL " if gl_family else "ok   ") + "libraries loaded at start (ldd): " +
          (f"{gl_family}: a missing one stops the stage before main" if gl_family else "no libEGL, libOSMesa, libGL or libOpenGL"))
    failed += bool(gl_family)

    target = os.path.join(work, "o.png")
    r = subprocess.run([exe, "--scene", "builtin:whitted", "--width", "16", "--height", "12", "--out", "o.png",
                        "--quiet"], cwd=work, env=dict(os.environ, **no_egl), capture_output=True, text=True,
                       timeout=120)
    is_png = False
    if os.path.exists(target):
        with open(target, "rb") as f:
            is_png = f.read(8) == b"\x89PNG\r\n\x1a\n"
    problem = (f"exit {r.returncode}: {r.stderr.strip()!r}" if r.returncode != 0 else
               "" if is_png else "o.png is not a PNG")
    print(("FAIL " if problem else "ok   ") + "missing libEGL --backend auto renders through OSMesa" +
          (": " + problem if problem else ""))
    failed += bool(problem)
    if os.path.exists(target):
        os.remove(target)

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
