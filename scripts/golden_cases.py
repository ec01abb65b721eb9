"""scripts/golden_cases.py - tests/golden/scenes.txt as the scripts read it, the way tests/golden.cmake and
tests/run_golden.cmake (and tests/last_frame.cmake) do (scripts/grade, scripts/grade_report.py, scripts/gpu-check).
"""
import os
import re

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def golden_scenes():
    """(name, scene, extra arguments) of tests/golden/scenes.txt, @SOURCE_DIR@ replaced as tests/golden.cmake does."""
    scenes = []
    with open(os.path.join(ROOT, "tests", "golden", "scenes.txt")) as f:
        for line in f:
            fields = line.split("#", 1)[0].replace("@SOURCE_DIR@", ROOT).split()
            if fields:
                scenes.append((fields[0], fields[1], fields[2:]))
    return scenes


def golden_size():
    """(width, height) every golden frame is rendered at: RT_GOLDEN_WIDTH and RT_GOLDEN_HEIGHT of tests/golden.cmake,
    read from there so the scripts cannot drift from the tests."""
    size = {}
    with open(os.path.join(ROOT, "tests", "golden.cmake")) as f:
        for line in f:
            m = re.match(r"^set\(RT_GOLDEN_(WIDTH|HEIGHT) ([0-9]+)\)$", line.strip())
            if m:
                size[m.group(1)] = int(m.group(2))
    if set(size) != {"WIDTH", "HEIGHT"}:
        raise ValueError("tests/golden.cmake: no set(RT_GOLDEN_WIDTH N) and set(RT_GOLDEN_HEIGHT N) lines")
    return size["WIDTH"], size["HEIGHT"]


def frame_suffixes(frames):
    """What frame_path (common/app) adds to a file name for each of FRAMES frames: _0000 ... _(N-1) with --frames N
    above 1; one frame keeps the name as given ("")."""
    return [f"_{i:04d}" for i in range(frames)] if frames > 1 else [""]


def last_frame_suffix(args):
    """The suffix of the frame the golden test compares: the last of --frames N (frame_suffixes), "" without it."""
    return frame_suffixes(int(args[args.index("--frames") + 1]))[-1] if "--frames" in args else ""
