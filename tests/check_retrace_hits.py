#!/usr/bin/env python3
"""hits.retrace_hits_checks: retrace_hits (the tracing half of hits.02_raster_hybrid.*) is itself right.

  - 01_naive's own rays, traced again, give 01's own hits bit for bit (t to 0 ulps), on scenes with every ray kind,
    cut-outs, BLEND transparency rays, several lights and an animated frame: so any difference it reports is the
    other stage's;
  - a hit it is given is never copied through: a dump whose triangles and t were altered is traced to the real ones;
  - bad input is refused before anything is written (exit 2, one line naming the file): a missing, truncated or
    foreign --rays file, a shadow ray naming a light the scene lacks, no --dump-hits.

usage: check_retrace_hits.py --build-dir DIR
"""
import argparse
import os
import struct
import subprocess
import sys
import tempfile

RECORD = struct.Struct("<4Iif3f3f")   # common/trace/hit_record.h: 48 bytes
MAGIC = b"RTHITS\0\1"
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def read(path):
    data = open(path, "rb").read()
    return [RECORD.unpack_from(data, 8 + i * RECORD.size) for i in range((len(data) - 8) // RECORD.size)]


def write(path, records):
    with open(path, "wb") as f:
        f.write(MAGIC + b"".join(RECORD.pack(*r) for r in records))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build-dir", required=True)
    a = p.parse_args()
    naive = os.path.join(a.build_dir, "bin", "01_naive")
    retrace = os.path.join(a.build_dir, "tests", "retrace_hits")
    compare = os.path.join(a.build_dir, "tests", "compare_hits")
    with tempfile.TemporaryDirectory(prefix="retrace-") as work:
        return checks(naive, retrace, compare, work)


def checks(naive, retrace, compare, work):
    size = ["--width", "40", "--height", "30", "--quiet"]
    cases = [("whitted", ["--scene", "builtin:whitted"]), ("cutouts", ["--scene", "builtin:cutouts"]),
             ("absorption", ["--scene", "builtin:absorption"]), ("office", ["--scene", "builtin:office"]),
             ("dynamic", ["--scene", "builtin:dynamic", "--frames", "2", "--fps", "4"])]
    for name, args in cases:
        own = os.path.join(work, name + ".hits")
        again = os.path.join(work, name + ".again.hits")
        subprocess.run([naive] + args + size + ["--dump-hits", own], check=True)
        r = subprocess.run([retrace, "--rays", own.replace(".hits", "_0001.hits") if "--frames" in args else own]
                           + args + size + ["--dump-hits", again], capture_output=True, text=True)
        check(r.returncode == 0, f"{name}: retrace_hits runs ({r.stderr.strip()})")
        if "--frames" in args:
            own, again = own.replace(".hits", "_0001.hits"), again.replace(".hits", "_0001.hits")
        kinds = sorted({rec[3] & 0xff for rec in read(own)})
        c = subprocess.run([compare, own, again, "--ray-ulps", "0", "--t-ulps", "0"], capture_output=True, text=True)
        check(c.returncode == 0 and read(own) == read(again),
              f"{name}: 01's {len(read(own))} rays (kinds {kinds}) traced again: the same records, bit for bit")

    # Altered hits are not copied through: each closest-hit ray's triangle and t, and each shadow answer, replaced.
    own = os.path.join(work, "whitted.hits")
    altered = [(s, px, path, kl, (-tri if (kl & 0xff) == 1 else tri + 1), t * 2.0 + 1.0, *rest)
               for (s, px, path, kl, tri, t, *rest) in read(own)]
    bent = os.path.join(work, "bent.hits")
    write(bent, altered)
    out = os.path.join(work, "bent.again.hits")
    subprocess.run([retrace, "--rays", bent, "--scene", "builtin:whitted"] + size + ["--dump-hits", out], check=True)
    check(read(out) == read(own), "altered triangles, t and shadow answers in the input: traced to 01's own hits")

    # Bad input: exit 2, one line naming the problem, no output file.
    foreign = os.path.join(work, "foreign.hits")
    open(foreign, "wb").write(b"not a hit file at all, 48 bytes of text padding.........")
    truncated = os.path.join(work, "truncated.hits")
    open(truncated, "wb").write(open(own, "rb").read()[:-7])
    no_light = os.path.join(work, "no_light.hits")
    write(no_light, [(0, 0, 1, 1 | (7 << 8), -1, 0.0, 0, 0, 0, 0, 1, 0)])
    bad = [("a missing file", ["--rays", os.path.join(work, "missing.hits")], "missing.hits"),
           ("a foreign file", ["--rays", foreign], "foreign.hits"),
           ("a truncated file", ["--rays", truncated], "truncated.hits"),
           ("a shadow ray of light 7 in a scene of 1 light", ["--rays", no_light], "light 7")]
    for what, args, named in bad:
        out = os.path.join(work, "bad.hits")
        r = subprocess.run([retrace] + args + ["--scene", "builtin:whitted"] + size + ["--dump-hits", out],
                           capture_output=True, text=True)
        lines = r.stderr.strip().splitlines()
        check(r.returncode == 2 and len(lines) == 1 and named in lines[0] and not os.path.exists(out),
              f"{what}: exit 2, one line naming it, nothing written (exit {r.returncode}: {r.stderr.strip()})")
    r = subprocess.run([retrace, "--rays", own, "--scene", "builtin:whitted"] + size, capture_output=True, text=True)
    check(r.returncode == 2 and "--dump-hits" in r.stderr, f"no --dump-hits: exit 2 ({r.stderr.strip()})")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
