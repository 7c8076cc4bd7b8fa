"""Steps a coupled model from Python and adds a load between steps (docs/python.md).

    python3 examples/python/stepping_load.py [LOADED.csv]

The 1000 kg wheel of models/bridge_moving_mass.yaml crosses the 20 m deck; at
t = 0.3 s the script adds a harmonic point load at midspan,
f(t) = -5 kN sin(40 rad/s (t - 0.3 s)), and steps on to the end of the run,
reading the outputs every 0.01 s. It then runs
examples/stepping_load/bridge_with_load.yaml, the same model with that load
written into the file, in one call, and checks the two agree to round-off
(exit status 1 if they do not). Given LOADED.csv, the output of
`mbfe simulate examples/stepping_load/bridge_with_load.yaml --every 10 --out LOADED.csv`,
it checks the stepped run against the command line's as well.
"""
import csv
import math
import os
import sys

import numpy as np

import mbfe

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..", "..")

LOAD_START, AMPLITUDE, OMEGA, MIDSPAN = 0.3, -5.0e3, 40.0, 10.0  # s, N, rad/s, m
ROW_EVERY = 0.01  # s
# The load enters the same force vector by two routes summed in another order.
ROUND_OFF = 1e-12  # of each column's largest magnitude

model = mbfe.load(os.path.join(root, "models", "bridge_moving_mass.yaml"))
sim = model.simulator()  # the model's simulation block: RK4, 1e-3 s, to 1.2 s
rows = [sim.outputs()]
k = 0
while not sim.finished:
    k += 1
    t = k * ROW_EVERY
    if abs(sim.time - LOAD_START) < 0.5 * sim.step:
        sim.set_beam_load("deck", MIDSPAN, lambda time: AMPLITUDE * math.sin(OMEGA * (time - LOAD_START)))
    sim.advance_to(t)
    rows.append(sim.outputs())
report = sim.report()
if report["status"] != "completed":
    sys.exit(f"stepping_load: {report['message']}")
stepped = {name: np.array([row[name] for row in rows]) for name in sim.columns}
print(f"{report['steps']} steps; largest tyre force {np.abs(stepped['force_tyre']).max():.0f} N")

whole = mbfe.load(os.path.join(root, "examples", "stepping_load", "bridge_with_load.yaml")).simulate(every=10)
worst = max(np.abs(stepped[c] - whole[c]).max() / max(np.abs(whole[c]).max(), 1e-300) for c in whole.columns)
print(f"against the model file with the load: largest difference {worst:.1e} of a column's scale")
ok = worst <= ROUND_OFF and len(rows) == len(whole.t)
if len(sys.argv) > 1:
    with open(sys.argv[1], newline="") as f:
        table = list(csv.reader(f))
    cli = {name: np.array([float(r[k]) for r in table[1:]]) for k, name in enumerate(table[0])}
    worst_cli = max(np.abs(stepped[c] - cli[c]).max() / max(np.abs(cli[c]).max(), 1e-300)
                    for c in cli if c != "t")
    print(f"against mbfe simulate ({sys.argv[1]}): largest difference {worst_cli:.1e} of a column's scale")
    ok = ok and worst_cli <= ROUND_OFF and len(table) - 1 == len(rows)
sys.exit(0 if ok else 1)
