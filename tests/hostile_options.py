#!/usr/bin/env python3
"""Every option of a stage, fed hostile values, either runs or is refused in one line.

The options come from the stage's own --help (CLI11 prints every option it registered, with its type and bounds),
so an option added later is tested without editing this file. With --own-only, options that 01_naive also has are
left out: they are parsed by the same shared code (common/app/options.cpp) and tested once, on 01_naive.

Every option that takes a value gets "", " ", "nan", "1e400", "-0", "0x10", "4.0" and " 4"; a numeric option also gets
its bounds from --help: the lower bound (allowed), one below it and one above the upper bound (refused; the upper
bound itself is not rendered: at --frames 10000 or --spp 4096 that is a long run, not a parsing check). Each run must:
  - exit 0 or 2, never another status or a signal (a crash), within 120 s;
  - on exit 2, print exactly one line "<stage>: error: ..." that names the option;
  - refuse "", " ", " 4", "nan", "1e400" and "0x10" for a numeric option, "4.0" for an integer one, and the values
    outside the bounds, giving a reason (not CLI11's bare "Could not convert");
  - leave no temporary behind.

usage: hostile_options.py --bin-dir DIR --stage STAGE --work DIR [--own-only]
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

HOSTILE = ["", " ", "nan", "1e400", "-0", "0x10", "4.0", " 4"]
REFUSED_IF_NUMERIC = {"", " ", " 4", "nan", "1e400", "0x10"}
BASE = {"--scene": "builtin:diffuse", "--width": "8", "--height": "6", "--out": "o.png"}
# "  --name[,--alias] TYPE..." (a flag has no TYPE, or "{false}" glued to its name).
OPTION = re.compile(r"^\s{2}(?:-\w,)?(--[\w-]+)(\S*)\s*(.*)$")


def options_of(exe):
    text = subprocess.run([exe, "--help"], capture_output=True, text=True, check=True).stdout
    found = {}
    for line in text.splitlines():
        m = OPTION.match(line)
        if not m or m.group(1) in ("--help", "--version") or m.group(2):
            continue   # not an option line, or a flag with a negation ("--gl-debug,--no-gl-debug{false}")
        rest = m.group(3)
        kind = re.split(r"[:= ]", rest, maxsplit=1)[0] if rest[:1].isupper() else ""
        if kind not in ("TEXT", "INT", "UINT", "FLOAT", "DOUBLE"):
            continue   # a flag (its help text follows on the same line or the next)
        bounds = None
        b = re.search(r"at least (-?[\d.e+]+) and at most (-?[\d.e+]+)", rest) or \
            re.search(r"above (-?[\d.e+]+) and at most (-?[\d.e+]+)", rest) or \
            re.search(r"in \[(-?[\d.e+]+) - (-?[\d.e+]+)\]", rest)
        if b:
            bounds = (float(b.group(1)), float(b.group(2)), "above" in b.group(0))
        found[m.group(1)] = {"kind": kind, "bounds": bounds, "integer": kind in ("INT", "UINT"),
                             "numeric": kind != "TEXT"}
    return found


def number(v, integer):
    return str(int(v)) if integer else repr(v)


def cases_for(name, o):
    values = [(v, "refused" if o["numeric"] and v in REFUSED_IF_NUMERIC or (o["integer"] and v == "4.0") else "any")
              for v in HOSTILE]
    if o["bounds"]:
        lo, hi, exclusive = o["bounds"]
        step = 1 if o["integer"] else max(abs(lo), 1.0) * 0.5
        if not exclusive:
            values.append((number(lo, o["integer"]), "any"))   # allowed (may still be refused by what it means)
        values.append((number(lo - step if not exclusive else lo, o["integer"]), "refused"))
        values.append((number(hi + (1 if o["integer"] else max(abs(hi), 1.0)), o["integer"]), "refused"))
    return values


def run_case(stage, exe, folder, name, value, expect):
    args = [exe, "--quiet"]
    for k, v in BASE.items():
        if k != name:
            args += [k, v]
    args += [name, value]
    before = set(os.listdir(folder))
    try:
        r = subprocess.run(args, cwd=folder, capture_output=True, text=True, timeout=120)
    except subprocess.TimeoutExpired:
        return f"{name} {value!r}: still running after 120 s"
    problems = []
    if r.returncode not in (0, 2):
        problems.append(f"exit {r.returncode}" + (" (killed by a signal)" if r.returncode < 0 else ""))
    if expect == "refused" and r.returncode != 2:
        problems.append(f"accepted (exit {r.returncode}), expected a refusal")
    if r.returncode == 2:
        lines = r.stderr.splitlines()
        if len(lines) != 1 or not lines[0].startswith(f"{stage}: error: "):
            problems.append(f"not one '{stage}: error:' line: {r.stderr!r}")
        elif name not in lines[0] and not (name == "--scene" or name == "--out"):
            problems.append(f"the error does not name {name}: {lines[0]!r}")
        elif "Could not convert" in lines[0]:
            problems.append(f"no reason given: {lines[0]!r}")
    left = {f for f in set(os.listdir(folder)) - before if ".tmp" in f}
    if left:
        problems.append(f"left behind: {sorted(left)}")
    for f in set(os.listdir(folder)) - before:
        path = os.path.join(folder, f)
        (shutil.rmtree if os.path.isdir(path) else os.remove)(path)
    return f"{name} {value!r}: " + "; ".join(problems) if problems else None


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--bin-dir", required=True)
    p.add_argument("--stage", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--own-only", action="store_true")
    a = p.parse_args()
    exe = os.path.abspath(os.path.join(a.bin_dir, a.stage))
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    options = options_of(exe)
    if a.own_only:
        shared = options_of(os.path.abspath(os.path.join(a.bin_dir, "01_naive")))
        options = {k: v for k, v in options.items() if k not in shared}
    if not options:
        print(f"{a.stage}: no options found in --help")
        return 1
    failures, runs = [], 0
    for name, o in sorted(options.items()):
        for value, expect in cases_for(name, o):
            runs += 1
            problem = run_case(a.stage, exe, a.work, name, value, expect)
            if problem:
                failures.append(problem)
                print("FAIL " + problem)
    print(f"{a.stage}: {len(options)} options ({', '.join(sorted(options))}), {runs} runs, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
