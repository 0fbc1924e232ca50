#!/usr/bin/env python3
"""The docs' tables of defaults and ranges against the code that declares them, and the README's
cost ratios against docs/performance.md's tables. Fails, naming the page and the row, on the first
disagreements it finds (all of them are listed).

  - the scene loader's bounds and the caps on work (sim/limits.hpp) in docs/reliability.md's tables and
    docs/scene-format.md's tables and paragraph of bounds (bodies, damping, time);
  - `boxpile settings`' defaults and ranges of our engine in docs/scene-format.md's `solver` and
    `collision` tables;
  - `boxpile scene --help`'s defaults in docs/scene-format.md's table of kinds;
  - `boxpile settings`' defaults in the tables and lists written by hand: MuJoCo's and the
    WebAssembly engines' (Jolt, Rapier, MuJoCo 3.14) in docs/reference-engines.md,
    and the penalty method's derived settings (with sim/solver/penalty_parameters.hpp's constants)
    in docs/penalty.md;
  - the ratios of our step to Bullet's quoted in the README and in docs/performance.md's prose (aim 1,
    the round in motion, the summary of aims) against that page's "steps" and "moving" tables, so
    that a rerun of scripts/perf-report that changes them fails here until the prose follows.

(The pages that copy `boxpile settings`' tables whole are checked by tests/test_registry.cpp.)

Usage: doc_tables_test.py BOXPILE SOURCE_DIR"""
import re
import subprocess
import sys

boxpile, root = sys.argv[1], sys.argv[2]
failures = []


def read(rel):
    with open(f"{root}/{rel}", encoding="utf-8") as f:
        return f.read()


def sci(v):
    """A bound as the docs write it: 1e-6, 5e-4, 1e3."""
    mantissa, exponent = f"{v:.0e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def row(page, text, key):
    """The table row of PAGE whose first cell is KEY."""
    rows = [line for line in text.splitlines() if line.startswith(f"| {key} |")]
    if not rows:
        failures.append(f"{page}: no row {key}")
        return ""
    return rows[0]


def expect(page, where, haystack, needle):
    if needle not in haystack:
        failures.append(f"{page}: {where} should say {needle!r} (from the code or the table it cites): {haystack.strip()[:200]!r}")


# --- the loader's bounds --------------------------------------------------------------------------
limits = {m.group(1): float(m.group(2).replace("'", ""))
          for m in re.finditer(r"inline constexpr \w+(?:::\w+)? (k\w+) = ([-0-9.e']+)", read("sim/limits.hpp"))}
shifted = re.search(r"kDefaultMaxInputBytes = std::size_t\{1\} << (\d+);", read("sim/limits.hpp"))
if shifted:
    limits["kDefaultMaxInputBytes"] = float(1 << int(shifted.group(1)))
L = {k: sci(v) for k, v in limits.items()}

page = "docs/reliability.md"
rel = read(page)
for key, needle in [
        ("`mass`", f"{L['kMinMass']} .. {L['kMaxMass']} kg"),
        ("`half_extents`", f"{L['kMinHalfExtent']} .. {L['kMaxHalfExtent']} m"),
        ("`half_extents` of a contact query", f"{L['kMinQueryHalfExtent']} .. {L['kMaxHalfExtent']} m"),
        ("`velocity`", f"norm up to {L['kMaxSpeed']} m/s"),
        ("`angular_velocity`", f"norm up to {L['kMaxAngularSpeed']} rad/s"),
        ("coordinates (`position`, `offset`, wire ends, ground `offset`)", f"each component up to {L['kMaxCoordinate']} m"),
        ("`gravity`", f"each component up to {L['kMaxGravity']} m/s²"),
        ("`orientation`, ground `normal`", f"each component up to {L['kMaxDirectionComponent']}"),
        ("`friction`", f"0 .. {L['kMaxFriction']}"),
        ("`damping` rates", f"0 .. {L['kMaxDampingRate']} 1/s"),
        ("margins and slops", f"0 .. {L['kMaxMargin']} m"),
        ("`time.dt`, `--dt`", f"(0, {limits['kMaxTimeStep']:g}] s")]:
    expect(page, f"row {key}", row(page, rel, key), needle)

