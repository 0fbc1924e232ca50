"""Helpers shared by the scripts that regenerate docs from real runs (make-lab-report,
make-accuracy-cost): running boxpile, number formatting, and the generated tables of a Markdown
page, each between its markers

    <!-- SCRIPT: NAME -->  ...  <!-- end NAME -->
"""
import math
import re
import subprocess
import sys


def run(cmd, **kw):
    print("+ " + " ".join(cmd), file=sys.stderr)
    return subprocess.run(cmd, check=True, **kw)


def fmt(x, spec=".3g"):
    return "—" if x is None or (isinstance(x, float) and not math.isfinite(x)) else format(x, spec)


def replace_table(text, script, name, table, page):
    """The page's text with the table NAME (between the markers of SCRIPT) replaced."""
    pattern = re.compile(r"(<!-- %s: %s -->\n).*?(<!-- end %s -->)" % (script, name, name), re.S)
    if not pattern.search(text):
        sys.exit(f"{script}: {page} has no marker for the table {name}")
    return pattern.sub(lambda m: m.group(1) + table.rstrip() + "\n" + m.group(2), text)


def value_text(v):
    """A setting's value as a grid writes it: true, 1e+05, quickstep."""
    if isinstance(v, bool):
        return "true" if v else "false"
    return format(v, "g") if isinstance(v, float) else str(v)


def settings_text(settings):
    return " ".join(f"{k}={value_text(v)}" for k, v in settings.items())


def machine_line(doc, wall_seconds=None):
    """Where and how a sweep ran, from its sweep.json."""
    m = doc["machines"][0]
    load = ", ".join(f"{x:.2f}" for x in m["load_average"])
    line = (f"{len(doc['cells'])} cells, {doc['grid'].get('repetitions', 3)} timed runs each, {m['jobs']} process(es)"
            f" on {m['cpu']} ({m['cores']} cores), load average {load} when the sweep started")
    if wall_seconds is not None:
        line += f"; {wall_seconds:.0f} s of wall time"
    return line + "."
