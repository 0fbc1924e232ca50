#!/usr/bin/python3
"""The replay page in a real browser: boxpile compare writes replay.html for a short run of the
bone scene; headless Chromium loads it from disk and the page's state on <body> is checked
against report.json; a screenshot's pixels must show each engine's colour in its own viewport,
the ground under them and the contact points in their light tint; the first camera must frame the
bodies as they start (the bone scene's across the viewport, a tower beside a cube shot away from
it from top to bottom); the timeline's energy graph must hold one line per engine, in its colour,
through report.json's energies, with its cursor at the frame shown; the page must hold no external
resource. Run by ctest (tests/CMakeLists.txt).

Usage: replay_test.py BOXPILE CHROMIUM FIXTURES WORK
"""
import colorsys
import json
import os
import re
import shutil
import subprocess
import sys
import time

import png  # python3-png

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from browser_checks import check, failures  # noqa: E402

ENGINES = ["own", "ode", "bullet"]
# Each engine's colour, read from the page's data (the engine registry's colours).
COLOURS = {}
# A pixel counts as an engine's when its hue is this close to the engine colour's (shading changes
# brightness, not hue) and it is saturated enough not to be ground or background.
HUE_TOLERANCE = 12 / 360
MIN_SATURATION = 0.3
MIN_VALUE = 0.15
# Ten 0.4 m boxes of the pile in a 400 x 560 viewport cover thousands of pixels; 300 is far
# above noise (antialiased edges of another engine's colour) and far below the real count.
MIN_ENGINE_PIXELS = 300
# Another engine's colour inside a viewport: at most this fraction of the viewport's own.
MAX_FOREIGN_FRACTION = 0.02
# The ground: grey (saturation below this), neither background-dark nor white.
GROUND_SATURATION = 0.1
GROUND_VALUE = (0.35, 0.8)
# The ground fills the lower part of every viewport: at least this fraction of its pixels.
MIN_GROUND_FRACTION = 0.15
WINDOW = (1200, 700)
# The frame shown in the checks: the start, which shows the first step's contact set.
FRAME = 0
# Tries of the playing page before its check fails (see main).
PLAY_ATTEMPTS = 3
# The first camera frames the bodies of the first frame: through it they span at least this share
# of the first viewport's width or height (the page's data-framing; the fit leaves a margin of
# 8%, so a fitted view gives about 0.92), and a screenshot's pixels of the engine's colour span at
# least the second share of its viewport (the bone 6 m from the pile across; SHOT_SCENE's tower
# from top to bottom).
MIN_FRAMING = 0.85
MIN_PIXEL_SPAN = 0.7
# Contact points: a light tint of the engine's colour, at least this contrast ratio (WCAG's
# relative luminance) against the engine's colour, so that a dot reads on its boxes (a face is
# drawn at most as bright as the colour itself: ambient and sun add up to less than 1), with a dark
# rim for the light ground; the engines' colours, of luminance 0.16 to 0.26, allow a tint of
# about 2.9 to 5 that still shows whose it is (1 for the colour itself, 21 black on white), and the
# rim at least MIN_RIM_CONTRAST against it (the light colours, as MuJoCo's orange, need it); a pixel
# within this RGB distance of the tint counts as a dot's, and every viewport at frame 0 (50 to 64
# contacts, dots of at least 8 pixels) shows at least this many.
MIN_CONTACT_CONTRAST = 2.8
MIN_RIM_CONTRAST = 3.0
TINT_DISTANCE = 24
MIN_CONTACT_PIXELS = 150
DOT_PIXELS = (8, 20)
# The energy graph's drawing (validation/replay/viewer.js: GRAPH_WIDTH, GRAPH_HEIGHT, GRAPH_MARGIN)
# and the rounding of its coordinates (one decimal).
GRAPH = (1000, 100, 8)
GRAPH_ROUNDING = 0.051



def chromium_command(chromium, extra, url):
    return [chromium, "--headless", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
            "--disable-gpu-sandbox", "--no-first-run", "--mute-audio",
            # Any network request would fail: the page must not need one.
            "--host-resolver-rules=MAP * ~NOTFOUND", "--virtual-time-budget=5000"] + extra + [url]


def run_chromium(chromium, extra, url):
    start = time.monotonic()
    result = subprocess.run(chromium_command(chromium, extra, url), capture_output=True, text=True, timeout=240)
    print(f"chromium {' '.join(extra)}: {time.monotonic() - start:.1f} s")
    if result.returncode != 0:
        print(result.stderr[-2000:])
    return result


