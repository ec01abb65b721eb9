"""scripts/golden_cases.py - tests/golden/scenes.txt as the scripts read it, the way tests/golden.cmake and
tests/run_golden.cmake do (scripts/grade, scripts/grade_report.py, scripts/gpu-check).
"""
import os

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


def last_frame_suffix(args):
    """What frame_path adds to a file name for the frame the golden test compares: with --frames N the stage writes
    <name>_0000 ... <name>_(N-1) and the last one is compared; one frame keeps the name as given."""
    return f"_{int(args[args.index('--frames') + 1]) - 1:04d}" if "--frames" in args else ""
