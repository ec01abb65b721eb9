#!/usr/bin/python3
"""Runs every stage command of the READMEs (README.md and each <stage>/README.md: the `build/bin/<stage> ...` lines of
their sh code blocks) at 64x48, so a README's commands cannot go stale: each must exit 0 and write the files it
names, and each file it names must lie under out/, which git ignores, so that run from the repository root as the
README says it leaves `git status` clean. Run by CTest as readme.commands_render (tests/readme.cmake):

    run_readme_commands.py --root SOURCE --bin-dir BUILD/bin --work DIR
"""
import argparse
import glob
import os
import shlex
import shutil
import subprocess
import sys

OUTPUTS = ("--out", "--stats", "--heatmap", "--dump-hits", "--export")


def commands(path):
    """(line number, command text) of the stage commands in the file's sh code blocks (continuations joined)."""
    found, block, pending, start = [], False, "", 0
    with open(path) as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if line.startswith("```"):
                block = not block and line.strip() in ("```sh", "```bash")
                continue
            if not block:
                continue
            if pending:
                pending += " " + line.strip()
            elif line.startswith("build/bin/"):
                pending, start = line, number
            else:
                continue
            if pending.endswith("\\"):
                pending = pending[:-1]
                continue
            found.append((start, pending))
            pending = ""
    return found


def frame_paths(path, frames):
    if frames <= 1:
        return [path]
    stem, ext = os.path.splitext(path)
    return [f"{stem}_{i:04d}{ext}" for i in range(frames)]


def ignored_by_git(root, path):
    r = subprocess.run(["git", "-C", root, "check-ignore", "-q", path], capture_output=True)
    return r.returncode == 0 if r.returncode in (0, 1) else path.startswith("out/")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--root", required=True)
    p.add_argument("--bin-dir", required=True)
    p.add_argument("--work", required=True)
    a = p.parse_args()
    a.root, a.bin_dir, a.work = (os.path.abspath(x) for x in (a.root, a.bin_dir, a.work))
    readmes = [os.path.join(a.root, "README.md")] + sorted(glob.glob(os.path.join(a.root, "0*", "README.md")))
    failures, count = [], 0
    for readme in readmes:
        rel = os.path.relpath(readme, a.root)
        for line, text in commands(readme):
            count += 1
            where = f"{rel}:{line}"
            args = shlex.split(text, comments=True)
            exe = os.path.join(a.bin_dir, os.path.basename(args[0]))
            if not os.path.exists(exe):
                failures.append(f"{where}: {args[0]} is not built")
                continue
            rest = args[1:]
            for option, value in (("--width", "64"), ("--height", "48")):
                if option in rest:
                    rest[rest.index(option) + 1] = value
                else:
                    rest += [option, value]
            frames = int(rest[rest.index("--frames") + 1]) if "--frames" in rest else 1
            named = [(x, rest[i + 1]) for i, x in enumerate(rest[:-1]) if x in OUTPUTS]
            outputs = [path for _, path in named]
            for path in outputs:
                if os.path.isabs(path) or not ignored_by_git(a.root, path):
                    failures.append(f"{where}: {path} is not under out/ (run from the root it would leave git "
                                    f"status unclean, or overwrite a tracked file)")
            # Inputs named relative to the root (tests/data/...) are given to the command as absolute paths.
            rest = [os.path.join(a.root, x) if x not in outputs and not x.startswith("-") and
                    os.path.exists(os.path.join(a.root, x)) else x for x in rest]
            work = os.path.join(a.work, f"{count:02d}")
            shutil.rmtree(work, ignore_errors=True)
            os.makedirs(os.path.join(work, "out"))
            r = subprocess.run([exe, *rest, "--quiet"], cwd=work, capture_output=True, text=True, timeout=600)
            if r.returncode != 0:
                failures.append(f"{where}: exit {r.returncode}: {(r.stderr.strip().splitlines() or [''])[-1]}")
                continue
            # --out, --heatmap and --dump-hits write one file per frame; --stats and --export one in all.
            missing = [q for option, path in named
                       for q in (frame_paths(path, frames) if option in ("--out", "--heatmap", "--dump-hits") else [path])
                       if not os.path.exists(os.path.join(work, q))]
            if missing:
                failures.append(f"{where}: ran, but wrote no {', '.join(missing)}")
                continue
            print(f"ok   {where}: {text}")
    for f in failures:
        print(f"FAIL {f}")
    print(f"{count - len(failures)} of {count} README commands ran and wrote what they name")
    return 1 if failures or count == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
