"""scripts/grade_report.py - the report of scripts/grade: each scene's images (reference, actual, difference x10,
tests-per-pixel heatmap on the stage's one scale) and metrics, the HTML page, and the headless-browser check that the page
loads. scripts/grade decides the verdicts; this module only draws them.
"""
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

from golden_cases import last_frame_suffix

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
THRESHOLD, FAIL_FRACTION = 0.016, 0.01   # tests/image_compare.cpp's defaults


def display(test):
    """A CTest name as a person reads it: without GoogleTest's "  # GetParam() = ..." comment."""
    return test.split("  # ")[0]


def fail(message):
    print(f"grade: error: {message}", file=sys.stderr)
    sys.exit(2)


def srgb8(path):
    """An image as image_compare sees it: sRGB values quantized to 8 bits, in [0, 1] (float files encoded)."""
    buf = oiio.ImageBuf(path)
    pixels = buf.get_pixels(oiio.FLOAT)
    if pixels is None or pixels.size == 0:
        raise RuntimeError(f"cannot read {path}")
    rgb = np.nan_to_num(pixels[:, :, :3] if pixels.shape[2] >= 3 else np.repeat(pixels[:, :, :1], 3, axis=2))
    if path.endswith((".exr", ".hdr")):
        c = np.clip(rgb, 0.0, 1.0)
        rgb = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1.0 / 2.4) - 0.055)
        rgb = np.round(rgb * 255.0) / 255.0
    return rgb.astype(np.float32)


def write_png(rgb, path):
    out = oiio.ImageBuf(oiio.ImageSpec(rgb.shape[1], rgb.shape[0], 3, oiio.UINT8))
    out.set_pixels(oiio.ROI(), np.ascontiguousarray(np.clip(rgb, 0.0, 1.0), dtype=np.float32))
    if not out.write(path):
        raise RuntimeError(f"cannot write {path}: {out.geterror()}")


def actual_image(build, stage, name, args):
    """The frame golden.<stage>.<name> compared (tests/run_golden.cmake: the last of --frames N)."""
    return os.path.join(build, "test-output", "golden", stage, f"{name}{last_frame_suffix(args)}.exr")




def grade_scene(build, stage, name, scene, args, passed, out):
    entry = {"name": name, "scene": scene, "passed": passed, "images": {}}
    reference = os.path.join(ROOT, "tests", "golden", stage, f"{name}.png")
    actual = actual_image(build, stage, name, args)
    prefix = f"{stage}/{name}"
    os.makedirs(os.path.join(out, stage), exist_ok=True)
    if os.path.exists(reference):
        shutil.copyfile(reference, os.path.join(out, prefix + "_reference.png"))
        entry["images"]["reference"] = prefix + "_reference.png"
    if os.path.exists(actual) and os.path.exists(reference):
        a, r = srgb8(actual), srgb8(reference)
        write_png(a, os.path.join(out, prefix + "_actual.png"))
        entry["images"]["actual"] = prefix + "_actual.png"
        if a.shape == r.shape:
            d = np.abs(a - r)
            failing = int(np.count_nonzero(d.max(axis=2) > THRESHOLD))
            entry.update(failing_pixels=failing, failing_fraction=failing / (a.shape[0] * a.shape[1]),
                         max_error=float(d.max()), rmse=float(np.sqrt(np.mean(d * d))))
            write_png(np.minimum(d * 10.0, 1.0), os.path.join(out, prefix + "_diff.png"))
            entry["images"]["difference x10"] = prefix + "_diff.png"
        else:
            entry["error"] = f"size {a.shape[1]}x{a.shape[0]}, reference {r.shape[1]}x{r.shape[0]}"
    else:
        entry["error"] = "no image rendered" if not os.path.exists(actual) else "no reference image"
    return entry


def add_heatmaps(build, report, staging, scenes_args):
    """Every scene's heatmap: the one its golden test drew from the frame it compared (tests/run_golden.cmake), so
    grading renders nothing more. A stage's heatmaps share one scale, from 0 to the most tests any pixel of the
    stage's references took (a frame above that takes the top colour), so they compare colour for colour; a scene
    without one says why."""
    for stage, st in report["stages"].items():
        folder = os.path.join(build, "test-output", "golden", stage)
        for sc in st["scenes"]:
            name = sc["name"]
            drawn = os.path.join(folder, f"{name}_heatmap{last_frame_suffix(scenes_args[name])}.png")
            why = os.path.join(folder, f"{name}_heatmap.txt")   # the stage's reason when it cannot draw one
            if os.path.exists(why):
                with open(why) as f:
                    sc["heatmap_error"] = (f.read().strip().splitlines() or ["the stage cannot draw it"])[0]
                continue
            if not os.path.exists(drawn):
                sc["heatmap_error"] = f"golden.{stage}.{name} drew none (it did not render)"
                continue
            try:
                with open(os.path.join(folder, f"{name}.json")) as f:
                    top = int(json.load(f)["heatmap"]["scale_max"])
            except (OSError, ValueError, KeyError, TypeError) as e:
                sc["heatmap_error"] = f"golden.{stage}.{name}'s stats give no heatmap scale ({e})"
                continue
            shutil.copyfile(drawn, os.path.join(staging, f"{stage}/{name}_heatmap.png"))
            sc["images"][f"tests per pixel (0 to {top})"] = f"{stage}/{name}_heatmap.png"


