#!/usr/bin/env python3
"""Every output of a stage, written where the disk cannot take it, fails as the developers' guide says.

For each output kind and format (--out .png .jpg .exr .hdr, --heatmap, --export .gltf .glb, --stats, --dump-hits,
--frames 2 --out), on two kinds of failing file system:
  fsize  the run's file-size limit is 512 bytes (RLIMIT_FSIZE, SIGXFSZ at its default, as after a shell's
         `ulimit -f 1`): every write past it must fail with EFBIG, as a full disk fails a write with ENOSPC, not end
         the run on the signal. Runs for any user.
  tmpfs  a 256 KiB tmpfs filled to the last byte: a real full disk (ENOSPC). Needs root (mount); without it this part
         says why it is skipped, and the fsize part still runs.
each run must exit 1 with exactly one line, "<stage>: error: cannot write <option> <file>: <cause>", the cause being
"file too large" or "no space left on device"; the file that was there before must be untouched; and nothing else may
be left in the folder (no temporary).

usage: write_failures.py --bin-dir DIR --stage STAGE --work DIR
"""
import os
import resource
import signal
import subprocess
import sys

import stage_script

CASES = [
    (["--out", "o.png"], "o.png"),
    (["--out", "o.jpg"], "o.jpg"),
    (["--out", "o.exr"], "o.exr"),
    (["--out", "o.hdr"], "o.hdr"),
    (["--heatmap", "h.png"], "h.png"),
    (["--export", "x.gltf"], "x.gltf"),
    (["--export", "x.glb"], "x.glb"),
    (["--stats", "s.json"], "s.json"),
    (["--dump-hits", "d.hits"], "d.hits"),
    (["--frames", "2", "--out", "f.png"], "f_0000.png"),
]
PREVIOUS = b"the user's previous file\n"
CAUSE = {"fsize": "file too large", "tmpfs": "no space left on device"}


def limit_file_size():
    # As a user's shell runs it after `ulimit -f`: SIGXFSZ at its default (it would end the run); the stage must
    # turn a write past the limit into its one-line error itself.
    signal.signal(signal.SIGXFSZ, signal.SIG_DFL)
    resource.setrlimit(resource.RLIMIT_FSIZE, (512, 512))


def fill(folder):
    """Fills the file system of `folder` to the last byte."""
    with open(os.path.join(folder, "fill"), "wb", buffering=0) as f:
        chunk = b"\0" * 4096
        try:
            while True:
                f.write(chunk)
        except OSError:
            pass
        try:
            while True:
                f.write(b"\0")
        except OSError:
            pass


def check(stage, exe, folder, mode, args, target):
    name = f"{mode} {' '.join(args)}"
    before = set(os.listdir(folder))
    cmd = [exe, "--scene", "builtin:whitted", "--width", "64", "--height", "48", "--quiet"] + args
    r = subprocess.run(cmd, cwd=folder, capture_output=True, text=True, timeout=300,
                       preexec_fn=limit_file_size if mode == "fsize" else None)
    problems = []
    if r.returncode != 1:
        problems.append(f"exit {r.returncode}, expected 1")
    lines = r.stderr.splitlines()
    option = args[-2]
    want = f"{stage}: error: cannot write {option} "
    if len(lines) != 1 or not lines[0].startswith(want) or not lines[0].endswith(": " + CAUSE[mode]):
        problems.append(f"stderr is not one line '{want}FILE: {CAUSE[mode]}': {r.stderr!r}")
    with open(os.path.join(folder, target), "rb") as f:
        if f.read() != PREVIOUS:
            problems.append(f"{target}, there before the run, was changed")
    left = set(os.listdir(folder)) - before
    if left:
        problems.append(f"left behind: {sorted(left)}")
    print(("FAIL " if problems else "ok   ") + name + (": " + "; ".join(problems) if problems else ""))
    return not problems


def run_all(stage, exe, folder, mode):
    ok = True
    for args, target in CASES:
        with open(os.path.join(folder, target), "wb") as f:
            f.write(PREVIOUS)
    if mode == "tmpfs":
        fill(folder)
    for args, target in CASES:
        ok &= check(stage, exe, folder, mode, args, target)
    return ok


def main():
    exe, work, stage = stage_script.setup(__doc__)

    ok = True
    folder = os.path.join(work, "fsize")
    os.makedirs(folder)
    ok &= run_all(stage, exe, folder, "fsize")

    folder = os.path.join(work, "tmpfs")
    os.makedirs(folder)
    if os.geteuid() != 0:
        print("skipped tmpfs: not root (mounting a small tmpfs needs root; the fsize cases above ran)")
    else:
        m = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", folder], capture_output=True, text=True)
        if m.returncode != 0:
            print(f"skipped tmpfs: mount failed ({m.stderr.strip()}); the fsize cases above ran")
        else:
            try:
                ok &= run_all(stage, exe, folder, "tmpfs")
            finally:
                subprocess.run(["umount", folder])
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
