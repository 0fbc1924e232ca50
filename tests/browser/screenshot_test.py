#!/usr/bin/python3
"""scripts/make-viewer-screenshot on a small scene (stack_5, 0.2 s) in headless Chromium, twice:
with boxpile's own default engine list (no --engines: the report's engines must be the list
`boxpile compare --help` names as its default) and with an explicit list of two. Each PNG must have
the window's size, be far from blank (many distinct colours, the ground's grey among them) and show
every engine's colour (the page's data: the registry's colours) in at least MIN_ENGINE_PIXELS pixels,
and no colour of an engine that did not run. Run by ctest (tests/CMakeLists.txt).

Usage: screenshot_test.py BOXPILE CHROMIUM SOURCE_DIR WORK
"""
import json
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from replay_test import (GROUND_SATURATION, GROUND_VALUE, HUE_TOLERANCE, MIN_SATURATION, MIN_VALUE,  # noqa: E402
                         hue_distance, hue_of, read_png)
import colorsys  # noqa: E402

from browser_checks import check, failures  # noqa: E402

WINDOW = (1200, 600)
# Five 1 m cubes in a 400-600 x 600 viewport cover tens of thousands of pixels; 300 is far above
# antialiasing noise and far below the real count.
MIN_ENGINE_PIXELS = 300
# A rendered page (boxes shaded, ground, labels, timeline): thousands of colours; a blank or
# single-colour page a handful.
MIN_DISTINCT_COLOURS = 200



def default_engines(boxpile):
    text = subprocess.run([boxpile, "compare", "--help"], check=True, capture_output=True, text=True).stdout
    match = re.search(r"--engines .*?default: ([\w,-]+)\)", " ".join(text.split()))
    return match.group(1).split(",") if match else None


def shoot(boxpile, chromium, source, work, engines):
    name = "default" if engines is None else "-".join(engines)
    out, report = os.path.join(work, name + ".png"), os.path.join(work, name + "-report")
    cmd = [os.path.join(source, "scripts", "make-viewer-screenshot"), "--boxpile", boxpile, "--chromium", chromium,
           "--scene", os.path.join(source, "fixtures", "scenes", "stack_5.json"), "--duration", "0.2",
           "--view", "t=0.1&mode=side", "--window", f"{WINDOW[0]},{WINDOW[1]}", "--out", out, "--report", report]
    if engines is not None:
        cmd += ["--engines", ",".join(engines)]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    print(" ".join(cmd), "->", result.returncode, result.stdout.strip(), result.stderr.strip()[-500:])
    check(result.returncode == 0 and os.path.isfile(out), f"{name}: make-viewer-screenshot failed")
    if result.returncode != 0 or not os.path.isfile(out):
        return None, None, None
    with open(os.path.join(report, "report.json"), encoding="utf-8") as f:
        ran = sorted(json.load(f)["engines"])
    with open(os.path.join(report, "replay.html"), encoding="utf-8") as f:
        data = json.loads(re.search(r'<script id="replay-data" type="application/json">(.*?)</script>', f.read(),
                                    re.DOTALL).group(1))
    colours = {e["name"]: e["colour"] for e in data["engines"]}
    if sorted(colours) != ran:
        check(False, f"{name}: the page shows {sorted(colours)}, report.json has {ran}")
    return out, [e["name"] for e in data["engines"]], colours


def check_png(name, path, colours, absent):
    width, height, rows = read_png(path)
    check((width, height) == WINDOW, f"{name}: the PNG is {width} x {height}, expected {WINDOW[0]} x {WINDOW[1]}")
    distinct, ground = set(), 0
    counts = {e: 0 for e in list(colours) + list(absent)}
    hues = {e: hue_of(c) for e, c in list(colours.items()) + list(absent.items())}
    for row in rows:
        for x in range(0, width):
            r, g, b = row[4 * x], row[4 * x + 1], row[4 * x + 2]
            distinct.add((r, g, b))
            h, s, v = colorsys.rgb_to_hsv(r / 255, g / 255, b / 255)
            if s < GROUND_SATURATION and GROUND_VALUE[0] <= v <= GROUND_VALUE[1]:
                ground += 1
            elif s >= MIN_SATURATION and v >= MIN_VALUE:
                for e, hue in hues.items():
                    if hue_distance(h, hue) <= HUE_TOLERANCE:
                        counts[e] += 1
    print(f"{name}: {len(distinct)} distinct colours, {ground} ground pixels, engine pixels {counts}")
    check(len(distinct) >= MIN_DISTINCT_COLOURS, f"{name}: {len(distinct)} distinct colours (blank?)")
    check(ground >= 0.05 * width * height, f"{name}: {ground} pixels of the ground's grey")
    for e in colours:
        check(counts[e] >= MIN_ENGINE_PIXELS, f"{name}: {counts[e]} pixels of {e}'s colour {colours[e]}")
    for e in absent:
        # An absent engine's hue may be near a present one's: only a hue far from all of them counts.
        if all(hue_distance(hues[e], hue_of(c)) > 2 * HUE_TOLERANCE for c in colours.values()):
            check(counts[e] < MIN_ENGINE_PIXELS, f"{name}: {counts[e]} pixels of {e}'s colour, which did not run")


def main():
    boxpile, chromium, source, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    expected = default_engines(boxpile)
    check(expected is not None, "boxpile compare --help names no default engine list")
    out, ran, colours = shoot(boxpile, chromium, source, work, None)
    if out:
        check(ran == expected, f"without --engines the script ran {ran}; boxpile's default list is {expected}")
        check_png("default engines", out, colours, {})
        default_colours = colours
        two = ["own", "ode"]
        out, ran, colours = shoot(boxpile, chromium, source, work, two)
        if out:
            check(ran == two, f"--engines own,ode ran {ran}")
            check_png("own,ode", out, colours, {e: c for e, c in default_colours.items() if e not in two})
    if failures:
        print(f"{len(failures)} failure(s)")
        sys.exit(1)
    print("ok")


if __name__ == "__main__":
    main()