def body_attributes(dom):
    match = re.search(r"<body\b([^>]*)>", dom)
    if not match:
        return {}
    return dict(re.findall(r'([\w-]+)="([^"]*)"', match.group(1)))


def external_resources(html):
    """What would load something from outside the file: a script with src, an element with src,
    href or data, url(...) or @import in a style, any address outside the inlined scripts (three.js
    holds namespace strings in its code, never loaded)."""
    found = [tag for tag in re.findall(r"<script\b[^>]*>", html, re.IGNORECASE) if re.search(r"\bsrc\s*=", tag)]
    outside = re.sub(r"<script\b[^>]*>.*?</script>", "", html, flags=re.DOTALL | re.IGNORECASE)
    found += re.findall(r"<\w+\b[^>]*\b(?:src|href|data|srcset|poster)\s*=[^>]*>", outside, re.IGNORECASE)
    found += re.findall(r"(?:https?:|ftp:|file:)//|url\(|@import", outside, re.IGNORECASE)
    return found


def hue_of(hex_colour):
    r, g, b = (int(hex_colour[k:k + 2], 16) / 255 for k in (1, 3, 5))
    return colorsys.rgb_to_hsv(r, g, b)[0]


def hue_distance(a, b):
    d = abs(a - b) % 1.0
    return min(d, 1.0 - d)


def luminance(hex_colour):
    def channel(c):
        return c / 12.92 if c <= 0.03928 else ((c + 0.055) / 1.055) ** 2.4
    r, g, b = (channel(int(hex_colour[k:k + 2], 16) / 255) for k in (1, 3, 5))
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def contrast(a, b):
    la, lb = sorted((luminance(a), luminance(b)), reverse=True)
    return (la + 0.05) / (lb + 0.05)


def read_png(path):
    width, height, rows, info = png.Reader(filename=path).asRGBA8()
    return width, height, [bytearray(r) for r in rows]


# The band at the top of a viewport that holds its label (the engine's swatch in its colour).
LABEL_BAND = 32


def colour_span(rows, box, engine):
    """The share of the box (x0, y0, x1, y1), its label's band left out, that the pixels of the
    engine's colour span, across and down."""
    x0, y0, x1, y1 = box
    y0 += LABEL_BAND
    hue = hue_of(COLOURS[engine])
    xs, ys = [], []
    for y in range(y0, y1):
        row = rows[y]
        for x in range(x0, x1):
            h, s, v = colorsys.rgb_to_hsv(row[4 * x] / 255, row[4 * x + 1] / 255, row[4 * x + 2] / 255)
            if s >= MIN_SATURATION and v >= MIN_VALUE and hue_distance(h, hue) < HUE_TOLERANCE:
                xs.append(x)
                ys.append(y)
    if not xs:
        return 0.0, 0.0
    return (max(xs) - min(xs) + 1) / (x1 - x0), (max(ys) - min(ys) + 1) / (y1 - y0)