# docs/reliability.md's caps on work (their defaults and flags' limits in sim/limits.hpp).
def grouped(n):
    return f"{int(n):,}"


caps = rel[rel.find("## Caps on work"):]
for key, needle in [
        ("steps of one run (duration / dt; the penalty method's substeps each count as a step)",
         f"| {grouped(limits['kDefaultMaxSteps'])} "),
        ("steps of one run (duration / dt; the penalty method's substeps each count as a step)",
         f"(up to {sci(limits['kMaxRepresentableSteps'])})"),
        ("bodies in a scene", f"| {grouped(limits['kDefaultMaxBodies'])} |"),
        ("pairs of bodies whose bounding boxes overlap: at the start (counted through the broadphase before any engine is"
         " handed the scene) and in every step of our engine", f"| {grouped(limits['kDefaultMaxPairs'])} |"),
        ("bytes of an input file (scene, query, grid, recording, sweep report); only regular files are read",
         f"| {int(limits['kDefaultMaxInputBytes']) >> 30} GiB |" if int(limits['kDefaultMaxInputBytes']) % (1 << 30) == 0
         else str(int(limits['kDefaultMaxInputBytes'])))]:
    expect("docs/reliability.md", f"the caps' row {key[:40]}...", row("docs/reliability.md", caps, key), needle)

page = "docs/scene-format.md"
fmt = read(page)
body_rows = fmt.split("| `name` | string | required | | not empty or only white space")[1]
expect(page, "row `mass`", row(page, body_rows, "`mass`"), f"{L['kMinMass']} to {L['kMaxMass']}")
for line in [l for l in fmt.splitlines() if l.startswith("| `half_extents` |")]:
    expect(page, "row `half_extents`", line, f"each {L['kMinHalfExtent']} to {L['kMaxHalfExtent']}")
expect(page, "row `position`", row(page, body_rows, "`position`"), f"within ±{L['kMaxCoordinate']}")
expect(page, "row `orientation`", row(page, body_rows, "`orientation`"), f"within ±{L['kMaxDirectionComponent']}")
expect(page, "row `normal`", row(page, fmt, "`normal`"), f"within ±{L['kMaxDirectionComponent']}")
expect(page, "row `velocity`", row(page, body_rows, "`velocity`"), f"norm ≤ {L['kMaxSpeed']}")
expect(page, "row `angular_velocity`", row(page, body_rows, "`angular_velocity`"), f"norm ≤ {L['kMaxAngularSpeed']}")
expect(page, "row `friction`", row(page, fmt, "`friction`"), f"0 to {L['kMaxFriction']}")
damping_rows = fmt[fmt.find("### `damping`"):]
for key in ("`linear`", "`angular`"):
    expect(page, f"`damping`'s row {key}", row(page, damping_rows, key), f"0 to {L['kMaxDampingRate']}")
time_rows = fmt[fmt.find("### `time`"):]
expect(page, "`time`'s row `dt`", row(page, time_rows, "`dt`"), f"in (0, {limits['kMaxTimeStep']:g}]")
expect(page, "`time`'s row `duration`", row(page, time_rows, "`duration`"),
       f"(10^{len(str(int(limits['kDefaultMaxSteps']))) - 1} by default, `--max-steps`)"
       if limits["kDefaultMaxSteps"] == 10 ** (len(str(int(limits["kDefaultMaxSteps"]))) - 1) else str(limits["kDefaultMaxSteps"]))
