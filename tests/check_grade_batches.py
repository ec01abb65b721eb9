#!/usr/bin/env python3
"""grading.unit_tests_batched_like_ctest: scripts/grade runs the GoogleTest cases it grades one process per test
binary (not one per case, as CTest does); that must give every case the verdict CTest gives it.

  - 25 cases of unit_tests_common_scene, run batched and one by one through CTest: the same verdicts (all pass);
  - a stand-in test binary (a script that answers --gtest_filter and --gtest_output as GoogleTest does) with a
    passing, a failing and a skipped case: only the passing one passes, the failure reads "file:line: Failure" and
    its assertion (what the report shows), the skip is not a pass;
  - the same stand-in crashing (SIGSEGV) or writing no report: none of its cases passes; they go back to CTest one
    by one: a real case of unit_tests_common_scene put in the stand-in's batch passes there, the stand-in's own cases
    (which CTest does not know) "did not run";
  - a ^C while CTest runs the other tests (the binaries run beside it): it reaches the caller, and the stand-in,
    started and still running, is stopped (no test process outlives the grading).

usage: check_grade_batches.py --build-dir DIR
"""
import argparse
import importlib.machinery
import importlib.util
import os
import signal
import stat
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

FAKE_GTEST = r'''#!/usr/bin/env python3
import os, signal, sys, time
args = dict(a.split("=", 1) for a in sys.argv[1:] if "=" in a)
cases = args["--gtest_filter"].split(":")
if os.environ.get("FAKE_MODE") == "hang":   # says it runs (its pid), then runs on
    pid_file = os.environ["FAKE_PID_FILE"]
    open(pid_file + ".tmp", "w").write(str(os.getpid()))
    os.rename(pid_file + ".tmp", pid_file)
    time.sleep(600)
if os.environ.get("FAKE_MODE") == "crash":
    os.kill(os.getpid(), signal.SIGSEGV)
if os.environ.get("FAKE_MODE") == "no-report":
    sys.exit(0)
out = ['<?xml version="1.0" encoding="UTF-8"?>', '<testsuites>']
for c in cases:
    suite, name = c.split(".", 1)
    result = "skipped" if name == "Skip" else "completed"
    out.append(f'<testsuite name="{suite}">'
               f'<testcase name="{name}" status="run" result="{result}" classname="{suite}">')
    if name == "Fail":
        out.append('<failure message="src/thing_test.cpp:12&#x0A;Expected equality of these values:&#x0A;  a'
                   '&#x0A;    Which is: 1" type=""/>')
    if name == "Skip":
        out.append('<skipped message=""/>')
    out.append('</testcase></testsuite>')
out.append('</testsuites>')
open(args["--gtest_output"][len("xml:"):], "w").write("\n".join(out))
sys.exit(1 if any(c.endswith(".Fail") for c in cases) else 0)
'''


def load_grade():
    path = os.path.join(ROOT, "scripts", "grade")
    loader = importlib.machinery.SourceFileLoader("grade", path)
    spec = importlib.util.spec_from_loader("grade", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build-dir", required=True)
    build = p.parse_args().build_dir
    grade = load_grade()
    problems = []
    work = tempfile.mkdtemp(prefix="grade-batches-")
    junit = os.path.join(work, "ctest.junit.xml")

    listing = grade.ctest_listing(build)
    scene = sorted(n for n, t in listing.items()
                   if (grade.gtest_case(t) or ("",))[0].endswith("/unit_tests_common_scene"))[:25]
    if len(scene) < 25:
        problems.append(f"only {len(scene)} cases of unit_tests_common_scene are registered")
    batched = grade.run_ctest(build, scene, junit)
    alone = grade.ctest_run(build, scene, junit, False)
    differ = [n for n in scene if batched.get(n, (None,))[0] != alone.get(n, (None,))[0]]
    if differ or not all(ok for ok, _ in batched.values()):
        problems.append(f"batched and one-by-one verdicts differ on {differ[:3]} (or a case failed)")

    fake = os.path.join(work, "fake_gtest")
    with open(fake, "w") as f:
        f.write(FAKE_GTEST)
    os.chmod(fake, os.stat(fake).st_mode | stat.S_IXUSR)
    names = {"Pass": "Fake.Pass", "Fail": "Fake.Fail  # GetParam() = 1", "Skip": "Fake.Skip"}
    fake_listing = {name: {"name": name, "command": [fake, f"--gtest_filter=Fake.{case}"],
                           "properties": [{"name": "WORKING_DIRECTORY", "value": work},
                                          {"name": "LABELS", "value": ["unit"]}]}
                    for case, name in names.items()}
    results = grade.run_ctest(build, list(fake_listing), junit, listing=fake_listing)
    if results.get(names["Pass"], (False,))[0] is not True:
        problems.append(f"the passing case is not passed: {results.get(names['Pass'])}")
    failed = results.get(names["Fail"], (True, ""))
    if failed[0] or grade.first_message(failed[1]) != ("src/thing_test.cpp:12: Failure\nExpected equality of these "
                                                        "values:\na\nWhich is: 1"):
        problems.append(f"the failing case reads {failed!r}, first message {grade.first_message(failed[1])!r}")
    if results.get(names["Skip"], (True,))[0]:
        problems.append("a skipped case passed")
    real = scene[0]
    in_batch = dict(fake_listing)
    in_batch[real] = dict(fake_listing[names["Pass"]], name=real,
                          command=[fake, "--gtest_filter=" + grade.gtest_case(listing[real])[2]])
    for mode in ("crash", "no-report"):
        os.environ["FAKE_MODE"] = mode
        results = grade.run_ctest(build, list(in_batch), junit, listing=in_batch)
        passed = [n for n in fake_listing if results.get(n, (True,))[0]]
        if passed or set(results) != set(in_batch):
            problems.append(f"{mode}: {passed or 'not every case'} passed or has no verdict: {results}")
        if not results.get(real, (False,))[0]:
            problems.append(f"{mode}: {real}, batched with the stand-in, was not run again by CTest: {results[real]}")

    # ^C while CTest's part runs: the stand-in (started beside it, hanging) must not outlive the grading.
    os.environ["FAKE_MODE"] = "hang"
    pid_file = os.environ["FAKE_PID_FILE"] = os.path.join(work, "fake.pid")
    ctest_run = grade.ctest_run

    def interrupted(*args, **kwargs):
        for _ in range(200):   # until the stand-in runs (at most 20 s)
            if os.path.exists(pid_file):
                break
            time.sleep(0.1)
        raise KeyboardInterrupt

    grade.ctest_run = interrupted
    try:
        grade.run_ctest(build, list(fake_listing), junit, listing=fake_listing)
        problems.append("^C during CTest's part: run_ctest returned instead of passing it on")
    except KeyboardInterrupt:
        pass
    finally:
        grade.ctest_run = ctest_run
    if not os.path.exists(pid_file):
        problems.append("^C during CTest's part: the stand-in never started")
    else:
        pid = int(open(pid_file).read())
        try:
            os.kill(pid, 0)
            problems.append(f"^C during CTest's part: the stand-in (pid {pid}) is still running")
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    del os.environ["FAKE_MODE"]

    for problem in problems:
        print("FAIL " + problem)
    print(f"grade batches: {len(scene)} cases of unit_tests_common_scene batched like CTest; a fake binary's pass, "
          f"failure, skip, crash, missing report and a ^C beside it: {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
