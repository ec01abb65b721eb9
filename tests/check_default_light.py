#!/usr/bin/env python3
"""A default-lit interior must give a readable image (docs/shading.md, "Defaults"): rendered by a stage with its
default options, under 5% of its pixels clip (a channel at 255) and its median luminance (Rec. 709, of the 8-bit
sRGB values) lies between 10% and 90% of the range, away from both ends.

usage: check_default_light.py --stage EXE --scene FILE.gltf|hall --work DIR [--width W --height H]
  hall: the large interior tests/data/make_interior_scene.py writes (about 65,000 triangles, camera inside).
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--stage", required=True)
    p.add_argument("--scene", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--width", type=int, default=160)
    p.add_argument("--height", type=int, default=120)
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    scene = a.scene
    if scene == "hall":
        scene = os.path.join(a.work, "hall.gltf")
        subprocess.run([sys.executable, os.path.join(HERE, "data", "make_interior_scene.py"), scene], check=True,
                       stdout=subprocess.DEVNULL)
    out, stats = os.path.join(a.work, "image.png"), os.path.join(a.work, "stats.json")
    subprocess.run([a.stage, "--scene", scene, "--width", str(a.width), "--height", str(a.height), "--out", out,
                    "--stats", stats, "--quiet"], check=True)
    with open(stats) as f:
        s = json.load(f)
    if not (s["defaults"]["light"] and s["defaults"]["headlight"]):
        sys.exit(f"{scene}: not lit by the default headlight: {s['defaults']}")
    pixels = oiio.ImageBuf(out).get_pixels(oiio.UINT8)[:, :, :3].astype(np.float64)
    clipped = float((pixels >= 255).any(axis=2).mean())
    luminance = pixels @ np.array([0.2126, 0.7152, 0.0722])
    median = float(np.median(luminance)) / 255.0
    print(f"{os.path.basename(scene)} in {os.path.basename(a.stage)}: {100 * clipped:.1f}% of pixels clipped, median "
          f"luminance {100 * median:.0f}% of the range, saved at EV {s.get('exposure', {}).get('ev', 0):.2f}")
    if clipped >= 0.05:
        sys.exit(f"{scene}: {100 * clipped:.1f}% of the pixels clip (at most 5%)")
    if not 0.1 <= median <= 0.9:
        sys.exit(f"{scene}: the median luminance is {100 * median:.0f}% of the range (10% to 90%)")


if __name__ == "__main__":
    main()