max_boxes = re.search(r"inline constexpr int kMaxBoxesPerBody = (\d+);", read("sim/body.hpp")).group(1)
expect(page, "row `boxes`", row(page, body_rows, "`boxes`"), f"1 to {max_boxes} boxes (`kMaxBoxesPerBody`)")
bounds = re.search(r"measured in \[reliability\.md\]\(reliability\.md\):(.*?)\. A scene", fmt, re.S)
if not bounds:
    failures.append(f"{page}: no paragraph of bounds (\"measured in [reliability.md](reliability.md): ...\")")
else:
    para = " ".join(bounds.group(1).split())
    for needle in [f"masses {L['kMinMass']} to {L['kMaxMass']} kg",
                   f"half extents {L['kMinHalfExtent']} to {L['kMaxHalfExtent']} m",
                   f"speeds and angular speeds up to {L['kMaxSpeed']} m/s",
                   f"coordinates within ±{L['kMaxCoordinate']} m",
                   f"gravity components within ±{L['kMaxGravity']} m/s²",
                   f"damping rates up to {L['kMaxDampingRate']} 1/s",
                   f"margins up to {L['kMaxMargin']} m"]:
        expect(page, "the paragraph of bounds", para, needle)
    after = " ".join(fmt[bounds.end():bounds.end() + 200].split())
    expect(page, "the paragraph of bounds", after, f"at most {grouped(limits['kDefaultMaxBodies'])} bodies unless `--max-bodies`")
if limits["kMaxSpeed"] != limits["kMaxAngularSpeed"]:
    failures.append(f"{page}: the paragraph of bounds gives one limit for speeds and angular speeds; the code has two")

# --- `boxpile scene`'s defaults --------------------------------------------------------------------
help_text = subprocess.run([boxpile, "scene", "--help"], check=True, capture_output=True, text=True).stdout
options = {}  # option -> its description, joined over its lines
current = None
for line in help_text.splitlines():
    m = re.match(r"\s+(--\w+)(.*)", line)
    if m:  # "  --seed UINT                 heap: the seed ...": the description after 2+ spaces
        current = m.group(1)
        parts = re.split(r"\s{2,}", m.group(2).strip(), maxsplit=1)
        options[current] = parts[1] if len(parts) > 1 else ""
    elif current and line.startswith(" " * 20):
        options[current] += " " + line.strip()
defaults = {}  # (kind, option) -> default as help prints it
for opt, desc in options.items():
    for part in desc.split(";"):
        m = re.match(r"\s*(\w+): .*\(default ([^)]+)\)", part)
        if m:
            defaults[(m.group(1), opt)] = m.group(2)
gap = re.search(r"\((.*)\)", options.get("--gap", ""))
if gap:
    for part in gap.group(1).split(";"):
        kinds, value = part.split(":")
        for kind in kinds.split(","):
            defaults[(kind.strip(), "--gap")] = value.strip().replace("--size", "size")
page = "docs/scene-format.md"
kinds_help = re.findall(r"^\s{30,}(\w+): ", help_text.split("Options:")[0], re.M)
for kind in kinds_help:
    line = row(page, fmt, f"`{kind}`")
    cell = line.split("|")[2] if line else ""
    documented = {}
    for m in re.finditer(r"`(--\w+)(?: ([^`]+))?`(?: ([^,|]+))?", cell):
        documented[m.group(1)] = (m.group(2) or m.group(3) or "").strip()
    wanted = {opt: v for (k, opt), v in defaults.items() if k == kind}
    if documented != wanted:
        failures.append(f"{page}: the row of `{kind}` gives defaults {documented}; `boxpile scene --help` {wanted}")

# --- engines' settings tables written by hand ---------------------------------------------------------
settings_text = subprocess.run([boxpile, "settings"], check=True, capture_output=True, text=True).stdout
settings = {}  # engine -> setting -> (default, unit)
for block in re.split(r"(?m)^(?=### )", settings_text):
    if not block.startswith("### "):
        continue
    engine = block.split("\n", 1)[0][4:].strip()
    settings[engine] = {}
    for line in block.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 5 and cells[0].startswith("`"):
            settings[engine][cells[0].strip("`")] = (cells[2].strip('"'), cells[3])


