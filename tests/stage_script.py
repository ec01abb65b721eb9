"""What the stage-running test scripts share (broken_driver.py, write_failures.py): their three arguments and a
fresh work folder.

    exe, work, stage = stage_script.setup(__doc__)   # --bin-dir DIR --stage STAGE --work DIR
"""
import argparse
import os
import shutil


def setup(description):
    """Parses --bin-dir, --stage and --work; empties the work folder. Returns (executable, work folder, stage)."""
    p = argparse.ArgumentParser(description=(description or "").split("\n\n")[0])
    p.add_argument("--bin-dir", required=True)
    p.add_argument("--stage", required=True)
    p.add_argument("--work", required=True)
    a = p.parse_args()
    exe = os.path.abspath(os.path.join(a.bin_dir, a.stage))
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    return exe, a.work, a.stage
