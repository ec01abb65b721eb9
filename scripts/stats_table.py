#!/usr/bin/env python3
"""Prints one table from the stats JSON files the stages write (scripts/demo)."""
import json
import sys


def main(paths):
    rows = []
    for path in paths:
        with open(path) as f:
            s = json.load(f)
        rays = s["traced_rays"]   # rasterized primary rays are not traced
        rows.append((s["stage"], s["scene"], f'{s["width"]}x{s["height"]}', f'{s["time_ms"]["total"]:.1f}',
                     f"{rays:,}", f'{s["mrays_per_s"]:.2f}', f'{s["intersection_tests"] / max(rays, 1):.1f}',
                     s["renderer"]))
    header = ("stage", "scene", "size", "time ms", "rays traced", "Mrays/s", "tests/ray", "renderer")
    widths = [max(len(str(r[i])) for r in rows + [header]) for i in range(len(header))]
    line = "  ".join(f"{{:{'<' if i in (0, 1, 7) else '>'}{w}}}" for i, w in enumerate(widths))
    print(line.format(*header))
    print("  ".join("-" * w for w in widths))
    for r in rows:
        print(line.format(*r))


if __name__ == "__main__":
    main(sys.argv[1:])