def same_value(doc, code):
    try:
        return float(doc) == float(code)
    except ValueError:
        return doc.lower() == code.lower()


def hand_table(page, text, heading):
    """The rows (cells) of the first table after HEADING."""
    start = text.find(heading)
    if start < 0:
        failures.append(f"{page}: no section {heading!r}")
        return []
    rows = []
    for line in text[start:].splitlines()[1:]:
        if line.startswith("|"):
            rows.append([c.strip() for c in line.strip().strip("|").split("|")])
        elif rows:
            break
    return rows[2:]


# docs/reference-engines.md's MuJoCo table: each setting's default (several settings to a row,
# their defaults comma-separated) is `boxpile settings`' own.
page = "docs/reference-engines.md"
ref = read(page)
listed = set()
for cells in hand_table(page, ref, "### Settings: `MujocoSettings`"):
    names = re.findall(r"`(\w+)`", cells[0])
    values = [v.strip() for v in cells[1].split(",")]
    if len(names) != len(values):
        failures.append(f"{page}: MuJoCo's row {cells[0]} gives {len(values)} defaults for {len(names)} settings")
        continue
    for name, value in zip(names, values):
        listed.add(name)
        code = settings.get("mujoco", {}).get(name)
        if code is None:
            failures.append(f"{page}: MuJoCo's table lists `{name}`, which `boxpile settings` has not")
        elif not same_value(value, code[0]):
            failures.append(f"{page}: MuJoCo's `{name}` defaults to {value} there, to {code[0]} in `boxpile settings`")
missing = set(settings.get("mujoco", {})) - listed - {"dt"}
if missing:
    failures.append(f"{page}: MuJoCo's table lacks {sorted(missing)} (in `boxpile settings`)")

# docs/scene-format.md's `solver` and `collision` tables: the scene keys are our engine's settings
# (`collision.margin` is `collision_margin`), each with `boxpile settings`' default and range.
def values_range(values):
    """ "integer in [1, 64]" -> "[1, 64]"; a number range as the docs write it (1e-06 kept)."""
    m = re.search(r"in ([\[(][^\])]*[\])])", values)
    return m.group(1) if m else None


page = "docs/scene-format.md"
own = settings.get("own", {})
own_values = {}
for line in settings_text.split("### own\n", 1)[-1].split("\n### ", 1)[0].splitlines():
    cells = [c.strip() for c in line.strip().strip("|").split("|")]
    if len(cells) == 5 and cells[0].startswith("`"):
        own_values[cells[0].strip("`")] = cells[1]
for heading, rename in [("### `solver`", {}), ("### `collision`", {"margin": "collision_margin"})]:
    rows = hand_table(page, fmt, heading)
    if not rows:
        continue
    keys = set()
    for cells in rows:
        key = rename.get(cells[0].strip("`"), cells[0].strip("`"))
        if key not in own:
            if key != "method":
                failures.append(f"{page}: {heading}'s `{cells[0]}` is no setting of `boxpile settings`' own")
            continue
        keys.add(key)
        default, code_default = cells[2].strip("`").strip('"'), own[key][0]
        if code_default == "derived from the scene":
            if default != "derived" and default not in own:  # derived, or another setting's value
                failures.append(f"{page}: {heading}'s `{key}` defaults to {default}; `boxpile settings`: derived")
        elif not same_value(default, code_default):
            failures.append(f"{page}: {heading}'s `{key}` defaults to {default}, `boxpile settings` {code_default}")
        wanted = values_range(own_values.get(key, ""))
        if wanted and f"in {wanted}" not in cells[4]:
            failures.append(f"{page}: {heading}'s `{key}` should say 'in {wanted}' (`boxpile settings`): {cells[4][:80]!r}")
    missing = {k for k in own if k != "dt" and (heading == "### `collision`") == (k in ("reduce_to_four", "collision_margin", "reuse_contacts"))} - keys
    if missing:
        failures.append(f"{page}: {heading} lacks {sorted(missing)} (in `boxpile settings`' own)")

