#!/usr/bin/python3
"""One labelled 16:9 picture for slides (scripts/demo): each stage's image above its --heatmap, labelled with the
frame time and the ray/triangle tests per ray, and one colour bar with the heatmaps' counts.

    scripts/demo_strip.py OUT.png STAGE.json ...

Each STAGE.json is a stage's --stats file; the image and the heatmap are the files beside it, STAGE.png and
STAGE_heatmap.png (what scripts/demo writes). The caption says whether the heatmaps share one scale (the stats'
heatmap min, max and scale equal) or not. Uses python3-matplotlib (PNG reading and writing included).
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from stats_table import tests_per_ray  # noqa: E402


def load(path):
    with open(path) as f:
        stats = json.load(f)
    base = os.path.splitext(path)[0]
    image = plt.imread(base + ".png")
    heat = plt.imread(base + "_heatmap.png")
    bar_rows = stats["heatmap"]["colour_bar_rows"]
    return stats, image, heat[: heat.shape[0] - bar_rows], heat[heat.shape[0] - bar_rows:]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out", help="the PNG to write (out/demo_strip.png)")
    p.add_argument("stats", nargs="+", help="the stages' stats JSON files, image and heatmap beside each")
    args = p.parse_args()
    try:
        stages = [load(path) for path in args.stats]
    except (OSError, ValueError, KeyError) as e:
        print(f"demo_strip: error: {e}", file=sys.stderr)
        sys.exit(2)

    n = len(stages)
    fig = plt.figure(figsize=(16, 9), dpi=120)
    first = stages[0][0]
    fig.suptitle(f'{first["scene"]}, {first["width"]}x{first["height"]}, every stage: the image, and the ray/triangle '
                 f'tests of each pixel\'s ray tree', fontsize=17, y=0.97)
    grid = fig.add_gridspec(3, n, height_ratios=[1, 1, 0.07], left=0.02, right=0.98, top=0.86, bottom=0.13,
                            hspace=0.12, wspace=0.04)
    for k, (stats, image, heat, _) in enumerate(stages):
        tpr = tests_per_ray(stats)
        top = fig.add_subplot(grid[0, k])
        top.imshow(image)
        top.set_title(f'{stats["stage"]}\n{stats["time_ms"]["total"]:.0f} ms, '
                      f'{"-" if tpr is None else f"{tpr:.1f}"} tests/ray', fontsize=14)
        bottom = fig.add_subplot(grid[1, k])
        bottom.imshow(heat)
        for ax in (top, bottom):
            ax.set_xticks([])
            ax.set_yticks([])

    scales = {(s["heatmap"]["min"], s["heatmap"]["max"], s["heatmap"]["scale"]) for s, *_ in stages}
    lo, hi, scale = max(scales, key=lambda t: t[1])
    bar_stats, bar = next((s, b) for s, _, _, b in stages if s["heatmap"]["max"] == hi)
    bar_ax = fig.add_subplot(grid[2, :])
    bar_ax.imshow(bar, aspect="auto", extent=(0, 1, 0, 1))
    ticks = bar_stats["heatmap"]["ticks"]
    bar_ax.set_xticks([i / (len(ticks) - 1) for i in range(len(ticks))])
    bar_ax.set_xticklabels([f"{t:,.0f}" for t in ticks], fontsize=12)
    bar_ax.set_yticks([])
    if len(scales) == 1:
        caption = (f"Heatmaps: ray/triangle tests per pixel, every stage on one {scale} scale from {lo:,} to {hi:,} "
                   f"(--heatmap-scale {scale} --heatmap-max {hi}: {stages[0][0]['stage']}'s largest count).")
    else:
        caption = (f"Heatmaps: ray/triangle tests per pixel, each stage on its own scale (they differ); the bar is "
                   f"{bar_stats['stage']}'s, {lo:,} to {hi:,}, {scale}.")
    fig.text(0.5, 0.035, caption + " Time: the frame's wall clock; tests/ray: every test per ray, rasterized "
             "primaries included.", ha="center", fontsize=12, wrap=True)
    fig.savefig(args.out)
    print(f"demo: wrote {args.out}")


if __name__ == "__main__":
    main()
