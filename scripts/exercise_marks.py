"""The course's exercise marks and its exercise table, read the same way by scripts/exercise and scripts/grade.

A block in a C++ or GLSL source reads

    // BEGIN EXERCISE 03.dda_cell_end: what to write (the hint; it may go on over the comment lines that follow)
    ... the solution ...
    // STUB: w.axis = 0;           <- code that compiles and does something harmless (a stub line per line)
    // END EXERCISE

An exercise may have several blocks (its CPU and GLSL twins carry the same name). tests/exercises.txt maps each
exercise to the CTest tests that grade it.
"""
import fnmatch
import os
import re
import subprocess

BEGIN = re.compile(r"^(\s*)//\s*BEGIN EXERCISE\s+(\d\d)\.([A-Za-z0-9_]+):\s*(.*)$")
STUB = re.compile(r"^(\s*)//\s*STUB:\s?(.*)$")
END = re.compile(r"^\s*//\s*END EXERCISE\s*$")
# In a student copy: the hint line, the line that marks the student's part, and its end.
COPY_HINT = re.compile(r"^\s*//\s*EXERCISE\s+(\d\d)\.([A-Za-z0-9_]+):\s*(.*)$")
TODO = "// TODO: your code here; the stub below only compiles (exercise {name})."
SOURCE_SUFFIXES = (".h", ".cpp", ".glsl", ".comp", ".vert", ".frag")
MANIFEST = ".exercises"   # written into a student copy by scripts/exercise: the stubs, to tell "not attempted"


def stages(root):
    """The stage list of tests/stages.txt, in order."""
    names = []
    with open(os.path.join(root, "tests", "stages.txt")) as f:
        for line in f:
            fields = line.split("#", 1)[0].split()
            if fields:
                names.append(fields[0])
    return names


def stage_of(exercise, stage_names):
    """The stage whose number starts the exercise's name (03.* -> 03_uniform_grid), or None."""
    for s in stage_names:
        if s[:2] == exercise[:2]:
            return s
    return None


def tracked_files(root):
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], check=True, capture_output=True).stdout
        return [p for p in out.decode().split("\0") if p and os.path.isfile(os.path.join(root, p))]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for folder, subfolders, names in os.walk(root):
            subfolders[:] = [d for d in subfolders if not d.startswith("build") and d != ".git" and d != "out"]
            files += [os.path.relpath(os.path.join(folder, n), root) for n in names]
        return files


def source_files(root):
    return sorted(p for p in tracked_files(root) if p.endswith(SOURCE_SUFFIXES) and not p.startswith("scripts/"))


def blocks_of(text):
    """Each marked block of a source text: dict(name, hint, solution (lines), stubs (lines), line (1-based))."""
    blocks, lines, i = [], text.splitlines(), 0
    while i < len(lines):
        m = BEGIN.match(lines[i])
        if not m:
            i += 1
            continue
        block = {"name": f"{m.group(2)}.{m.group(3)}", "line": i + 1, "solution": [], "stubs": []}
        hint = [m.group(4).strip()]
        i += 1
        while i < len(lines) and lines[i].lstrip().startswith("//") and not STUB.match(lines[i]) \
                and not END.match(lines[i]):
            hint.append(lines[i].strip().lstrip("/").strip())
            i += 1
        while i < len(lines) and not END.match(lines[i]):
            s = STUB.match(lines[i])
            if s:
                block["stubs"].append(s.group(1) + s.group(2))
            else:
                block["solution"].append(lines[i])
            i += 1
        block["hint"] = " ".join(h for h in hint if h)
        block["closed"] = i < len(lines)
        blocks.append(block)
        i += 1
    return blocks


def copy_hints(text):
    """(name, hint, line) of each exercise in a student copy's source ("// EXERCISE NN.name: ...")."""
    found, lines = [], text.splitlines()
    for i, line in enumerate(lines):
        m = COPY_HINT.match(line)
        if m:
            hint = [m.group(3).strip()]
            for follow in lines[i + 1:]:
                if not follow.lstrip().startswith("//") or "TODO: your code here" in follow:
                    break
                hint.append(follow.strip().lstrip("/").strip())
            found.append((f"{m.group(1)}.{m.group(2)}", " ".join(h for h in hint if h), i + 1))
    return found


def read_table(root):
    """tests/exercises.txt: {exercise: [pattern, ...]} in the file's order."""
    table = {}
    path = os.path.join(root, "tests", "exercises.txt")
    with open(path) as f:
        for number, line in enumerate(f, 1):
            fields = line.split("#", 1)[0].split()
            if not fields:
                continue
            if len(fields) != 2 or not re.fullmatch(r"\d\d\.[A-Za-z0-9_]+", fields[0]):
                raise ValueError(f"{path}:{number}: expected '<NN.exercise> <test pattern>'")
            table.setdefault(fields[0], []).append(fields[1])
    return table


def matching(pattern, names):
    """The names a table pattern (a shell glob on CTest names) matches."""
    return [n for n in names if fnmatch.fnmatchcase(n, pattern)]