# docs/reference-engines.md's list of the WebAssembly engines' defaults: "`key` value" pairs (a
# group of switches "(all on)", "on"/"off" for true/false), single precision read as float32.
def close(doc, code):
    words = {"on": "true", "off": "false"}
    doc = words.get(doc.lower(), doc)
    try:
        a, b = float(doc), float(code)
        return abs(a - b) <= 1e-6 * max(abs(a), abs(b))
    except ValueError:
        return doc.lower() == code.lower()


section = ref[ref.find("### Settings (hello's defaults"):]
section = section[:section.find("\n### ", 5)]
for title, engine in [("Jolt", "jolt"), ("Rapier", "rapier"), ("MuJoCo", "mujoco-wasm")]:
    item = re.search(r"^- \*\*%s\*\*(.*?)(?=^- \*\*|\Z)" % title, section, re.S | re.M)
    if not item:
        failures.append(f"{page}: no item for {title} under \"Settings (hello's defaults ...)\"")
        continue
    text = " ".join(item.group(1).split())
    found = {}
    for group in re.finditer(r"((?:`\w+`,? )+)\(all on\)", text):
        for key in re.findall(r"`(\w+)`", group.group(1)):
            found[key] = "true"
    for m in re.finditer(r"`(\w+)` ([-0-9.e]+|[A-Za-z]+)", text):
        found.setdefault(m.group(1), m.group(2).rstrip("."))
    code = settings.get(engine, {})
    for key, value in found.items():
        if key in code and not close(value, code[key][0]):
            failures.append(f"{page}: {title}'s `{key}` defaults to {value} there, to {code[key][0]} in `boxpile settings`")
    missing = [k for k in code if k != "dt" and not k.startswith("solimp_") and k not in found]
    if missing:
        failures.append(f"{page}: {title}'s list lacks {missing} (in `boxpile settings`)")

# docs/penalty.md's table: the settings of the penalty method derived from the scene, their units,
# and the constants the page derives them with (sim/solver/penalty_parameters.hpp).
page = "docs/penalty.md"
pen = read(page)
rows = {c[0].strip("`"): c for c in hand_table(page, pen, "## Settings and their defaults")}
derived = {k: v for k, v in settings.get("own-penalty", {}).items() if v[0] == "derived from the scene"}
if set(rows) != set(derived):
    failures.append(f"{page}: the table lists {sorted(rows)}; `boxpile settings` derives {sorted(derived)} from the scene")
for key in set(rows) & set(derived):
    doc_unit = rows[key][1].replace("·", " ").replace(" per contact point", "").strip() or "—"
    if doc_unit != derived[key][1]:
        failures.append(f"{page}: `{key}`'s unit is {rows[key][1]!r} there, {derived[key][1]!r} in `boxpile settings`")
penalty = {m.group(1): float(m.group(2)) for m in re.finditer(
    r"inline constexpr \w+ (k\w+) = ([-0-9.e]+)", read("sim/solver/penalty_parameters.hpp"))}
if "substeps" in rows:
    expect(page, "row `substeps`", rows["substeps"][2], f"≤ {penalty['kStabilityFraction']:g} ×")
expect(page, "the paragraph on stiffness", pen, f"d = {penalty['kDefaultRestingOverlap'] * 1e3:g} mm (`kDefaultRestingOverlap`")
expect(page, "the paragraph on stiffness", pen, f"sinks by\nd = M g / ({penalty['kPointsPerSupport']:g} k)")

# --- the README's cost ratios ------------------------------------------------------------------------
perf = read("docs/performance.md")