def page(report):
    e = html.escape
    verdict_class = {"passed": "pass", "failed": "fail", "not attempted": "todo", "not graded": "todo"}
    rows = "".join(
        f"<tr class={verdict_class[x['verdict']]}><td><a href='#{e(n)}'>{e(n)}</a></td><td>{e(x['stage'])}</td>"
        f"<td>{x['tests_passed']} / {len(x['tests'])}</td><td>{e(x['verdict'])}</td>"
        f"<td><code>{e(x['message'].splitlines()[0] if x['message'] else '')}</code></td></tr>"
        for n, x in report["exercises"].items())
    body = [f"<h1>Grading report</h1><p>{e(report['date'])} &middot; {e(report['root'])}</p>",
            "<table class=summary><tr><th>exercise</th><th>stage</th><th>tests passed</th><th>verdict</th>"
            f"<th>first failure</th></tr>{rows}</table>"]
    if report.get("build_error"):
        body.append(f"<p class=fail>The build failed: <code>{e(report['build_error'])}</code></p>")
    for n, x in report["exercises"].items():
        body.append(f"<div class='exercise {verdict_class[x['verdict']]}' id='{e(n)}'><h2>{e(n)}: {e(x['verdict'])}"
                    "</h2>")
        if x["message"]:
            body.append(f"<pre>{e(x['message'])}</pre>")
        for part in x["hint"]:
            body.append(f"<p class=hint><b>{e(part['path'])}:{part['line']}</b> {e(part['hint'])}</p>")
        if x["failed_tests"]:
            body.append("<p>Failing tests: " + ", ".join(f"<code>{e(display(t))}</code>" for t in x["failed_tests"][:30])
                        + (f" and {len(x['failed_tests']) - 30} more" if len(x["failed_tests"]) > 30 else "")
                        + "</p>")
        scenes = report["stages"].get(x["stage"], {}).get("scenes", [])
        for sc in scenes:
            if not sc["passed"] and f"golden.{x['stage']}.{sc['name']}" in x["failed_tests"]:
                body.append(scene_html(sc))
        body.append("</div>")
    for n, st in report["stages"].items():
        body.append(f"<h2 id='stage-{e(n)}'>{e(n)}: every scene</h2>")
        body += [scene_html(sc) for sc in st["scenes"]]
    style = ("body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}td,th{padding:4px 12px;"
             "border:1px solid #ccc;text-align:left}.pass td:nth-child(4){color:#070}"
             ".fail td:nth-child(4){color:#b00;font-weight:bold}.todo td:nth-child(4){color:#a60}"
             "figure{display:inline-block;margin:4px}img{width:300px;image-rendering:pixelated;border:1px solid #999}"
             ".scene,.exercise{border-left:6px solid #7a7;padding-left:8px;margin:12px 0}.scene.fail,"
             ".exercise.fail{border-color:#c44}.exercise.todo{border-color:#da4}pre{background:#f4f4f4;padding:6px;"
             "white-space:pre-wrap}.hint{color:#333}")
    # Once loaded, the page names in its title how many images decoded (--check-report reads it in a browser).
    script = ("window.addEventListener('load',()=>{const i=[...document.images];"
              "const bad=i.filter(x=>!x.complete||x.naturalWidth==0).map(x=>x.getAttribute('src'));"
              "document.title=bad.length?'report: missing '+bad.join(' '):'report: '+i.length+' images loaded';});")
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>Grading report</title><style>{style}</style>"
            f"<script>{script}</script></head><body>{''.join(body)}</body></html>\n")


def scene_html(sc):
    e = html.escape
    metrics = (f"failing pixels {sc['failing_pixels']} ({100 * sc['failing_fraction']:.2f}%, allowed "
               f"{100 * FAIL_FRACTION:.0f}%), max error {sc['max_error']:.3f}, RMSE {sc['rmse']:.4f}"
               if "rmse" in sc else e(sc.get("error", "")))
    if not sc["passed"] and "rmse" in sc and sc["failing_fraction"] <= FAIL_FRACTION:
        metrics += " &mdash; the image is within tolerance: its golden test failed on the frame's counts"
    if sc.get("heatmap_error"):
        metrics += f"; no heatmap: {e(sc['heatmap_error'])}"
    images = "".join(f"<figure><img src='{e(p)}' alt='{e(k)}'><figcaption>{e(k)}</figcaption></figure>"
                     for k, p in sc["images"].items())
    return (f"<div class='scene {'pass' if sc['passed'] else 'fail'}'><h3>{e(sc['name'])} "
            f"<small>{e(sc['scene'])}</small> &mdash; {'pass' if sc['passed'] else 'FAIL'}</h3>"
            f"<p>{metrics}</p>{images}</div>")


def check_report(folder, screenshot):
    """Loads folder/index.html in headless chromium; 0 when every image decoded."""
    page_path = os.path.join(os.path.abspath(folder), "index.html")
    if not os.path.isfile(page_path):
        fail(f"{page_path}: no report there")
    browser = shutil.which("chromium")
    if not browser:
        fail("chromium not found (scripts/setup installs it)")
    expected = len(re.findall(r"<img ", open(page_path).read()))
    flags = ["--headless", "--no-sandbox", "--disable-gpu", "--allow-file-access-from-files",
             "--virtual-time-budget=10000"]
    with tempfile.TemporaryDirectory() as profile:
        dom = subprocess.run([browser, *flags, f"--user-data-dir={profile}", "--dump-dom", "file://" + page_path],
                             capture_output=True, text=True, timeout=120).stdout
        if screenshot:
            subprocess.run([browser, *flags, f"--user-data-dir={profile}", "--window-size=1400,1800",
                            f"--screenshot={os.path.abspath(screenshot)}", "file://" + page_path],
                           capture_output=True, timeout=120)
    title = re.search(r"<title>(.*?)</title>", dom or "")
    title = html.unescape(title.group(1)) if title else "(no page)"
    ok = title == f"report: {expected} images loaded"
    print(f"grade: chromium: {title} (the page has {expected})")
    return 0 if ok else 1