def check_screenshot(path, canvas, tints):
    """`canvas`: left, top, width, height of the 3D view in the page (data-canvas), in pixels;
    `tints`: each engine's contact colour (data-contact-fill)."""
    width, height, rows = read_png(path)
    check((width, height) == WINDOW, f"screenshot is {width}x{height}, expected {WINDOW}")
    left, top, view_width, view_height = canvas
    check(view_width > 0 and view_height > 0 and left + view_width <= width and top + view_height <= height,
          f"data-canvas {canvas} does not lie within the {width}x{height} window")
    hues = {e: hue_of(COLOURS[e]) for e in ENGINES}
    columns = len(ENGINES)
    for index, engine in enumerate(ENGINES):
        # Side by side: the viewports split the view's width evenly.
        x0, x1 = left + index * view_width // columns, left + (index + 1) * view_width // columns
        counts = {e: 0 for e in ENGINES}
        ground = total = dots = 0
        tint = [int(tints[index][k:k + 2], 16) for k in (1, 3, 5)]
        for y in range(top, min(height, top + view_height)):
            row = rows[y]
            for x in range(x0, x1):
                r, g, b = row[4 * x] / 255, row[4 * x + 1] / 255, row[4 * x + 2] / 255
                h, s, v = colorsys.rgb_to_hsv(r, g, b)
                total += 1
                if sum((255 * c - t) ** 2 for c, t in zip((r, g, b), tint)) <= TINT_DISTANCE ** 2:
                    dots += 1
                if s < GROUND_SATURATION and GROUND_VALUE[0] <= v <= GROUND_VALUE[1]:
                    ground += 1
                if s < MIN_SATURATION or v < MIN_VALUE:
                    continue
                for e in ENGINES:
                    if hue_distance(h, hues[e]) < HUE_TOLERANCE:
                        counts[e] += 1
        print(f"viewport {engine}: engine pixels {counts}, ground {ground / total:.2f} of {total}, contact dots {dots}")
        check(dots >= MIN_CONTACT_PIXELS,
              f"viewport {index} ({engine}): {dots} pixels of the contact tint {tints[index]}, expected >= {MIN_CONTACT_PIXELS}")
        across, down = colour_span(rows, (x0, top, x1, min(height, top + view_height)), engine)
        print(f"viewport {engine}: its colour spans {across:.2f} across, {down:.2f} down")
        check(across >= MIN_PIXEL_SPAN,
              f"viewport {index} ({engine}): the bodies span {across:.2f} of its width, expected >= {MIN_PIXEL_SPAN}")
        check(counts[engine] >= MIN_ENGINE_PIXELS,
              f"viewport {index} ({engine}): {counts[engine]} pixels of its colour, expected >= {MIN_ENGINE_PIXELS}")
        for other in ENGINES:
            if other != engine:
                check(counts[other] <= MAX_FOREIGN_FRACTION * max(counts[engine], 1),
                      f"viewport {index} ({engine}): {counts[other]} pixels of {other}'s colour")
        check(ground >= MIN_GROUND_FRACTION * total,
              f"viewport {index} ({engine}): ground covers {ground / total:.2f}, expected >= {MIN_GROUND_FRACTION}")


def check_energy_graph(dom, report):
    """One polyline per engine, in its colour, through report.json's energy at every frame on the
    graph's one scale."""
    lines = re.findall(r'<polyline\b([^>]*)>', dom)
    attributes = [dict(re.findall(r'([\w-]+)="([^"]*)"', line)) for line in lines]
    check([a.get("data-engine") for a in attributes] == ENGINES,
          f"energy graph: polylines of {[a.get('data-engine') for a in attributes]}, expected one per engine {ENGINES}")
    series = {e: report["engines"][e]["series"] for e in ENGINES}
    energies = [x for e in ENGINES for x in series[e]["energy"] if x is not None]
    lo, hi = min(energies), max(energies)
    width, height, margin = GRAPH
    for a in attributes:
        engine = a.get("data-engine")
        if engine not in series:
            continue
        check(a.get("stroke", "").lower() == COLOURS[engine].lower(),
              f"energy graph: {engine}'s line is {a.get('stroke')}, its colour {COLOURS[engine]}")
        points = [tuple(float(v) for v in p.split(",")) for p in a.get("points", "").split()]
        t, energy = series[engine]["t"], series[engine]["energy"]
        check(len(points) == len(t), f"energy graph: {engine}'s line has {len(points)} points, {len(t)} frames")
        worst = 0.0
        for (x, y), tk, ek in zip(points, t, energy):
            expected_x = width * (tk - t[0]) / (t[-1] - t[0])
            expected_y = height - margin - (height - 2 * margin) * (ek - lo) / (hi - lo)
            worst = max(worst, abs(x - expected_x), abs(y - expected_y))
        # The page's energies are float32 (replay data): 333.5 J to 1e-5 J, far below a pixel here.
        check(worst <= GRAPH_ROUNDING + (height - 2 * margin) * 1e-4 * hi / (hi - lo),
              f"energy graph: {engine}'s line strays {worst:.3f} from report.json's energies")


# A tower of five unit cubes and a cube shot away from it at 40 m/s: 12 m away after 0.3 s. The
# first camera frames the bodies as they start (a camera fitted to the whole run, as the page had
# before, spans 0.53 of the view's height with them).
SHOT_SCENE = {"name": "tower_and_shot", "ground": {},
              "bodies": [{"name": f"t{k}", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [0, 0, 0.5 + k]}
                         for k in range(5)] +
                        [{"name": "shot", "mass": 1, "half_extents": [0.5, 0.5, 0.5], "position": [1.5, 0, 0.5],
                          "velocity": [40, 0, 0]}],
              "time": {"dt": 1 / 240, "duration": 0.3}}


