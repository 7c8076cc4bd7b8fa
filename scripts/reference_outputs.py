#!/usr/bin/env python3
"""Runs every shipped model of models/ (those SIMULATIONS and REPORTS below
name) and a test model of two joined spans, and compares the outputs with the
committed references in tests/reference_outputs/.

Most runs are a short stretch of the model's own run; some models are run
along several paths as well (--formulation augmented; --adjust off with
generalized_alpha).

A change that leaves the arithmetic alone gives bit-identical outputs; one that
only reorders sums (a refactor of the runtime) stays within 1e-9 of each
column's range. The check says which, run by run.

  scripts/reference_outputs.py                 # compare (what CI runs, as the test reference_outputs)
  scripts/reference_outputs.py --update        # rewrite the references from this build
  scripts/reference_outputs.py --only NAME ...  # some runs only

Each run writes a CSV (short runs, decimated, probes on large beams) and its
sidecar JSON; the reference keeps the CSV and the sidecar's status, steps, rows,
variant and contact/link tallies. `mbfe stability --json` and `mbfe modal --json`
of a few models are compared the same way (every number within 1e-9 of the
largest of its kind).
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REFERENCES = os.path.join(ROOT, "tests", "reference_outputs")
# Differences in summation order stay far below this fraction of a column's range.
RELATIVE_TOLERANCE = 1e-9
# Columns that are round-off by nature get an absolute floor instead: phi_abs,
# the constraint residual the partitioned formulation closes to ~1e-15 m, and
# the augmented formulation lets drift (its closure tolerance is 1e-10 m).
ABSOLUTE_FLOOR = {"phi_abs": 1e-12}  # m

M = "models/"
T = "tests/reference_outputs/models/"
# name, model, extra arguments of `mbfe simulate`
SIMULATIONS = [
    ("double_pendulum", M + "double_pendulum.yaml", ["--every", "10"]),
    ("cart_pendulum", M + "cart_pendulum.yaml", ["--every", "10"]),
    ("chain_20", M + "chain_20.yaml", ["--t-end", "0.2", "--every", "10"]),
    ("paper_beam_forward_euler", M + "paper_beam.yaml",
     ["--integrator", "forward_euler", "--step", "1.4e-5", "--t-end", "0.05", "--probe", "beam1@0.5,beam1@0.25",
      "--every", "50"]),
    ("paper_beam_original_alpha", M + "paper_beam.yaml",
     ["--adjust", "off", "--integrator", "generalized_alpha", "--step", "1e-4", "--t-end", "0.05",
      "--probe", "beam1@0.5"]),
    ("cantilever_trapezoid", M + "cantilever.yaml",
     ["--integrator", "trapezoid", "--step", "1e-4", "--t-end", "0.02", "--every", "10"]),
    ("paper_platform", M + "paper_platform.yaml",
     ["--t-end", "0.02", "--probe", "beam1@0.35,beam2@0.5", "--every", "20"]),
    ("paper_platform_augmented", M + "paper_platform.yaml",
     ["--t-end", "0.02", "--probe", "beam1@0.35,beam2@0.5", "--every", "20", "--formulation", "augmented"]),
    ("paper_platform_original_alpha", M + "paper_platform.yaml",
     ["--adjust", "off", "--integrator", "generalized_alpha", "--step", "1e-4", "--t-end", "0.05",
      "--probe", "beam1@0.35,beam2@0.5"]),
    ("double_pendulum_beam", M + "double_pendulum_beam.yaml", ["--t-end", "0.01", "--every", "20"]),
    ("bridge_moving_force", M + "bridge_moving_force.yaml", ["--probe", "deck@10", "--every", "10"]),
    ("bridge_moving_mass", M + "bridge_moving_mass.yaml", ["--probe", "deck@10", "--every", "10"]),
    ("bridge_moving_mass_nodal", M + "bridge_moving_mass.yaml",
     ["--probe", "deck@10", "--every", "10", "--formulation", "augmented"]),
    ("bridge_moving_mass_original_alpha", M + "bridge_moving_mass.yaml",
     ["--adjust", "off", "--integrator", "generalized_alpha", "--step", "1e-3", "--probe", "deck@10",
      "--every", "10"]),
    ("bridge_two_axle_vehicle", M + "bridge_two_axle_vehicle.yaml", ["--probe", "deck@10", "--every", "10"]),
    ("bridge_two_axle_vehicle_original_alpha", M + "bridge_two_axle_vehicle.yaml",
     ["--adjust", "off", "--integrator", "generalized_alpha", "--step", "1e-3", "--probe", "deck@10",
      "--every", "10"]),
    # The catenaries start from the state as written: their static start
    # (Newton on the adjusted wires' stiffness, whose low rank cancels most of
    # k* M) stops at ~1e-10 of the deflection, below the dynamics' digits but
    # above what a change of summation order must keep.
    ("pantograph_catenary_2span", M + "pantograph_catenary_2span.yaml",
     ["--start", "given", "--t-end", "0.2", "--probe", "contact_wire@60,contact_wire@66,messenger@66", "--every",
      "5"]),
    ("pantograph_catenary_2span_original_alpha", M + "pantograph_catenary_2span.yaml",
     ["--adjust", "off", "--integrator", "generalized_alpha", "--step", "2e-4", "--t-end", "0.05",
      "--probe", "contact_wire@60,contact_wire@66", "--every", "5"]),
    ("pantograph_catenary_300", M + "pantograph_catenary_300.yaml",
     ["--start", "given", "--t-end", "0.02", "--probe", "contact_wire@300,contact_wire@306"]),
    # The other shipped models, each over a short stretch of its run.
    ("chain_2", M + "chain_2.yaml", ["--t-end", "0.2", "--every", "10"]),
    ("chain_5", M + "chain_5.yaml", ["--t-end", "0.2", "--every", "10"]),
    ("chain_10", M + "chain_10.yaml", ["--t-end", "0.2", "--every", "10"]),
    ("four_bar", M + "four_bar.yaml", ["--t-end", "0.5", "--every", "10"]),
    ("four_bar_driven", M + "four_bar_driven.yaml", ["--t-end", "0.5", "--every", "10"]),
    ("double_pendulum_3d", M + "double_pendulum_3d.yaml", ["--t-end", "0.5", "--every", "10"]),
    ("slider_crank_3d", M + "slider_crank_3d.yaml", ["--t-end", "0.1", "--every", "10"]),
    ("arm7", M + "arm7.yaml", ["--t-end", "0.2", "--every", "10"]),
    ("spatial_chain_12", M + "spatial_chain_12.yaml",
     ["--integrator", "rk4", "--step", "1e-3", "--t-end", "0.05", "--every", "5"]),
    ("humanoid_35", M + "humanoid_35.yaml", ["--integrator", "rk4", "--step", "1e-3", "--t-end", "0.05", "--every", "5"]),
    ("bogie", M + "bogie.yaml", ["--t-end", "0.2", "--every", "10"]),
    ("paper_beam_a4.5", M + "paper_beam_a4.5.yaml",
     ["--integrator", "forward_euler", "--step", "1.4e-5", "--t-end", "0.01", "--probe", "beam1@0.5", "--every", "50"]),
    ("paper_beam_a5.5", M + "paper_beam_a5.5.yaml",
     ["--integrator", "forward_euler", "--step", "1.4e-5", "--t-end", "0.01", "--probe", "beam1@0.5", "--every", "50"]),
    ("paper_platform_a4.5", M + "paper_platform_a4.5.yaml",
     ["--t-end", "0.01", "--probe", "beam1@0.35,beam2@0.5", "--every", "50"]),
    ("paper_platform_a5.5", M + "paper_platform_a5.5.yaml",
     ["--t-end", "0.01", "--probe", "beam1@0.35,beam2@0.5", "--every", "50"]),
    ("bridge_hslm_20m", M + "bridge_hslm_20m.yaml", ["--t-end", "0.3", "--every", "10"]),
    ("vehicle_bridge_30m", M + "vehicle_bridge_30m.yaml", ["--t-end", "0.2", "--every", "10"]),
    ("vehicle_random_track", M + "vehicle_random_track.yaml", ["--t-end", "0.2", "--every", "10"]),
    ("pantograph_catenary_250", M + "pantograph_catenary_250.yaml",
     ["--start", "given", "--t-end", "0.02", "--probe", "contact_wire@300,contact_wire@306"]),
    ("two_span_joined", T + "two_span_joined.yaml", ["--start", "given", "--every", "5"]),
    ("two_span_joined_full_state", T + "two_span_joined.yaml", ["--start", "given", "--t-end", "0.01"]),
]
# name, command and model, each giving JSON on stdout, and the entries left
# out. A coupled model's linearised adjusted spectrum holds the cap's root as
# an eigenvalue of high multiplicity (every capped mode has it), which rounding
# splits into near pairs: it is not compared beyond the paper platform's limits.
REPORTS = [
    ("stability_paper_beam", ["stability", M + "paper_beam.yaml", "--json"], []),
    ("stability_paper_platform", ["stability", M + "paper_platform.yaml", "--json"], []),
    ("stability_double_pendulum", ["stability", M + "double_pendulum.yaml", "--json"], []),
    ("modal_paper_beam", ["modal", M + "paper_beam.yaml", "--json"], []),
    ("modal_bridge_two_axle_vehicle", ["modal", M + "bridge_two_axle_vehicle.yaml", "--json"], ["coupled"]),
]
SIDECAR_KEYS = ["status", "steps", "rows", "variant", "springs", "links", "message"]


def run(mbfe, args, env):
    proc = subprocess.run([mbfe] + args, cwd=ROOT, env=env, capture_output=True, text=True)
    return proc.returncode, proc.stdout, proc.stderr


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(v) for v in r] for r in rows[1:]]


def compare_tables(name, header, rows, ref_header, ref_rows):
    """Returns (identical, problems)."""
    problems = []
    if header != ref_header:
        return False, [f"{name}: columns differ: {header} vs {ref_header}"]
    if len(rows) != len(ref_rows):
        return False, [f"{name}: {len(rows)} rows, the reference has {len(ref_rows)}"]
    identical = True
    for c, column in enumerate(header):
        ref = [r[c] for r in ref_rows]
        got = [r[c] for r in rows]
        if got == ref:
            continue
        identical = False
        finite = [abs(v) for v in ref if math.isfinite(v)]
        span = (max(ref) - min(ref)) if finite else 0.0
        scale = max(span, 1e-3 * max(finite, default=0.0), 1e-300)
        allowed = max(RELATIVE_TOLERANCE * scale, ABSOLUTE_FLOOR.get(column, 0.0))
        worst = max(abs(a - b) for a, b in zip(got, ref))
        if not worst <= allowed:
            k = max(range(len(ref)), key=lambda i: abs(got[i] - ref[i]))
            problems.append(f"{name}: column '{column}' row {k + 1}: {got[k]!r} vs {ref[k]!r} "
                            f"(difference {worst:.3g}, allowed {allowed:.3g})")
    return identical, problems


def flatten_numbers(value, path="", out=None):
    out = {} if out is None else out
    if isinstance(value, dict):
        for k, v in value.items():
            flatten_numbers(v, f"{path}.{k}", out)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            flatten_numbers(v, f"{path}[{i}]", out)
    else:
        out[path] = value
    return out


def compare_json(name, got, ref):
    a, b = flatten_numbers(got), flatten_numbers(ref)
    if a.keys() != b.keys():
        return False, [f"{name}: entries differ: {sorted(set(a) ^ set(b))[:5]}"]
    numbers = [abs(v) for v in b.values() if isinstance(v, (int, float)) and not isinstance(v, bool)
               and math.isfinite(v)]
    scale = max(numbers, default=1.0)
    identical, problems = True, []
    for key in b:
        x, y = a[key], b[key]
        if x == y:
            continue
        identical = False
        if isinstance(x, (int, float)) and isinstance(y, (int, float)) and not isinstance(x, bool):
            # each number against the largest of its own kind (the last path component)
            if abs(x - y) <= RELATIVE_TOLERANCE * max(abs(y), 1e-12 * scale):
                continue
        problems.append(f"{name}: {key}: {x!r} vs {y!r}")
    return identical, problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--update", action="store_true", help="rewrite the references from this build")
    parser.add_argument("--only", nargs="*", help="run these names only")
    parser.add_argument("--mbfe", default=os.environ.get("MBFE_CLI", os.path.join(ROOT, "build", "bin", "mbfe")))
    args = parser.parse_args()
    env = dict(os.environ)
    env.setdefault("MBFE_CACHE_DIR", os.path.join(ROOT, "build", "test-cache"))
    os.makedirs(REFERENCES, exist_ok=True)
    failures, summary = [], []
    # A model added to models/ without a run here would go unchecked.
    listed = {model for _, model, _ in SIMULATIONS}
    for f in sorted(os.listdir(os.path.join(ROOT, "models"))):
        if f.endswith(".yaml") and M + f not in listed:
            failures.append(f"models/{f}: no run in SIMULATIONS (add one, then --update)")
    with tempfile.TemporaryDirectory() as tmp:
        for name, model, extra in SIMULATIONS:
            if args.only and name not in args.only:
                continue
            out = os.path.join(tmp, name + ".csv")
            code, _, err = run(args.mbfe, ["simulate", model, "--quiet", "--out", out] + extra, env)
            if code != 0:
                failures.append(f"{name}: mbfe simulate exited {code}: {err.strip()}")
                continue
            with open(out + ".json") as f:
                sidecar = json.load(f)
            kept = {k: sidecar[k] for k in SIDECAR_KEYS if k in sidecar}
            ref_csv = os.path.join(REFERENCES, name + ".csv")
            ref_json = os.path.join(REFERENCES, name + ".json")
            if args.update:
                with open(out) as src, open(ref_csv, "w") as dst:
                    dst.write(src.read())
                with open(ref_json, "w") as f:
                    json.dump(kept, f, indent=1, sort_keys=True)
                    f.write("\n")
                summary.append(f"{name}: written")
                continue
            if not os.path.exists(ref_csv):
                failures.append(f"{name}: no reference (run with --update)")
                continue
            header, rows = read_csv(out)
            ref_header, ref_rows = read_csv(ref_csv)
            same_table, problems = compare_tables(name, header, rows, ref_header, ref_rows)
            with open(ref_json) as f:
                same_side, side_problems = compare_json(name + " (sidecar)", kept, json.load(f))
            failures += problems + side_problems
            if not problems and not side_problems:
                summary.append(f"{name}: {'bit-identical' if same_table and same_side else 'within tolerance'}")
        for name, command, left_out in REPORTS:
            if args.only and name not in args.only:
                continue
            code, out, err = run(args.mbfe, command, env)
            if code != 0:
                failures.append(f"{name}: mbfe {command[0]} exited {code}: {err.strip()}")
                continue
            got = json.loads(out)
            for key in left_out:
                got.pop(key, None)
            ref_path = os.path.join(REFERENCES, name + ".json")
            if args.update:
                with open(ref_path, "w") as f:
                    json.dump(got, f, indent=1, sort_keys=True)
                    f.write("\n")
                summary.append(f"{name}: written")
                continue
            if not os.path.exists(ref_path):
                failures.append(f"{name}: no reference (run with --update)")
                continue
            with open(ref_path) as f:
                same, problems = compare_json(name, got, json.load(f))
            failures += problems
            if not problems:
                summary.append(f"{name}: {'bit-identical' if same else 'within tolerance'}")
    for line in summary:
        print(line)
    for line in failures:
        print("FAILED " + line)
    print(f"reference outputs: {len(summary)} ok, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
