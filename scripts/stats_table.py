#!/usr/bin/python3
"""Prints one table from the stats JSON files the stages write (scripts/demo), with a line per column saying what it
counts.

    scripts/stats_table.py out/01_naive.json out/02_raster_hybrid.json ...

Primary rays are one per pixel and sample in every stage; 01 traces them, 02-05 rasterize them into a G-buffer (03's
--primary trace traces them), so "rays traced" is every ray but the rasterized ones (the stats' traced_rays). Mrays/s
is those traced rays per second of time_ms.trace; where nothing was traced it is "-", never 0.00.
"""
import argparse
import json
import sys

HEADER = ("stage", "scene", "size", "frame ms", "primary rays", "primaries rasterized", "rays traced", "trace ms",
          "traced Mrays/s", "tests/ray", "renderer")
LEFT = {"stage", "scene", "renderer"}
LEGEND = """\
frame ms: the frame's wall clock (time_ms.total).  primary rays: one per pixel and sample, however found.
primaries rasterized: those found by the G-buffer instead of traced.  rays traced: every other ray (traced
primaries, shadow, reflection, refraction, transparency).  trace ms: time_ms.trace (01: tracing and shading; GPU stages: the
traversal passes).  traced Mrays/s: rays traced / trace ms ("-" where no ray was traced; 2 significant digits
below 1).  tests/ray: the frame's ray/triangle tests (the G-buffer's included) per ray, rasterized primaries too."""


def all_rays(stats):
    r = stats["rays"]
    return r["primary"] + r["shadow"] + r["reflection"] + r["refraction"] + r.get("transparency", 0)


def tests_per_ray(stats):
    """Every ray/triangle test of the frame per ray of the frame (rasterized primaries included), or None."""
    rays = all_rays(stats)
    return stats["intersection_tests"] / rays if rays else None


def mrays(stats):
    """Traced rays per microsecond of time_ms.trace, or None where no ray was traced (or no trace time measured)."""
    traced, ms = stats["traced_rays"], stats["time_ms"]["trace"]
    return traced / (ms * 1e3) if traced and ms > 0 else None


def rate_text(rate):
    """Mrays/s with the digits it needs: 2 decimals from 1 up, 2 significant digits below (0.0039, never 0.00)."""
    if rate is None:
        return "-"
    return f"{rate:.2f}" if rate >= 1 else f"{rate:.2g}"


def row(stats):
    rate, tpr = mrays(stats), tests_per_ray(stats)
    return (stats["stage"], stats["scene"], f'{stats["width"]}x{stats["height"]}', f'{stats["time_ms"]["total"]:.1f}',
            f'{stats["rays"]["primary"]:,}', f'{stats["rays"]["rasterized"]:,}', f'{stats["traced_rays"]:,}',
            f'{stats["time_ms"]["trace"]:.1f}', rate_text(rate),
            "-" if tpr is None else f"{tpr:.1f}", stats["renderer"])


def table(rows):
    widths = [max(len(str(r[i])) for r in rows + [HEADER]) for i in range(len(HEADER))]
    line = "  ".join(f"{{:{'<' if HEADER[i] in LEFT else '>'}{w}}}" for i, w in enumerate(widths))
    out = [line.format(*HEADER), "  ".join("-" * w for w in widths)]
    out += [line.format(*r) for r in rows]
    return "\n".join(out)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("stats", nargs="+", help="stats JSON files (--stats of a stage)")
    args = p.parse_args()
    rows = []
    for path in args.stats:
        try:
            with open(path) as f:
                rows.append(row(json.load(f)))
        except (OSError, ValueError, KeyError, TypeError) as e:
            print(f"stats_table: error: {path}: {e!r}", file=sys.stderr)
            sys.exit(2)
    print(table(rows))
    print()
    print(LEGEND)


if __name__ == "__main__":
    main()