def table(name):
    block = re.search(r"<!-- perf-report: %s -->\n(.*?)<!-- end %s -->" % (name, name), perf, re.S).group(1)
    rows, column = {}, None
    for line in block.splitlines():
        if not line.startswith("|"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if cells[0] == "scene":  # the header names the column of ours over Bullet's
            column = next((i for i, c in enumerate(cells) if c.startswith("ours / Bullet")), None)
            continue
        if column is None or cells[0].startswith("---") or len(cells) <= column or not cells[column].strip("*"):
            continue
        rows[cells[0]] = cells[column].strip("*")
    return rows


steps, moving = table("steps"), table("moving")
resting = [float(v) for k, v in steps.items() if k.startswith(("`stack_10`", "`pyramid", "Jenga"))]
rammed = [v for k, v in moving.items() if "rammed" in k]
others = [float(v) for k, v in moving.items() if not k.startswith("`pile_100`") and "rammed" not in k]
readme = " ".join(read("README.md").split())
page = "README.md"
for needle in [f"the Jenga tower ({min(resting):.2f}-{max(resting):.2f} of Bullet's step)",
               f"more on the pile of 100 boxes ({steps['`pile_100`']})",
               f"in motion it costs {next(v for k, v in moving.items() if k.startswith('`pile_100`'))} of Bullet's step on the pile of 100 boxes",
               f"{rammed[0] if rammed else '?'} on the rammed cube",
               f"{min(others):.2f}-{max(others):.2f} on the bone scene and the falling heaps"]:
    expect(page, "the paragraph \"What it costs against ODE and Bullet\"", readme, needle)
if max(resting) >= 1 or float(steps["`pile_100`"]) <= 1:
    failures.append(f"{page}: the README says ours costs less than Bullet at rest on the stacks, pyramids and Jenga"
                    f" tower and more on the pile; docs/performance.md's table no longer shows that")

# docs/performance.md's own prose on the same tables.
page = "docs/performance.md"
flat = " ".join(perf.split())
ratio = {k.split(" (")[0]: v for k, v in list(steps.items())}
moving_ratio = {k.split(" (")[0]: v for k, v in moving.items()}
for needle in [
        f"met on `stack_10` ({ratio['`stack_10`']}), the pyramids ({ratio['`pyramid_6`']} and {ratio['`pyramid_10`']}) and"
        f" the Jenga tower ({ratio['Jenga tower']}), not met on `pile_100` ({ratio['`pile_100`']})",
        f"ours / Bullet {ratio['`stack_10`']} (`stack_10`), {ratio['`pile_100`']} (`pile_100`), {ratio['`pyramid_6`']}"
        f" (`pyramid_6`), {ratio['`pyramid_10`']} (`pyramid_10`), {ratio['Jenga tower']} (`jenga`)",
        f"ours costs {moving_ratio['`pile_100`']} of Bullet's step on `pile_100`, {rammed[0] if rammed else '?'} on the rammed"
        f" cube, {moving_ratio['the bone scene']} on the bone scene, {moving_ratio['a heap of 300 falling boxes']} on the heap"
        f" of 300 and {moving_ratio['a heap of 1,000 falling boxes']} on the heap of 1,000"]:
    expect(page, "the prose on the steps tables", flat, needle)
dearer = [k for k, v in moving.items() if float(v) > 1.05]
if len(dearer) == len(moving):
    expect(page, "the section on scenes in motion", flat, "ours is dearer than Bullet on every scene")
    expect(page, "README's paragraph on cost", readme, "in motion Bullet is the cheaper engine on every scene")
else:
    failures.append(f"{page}: says ours is dearer than Bullet on every scene in motion; the moving table: {moving}")

for f in failures:
    print("doc_tables_test: " + f, file=sys.stderr)
print(f"doc_tables_test: {len(failures)} disagreement(s)")
sys.exit(1 if failures else 0)