def check_first_frame_framing(boxpile, chromium, work, canvas):
    """The tower and the shot as they start fill the view from top to bottom."""
    scene = os.path.join(work, "shot.json")
    with open(scene, "w") as f:
        json.dump(SHOT_SCENE, f)
    report_dir = os.path.join(work, "shot")
    run = subprocess.run([boxpile, "compare", scene, "--engines", "own", "--report", report_dir],
                         capture_output=True, text=True)
    check(run.returncode == 0, f"boxpile compare {scene}: exit {run.returncode}\n{run.stderr}")
    shot = os.path.join(work, "shot.png")
    run_chromium(chromium, [f"--screenshot={shot}", f"--window-size={WINDOW[0]},{WINDOW[1]}"],
                 "file://" + os.path.abspath(os.path.join(report_dir, "replay.html")) + "#frame=0")
    check(os.path.isfile(shot), "chromium wrote no screenshot of the shot scene")
    if not os.path.isfile(shot):
        return
    width, height, rows = read_png(shot)
    left, top, view_width, view_height = canvas
    across, down = colour_span(rows, (left, top, left + view_width, min(height, top + view_height)), "own")
    print(f"tower and shot: own's colour spans {across:.2f} across, {down:.2f} down")
    check(down >= MIN_PIXEL_SPAN, f"tower and shot: the bodies span {down:.2f} of the view's height, expected >= {MIN_PIXEL_SPAN}")


