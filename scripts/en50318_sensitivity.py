#!/usr/bin/env python3
"""How the EN 50318 quantities move when one uncertain parameter changes.

    scripts/en50318_sensitivity.py            (about 7 minutes on 2 cores)

Each variant is the parameter table models/catenary/en50318_2002.json with one
value changed: a value tagged [A] or [U] in docs/validation-en50318.md, or one
the open sources disagree on. For each, both speeds run as the models ship
(adjusted, RK4 at 1e-3 s, the two speeds side by side) and the 16 quantities
are computed as scripts/en50318.sh computes them. Prints a Markdown table (the
one in docs/validation-en50318.md, "What moves the quantities outside"). No
variant is a proposal for the model: the shipped table stays as its sources
give it.
"""
import copy
import csv
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TABLE = os.path.join(ROOT, "models", "catenary", "en50318_2002.json")
MBFE = os.path.join(ROOT, "build", "bin", "mbfe")

# EN 50318:2002 acceptance ranges (docs/validation-en50318.md gives the source).
RANGES = {
    "mean": {250: (110, 120), 300: (110, 120)},
    "std": {250: (26, 31), 300: (32, 40)},
    "statistical_max": {250: (190, 210), 300: (210, 230)},
    "statistical_min": {250: (20, 40), 300: (-5, 20)},
    "max": {250: (175, 210), 300: (190, 225)},
    "min": {250: (50, 75), 300: (30, 55)},
    "uplift": {250: (48, 55), 300: (55, 65)},
    "loss_percent": {250: (0, 0), 300: (0, 0)},
}

# (label, key path, value): one change each.
VARIANTS = [
    ("as shipped", None, None),
    ("steady arm 100 N/m (a third)", ("steady_arm", "stiffness"), 100.0),
    ("steady arm 3,000 N/m (10x)", ("steady_arm", "stiffness"), 3000.0),
    ("steady arm mass 0.5 kg (half)", ("steady_arm", "mass"), 0.5),
    ("clamp masses swapped", ("clamps",), {"contact_wire": 0.165, "messenger": 0.195}),
    ("damping ratio 0.01 (2x)", ("damping_ratio",), 0.01),
    ("pre-sag 27.5 mm (half)", ("presag",), 0.0275),
    ("pre-sag 0 mm", ("presag",), 0.0),
]


def changed(table, path, value):
    t = copy.deepcopy(table)
    if path is None:
        return t
    node = t
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    return t


def quantities(csv_path, table, kmh):
    """The 16 quantities' 8 at one speed, as scripts/en50318.sh computes them."""
    span, start = table["span_length"], table["start"]
    first, last = table["analysis_spans"][0], table["analysis_spans"][-1]
    x0, x1 = (first - 1) * span, last * span
    v = kmh / 3.6
    t0, t1 = (x0 - start) / v, (x1 - start) / v
    stats = json.loads(subprocess.run(
        [MBFE, "stats", csv_path, "--column", "force_strip", "--lowpass", "20", "--from", str(t0), "--to", str(t1),
         "--json"], check=True, capture_output=True, text=True).stdout)
    probes = ["contact_wire@%g" % (k * span) for k in range(first - 1, last + 1)]
    rows = list(csv.DictReader(open(csv_path)))
    rest = {p: float(rows[0][p]) for p in probes}
    stats["uplift"] = max(float(r[p]) - rest[p] for r in rows if t0 <= float(r["t"]) <= t1 for p in probes) * 1e3
    return stats


def run_variant(table, work):
    path = os.path.join(work, "table.json")
    json.dump(table, open(path, "w"))
    span = table["span_length"]
    first, last = table["analysis_spans"][0], table["analysis_spans"][-1]
    probes = ",".join("contact_wire@%g" % (k * span) for k in range(first - 1, last + 1))
    jobs = {}
    for kmh in (250, 300):
        model = os.path.join(work, "m%d.yaml" % kmh)
        subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "make_catenary.py"), path, "--speed", str(kmh),
                        "--name", "pantograph_catenary_%d" % kmh, "-o", model], check=True)
        out = os.path.join(work, "run%d.csv" % kmh)
        jobs[kmh] = (subprocess.Popen([MBFE, "simulate", model, "--probe", probes, "--out", out, "--quiet"],
                                      stderr=subprocess.PIPE, text=True), out)
    got = {}
    for kmh, (proc, out) in jobs.items():
        _, err = proc.communicate()
        if proc.returncode != 0:
            sys.exit("en50318_sensitivity: %d km/h failed:\n%s" % (kmh, err))
        got[kmh] = quantities(out, table, kmh)
    return got


def cell(key, kmh, value):
    lo, hi = RANGES[key][kmh]
    mark = "" if lo - 1e-9 <= value <= hi + 1e-9 else "**"
    return "%s%.1f%s" % (mark, value, mark)


def main():
    if not os.access(MBFE, os.X_OK):
        sys.exit("en50318_sensitivity: build first (scripts/build.sh)")
    base = json.load(open(TABLE))
    shown = ["std", "statistical_max", "statistical_min", "max", "min", "uplift"]
    head = ["variant"] + ["%s %d" % (k, kmh) for kmh in (250, 300) for k in ("std", "stat max", "stat min", "max",
                                                                            "min", "uplift")] + ["inside"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for label, path, value in VARIANTS:
        with tempfile.TemporaryDirectory() as work:
            got = run_variant(changed(base, path, value), work)
        inside = sum(RANGES[k][kmh][0] - 1e-9 <= got[kmh][k] <= RANGES[k][kmh][1] + 1e-9
                     for kmh in (250, 300) for k in RANGES)
        cells = [cell(k, kmh, got[kmh][k]) for kmh in (250, 300) for k in shown]
        print("| %s | %s | %d of 16 |" % (label, " | ".join(cells), inside), flush=True)


if __name__ == "__main__":
    main()
