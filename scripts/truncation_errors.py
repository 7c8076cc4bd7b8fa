#!/usr/bin/env python3
"""The error measure of docs/catenary.md ("Modal truncation"): each EN 50318 statistic of a run's
contact force (`mbfe stats --column force_strip --lowpass 20 --from T0 --to T1 --json`) minus the
reference's, as a share of the reference's mean contact force, the worst of the six, and the
contact wire's largest uplift at the given supports over the same window (the rise of each probe
above its value in the first row, as scripts/en50318.sh reads it) against the reference's.

The reference is one run, or two runs of a second-order integrator at steps h and 2h given as
FINE,COARSE: then each quantity is its Richardson extrapolation, fine + (fine - coarse) / 3, and
the script prints that correction, |fine - coarse| / 3, as the reference's own error estimate.

    scripts/truncation_errors.py --from 3.4272 --to 5.1552 \\
        --probes contact_wire@240,contact_wire@300,contact_wire@360 \\
        --reference ga_1e-4.csv,ga_2e-4.csv cap.csv truncated.csv ...

Each CSV must hold force_strip and the probe columns at evenly spaced rows (mbfe simulate
--probe ... --every N). Output: one line per run, errors in % (of the reference's mean force for
the statistics, of the reference's uplift for the uplift). Exit status 2 on a missing column.
"""
import argparse
import csv
import json
import os
import subprocess
import sys

KEYS = ["mean", "std", "statistical_max", "statistical_min", "max", "min"]
MBFE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "bin", "mbfe")


def quantities(path, t0, t1, probes):
    """The six statistics of force_strip and the largest uplift (mm) at the probes within [t0, t1]."""
    out = subprocess.run([MBFE, "stats", path, "--column", "force_strip", "--lowpass", "20", "--from", str(t0),
                          "--to", str(t1), "--json"], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit("truncation_errors: mbfe stats failed on %s: %s" % (path, out.stderr.strip()))
    q = json.loads(out.stdout)
    with open(path) as f:
        rows = list(csv.DictReader(f))
    missing = [p for p in probes if p not in rows[0]]
    if missing:
        print("truncation_errors: %s has no column %s (run it with --probe %s)" % (path, missing[0], ",".join(probes)),
              file=sys.stderr)
        sys.exit(2)
    start = {p: float(rows[0][p]) for p in probes}
    q["uplift"] = 1e3 * max(float(r[p]) - start[p] for r in rows if t0 <= float(r["t"]) <= t1 for p in probes)
    return q


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--from", dest="t0", type=float, required=True, help="start of the window (s)")
    ap.add_argument("--to", dest="t1", type=float, required=True, help="end of the window (s)")
    ap.add_argument("--probes", required=True, help="the supports' probe columns, comma-separated")
    ap.add_argument("--reference", required=True, help="REF.csv, or FINE.csv,COARSE.csv for Richardson")
    ap.add_argument("runs", nargs="+", help="the runs' CSVs")
    a = ap.parse_args()
    probes = a.probes.split(",")
    refs = a.reference.split(",")
    if len(refs) == 1:
        ref = quantities(refs[0], a.t0, a.t1, probes)
    else:
        fine, coarse = (quantities(p, a.t0, a.t1, probes) for p in refs)
        ref = {k: fine[k] + (fine[k] - coarse[k]) / 3 for k in KEYS + ["uplift"]}
        own = {k: 100 * abs(fine[k] - coarse[k]) / 3 / ref["mean"] for k in KEYS}
        print("reference: Richardson of %s and %s; its own error (%% of the mean force): %s; worst %.4f %%"
              % (refs[0], refs[1], ", ".join("%s %.4f" % (k, own[k]) for k in KEYS), max(own.values())))
    print("reference: " + ", ".join("%s %.3f" % (k, ref[k]) for k in KEYS) + " N; uplift %.3f mm" % ref["uplift"])
    print("run | worst statistic error | each (mean, std, stat. max, stat. min, max, min), % | uplift (mm), error")
    for path in a.runs:
        q = quantities(path, a.t0, a.t1, probes)
        err = {k: 100 * (q[k] - ref[k]) / ref["mean"] for k in KEYS}
        worst = max(KEYS, key=lambda k: abs(err[k]))
        print("%s | %+.3f %% (%s) | %s | %.3f, %+.3f %%" % (path, err[worst], worst, " ".join(
            "%+.3f" % err[k] for k in KEYS), q["uplift"], 100 * (q["uplift"] - ref["uplift"]) / ref["uplift"]))


if __name__ == "__main__":
    main()