def main():
    boxpile, chromium, fixtures, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    report_dir = os.path.join(work, "report")
    compare = subprocess.run([boxpile, "compare", os.path.join(fixtures, "scenes", "bone_hits_pile.json"),
                              "--duration", "0.1", "--engines", ",".join(ENGINES), "--report", report_dir],
                             capture_output=True, text=True)
    check(compare.returncode == 0, f"boxpile compare: exit {compare.returncode}\n{compare.stderr}")
    page = os.path.join(report_dir, "replay.html")
    check(os.path.isfile(page), "compare wrote no replay.html")
    if failures:
        return 1
    with open(os.path.join(report_dir, "report.json")) as f:
        report = json.load(f)
    with open(page, encoding="utf-8") as f:
        html = f.read()
    check(external_resources(html) == [], f"external resources in the page: {external_resources(html)[:5]}")
    page_data = json.loads(re.search(r'<script id="replay-data" type="application/json">(.*?)</script>', html,
                                     re.DOTALL).group(1))
    COLOURS.update({e["name"]: e["colour"] for e in page_data["engines"]})
    check(sorted(COLOURS) == sorted(ENGINES), f"the page's engines {sorted(COLOURS)}")

    url = "file://" + os.path.abspath(page) + f"#frame={FRAME}&mode=side"
    window = f"--window-size={WINDOW[0]},{WINDOW[1]}"
    dom = run_chromium(chromium, ["--dump-dom", window], url).stdout
    body = body_attributes(dom)
    print("body:", body)
    check(body.get("data-state") == "ready", f"data-state is {body.get('data-state')!r}, expected 'ready'")
    check(body.get("data-engines") == ",".join(ENGINES), f"data-engines is {body.get('data-engines')!r}")
    check(sorted(report["engines"]) == sorted(ENGINES), f"report.json engines {sorted(report['engines'])}")
    frames = {len(report["engines"][e]["series"]["t"]) for e in ENGINES}
    check(len(frames) == 1 and body.get("data-frames") == str(frames.pop()),
          f"data-frames {body.get('data-frames')!r} against report.json's {frames}")
    check(body.get("data-frame") == str(FRAME), f"data-frame {body.get('data-frame')!r}, expected {FRAME}")
    contacts = sum(report["engines"][e]["series"]["contacts"][FRAME] for e in ENGINES)
    check(contacts > 0, "report.json: no contact in the frame checked (the pile rests on the ground)")
    check(body.get("data-contacts") == str(contacts),
          f"data-contacts {body.get('data-contacts')!r}, expected {contacts} (report.json, frame {FRAME})")
    check(body.get("data-resources") == "0", f"the page loaded {body.get('data-resources')} resources")
    framing = [float(x) for x in body.get("data-framing", "0,0").split(",")]
    check(max(framing) >= MIN_FRAMING, f"data-framing {framing}: the first frame's bodies fill less than {MIN_FRAMING}")
    tints = body.get("data-contact-fill", "").split(",")
    check(len(tints) == len(ENGINES), f"data-contact-fill {tints}")
    for engine, tint in zip(ENGINES, tints):
        check(contrast(tint, COLOURS[engine]) >= MIN_CONTACT_CONTRAST,
              f"{engine}: contact tint {tint} has contrast {contrast(tint, COLOURS[engine]):.2f} against {COLOURS[engine]}")
    rim = body.get("data-contact-rim", "#000000")
    for engine, colour in COLOURS.items():
        check(contrast(rim, colour) >= MIN_RIM_CONTRAST, f"{engine}: the dots' rim {rim} has contrast "
              f"{contrast(rim, colour):.2f} against {colour}")
    check(contrast(rim, "#9c9c94") >= MIN_RIM_CONTRAST, f"the dots' rim {rim} against the ground")
    dot = float(body.get("data-contact-pixels", "0"))
    check(DOT_PIXELS[0] <= dot <= DOT_PIXELS[1], f"data-contact-pixels {dot}, expected within {DOT_PIXELS}")
    check_energy_graph(dom, report)
    check(body.get("data-energy-cursor") == "0.0000", f"frame 0: data-energy-cursor {body.get('data-energy-cursor')!r}")

    # Overlaid, contacts off, a body picked by name, playing: the 0.1 s run plays to its last frame
    # within the 5 s of virtual time, drawing no contact, with the body still picked. Playback runs
    # on animation frames, which headless Chromium's software renderer can starve on a loaded
    # machine (once in a CI run, under the sanitizer stage's load: no frame after the first). So the
    # play is tried up to PLAY_ATTEMPTS times; a page that does not play fails every one.
    last = str(len(report["engines"][ENGINES[0]]["series"]["t"]) - 1)
    for attempt in range(1, PLAY_ATTEMPTS + 1):
        other = body_attributes(run_chromium(chromium, ["--dump-dom"], url.replace("mode=side", "mode=overlay") +
                                             "&contacts=0&pick=p3_0&play=1").stdout)
        if other.get("data-frame") == last:
            break
        print(f"play=1, attempt {attempt}: stopped at frame {other.get('data-frame')!r}, expected {last}")
    check(other.get("data-mode") == "overlay", f"mode=overlay: data-mode is {other.get('data-mode')!r}")
    check(other.get("data-contacts") == "0", "contacts=0: contact points still drawn")
    check(other.get("data-picked") == "p3_0", f"pick=p3_0: data-picked is {other.get('data-picked')!r}")
    check(other.get("data-frame") == last,
          f"play=1: stopped at frame {other.get('data-frame')!r} in {PLAY_ATTEMPTS} attempts, expected {last}")
    check(other.get("data-frame") != last or other.get("data-energy-cursor") == "1.0000",
          f"the last frame: data-energy-cursor {other.get('data-energy-cursor')!r}, expected '1.0000'")

    # A page whose data does not add up says so on <body> rather than drawing nonsense.
    data_tag = re.search(r'(<script id="replay-data" type="application/json">)(.*?)(</script>)', html, re.DOTALL)
    data = json.loads(data_tag.group(2))
    data["engines"][1]["states"] = "AAAA"
    broken = os.path.join(work, "broken.html")
    with open(broken, "w", encoding="utf-8") as f:
        f.write(html[:data_tag.start(2)] + json.dumps(data).replace("</", "<\\/") + html[data_tag.end(2):])
    state = body_attributes(run_chromium(chromium, ["--dump-dom"], "file://" + broken).stdout).get("data-state", "")
    print("broken page:", state)
    check(state.startswith("error: ") and ENGINES[1] in state, f"a broken page reports data-state {state!r}")

    shot = os.path.join(work, "replay.png")
    run_chromium(chromium, [f"--screenshot={shot}", window], url)
    check(os.path.isfile(shot), "chromium wrote no screenshot")
    canvas = [int(v) for v in body.get("data-canvas", "0,0,0,0").split(",")]
    if os.path.isfile(shot):
        check_screenshot(shot, canvas, tints)
    check_first_frame_framing(boxpile, chromium, work, canvas)

    print("replay page: every check passed" if not failures else f"replay page: {len(failures)} check(s) failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
