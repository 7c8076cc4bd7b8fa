"""A 1000 kg wheel crossing a 20 m bridge at 20 m/s, from Python (docs/python.md).

    python3 examples/python/bridge_crossing.py [OUTDIR]

Loads models/bridge_moving_mass.yaml, simulates the crossing (adjusted damping,
RK4 at its limit, static start), prints the peak midspan deflection and the
tyre's lift-offs, and draws the deflection under the wheel and the tyre force
against the wheel's position into OUTDIR/bridge_crossing.png (matplotlib).
"""
import os
import sys

import numpy as np

import mbfe

here = os.path.dirname(os.path.abspath(__file__))
out_dir = sys.argv[1] if len(sys.argv) > 1 else "."
os.makedirs(out_dir, exist_ok=True)

model = mbfe.load(os.path.join(here, "..", "..", "models", "bridge_moving_mass.yaml"))
print(f"{model.name}: a {model.kind} model, coordinates {model.coordinates}")
print("largest stable RK4 step, adjusted:", model.step_limits()["rk4"]["adjusted"], "s")

run = model.simulate(probes=["deck@10"])
print(run, run.message or "(completed)")
x = run["carriage"]
print(f"lowest midspan deflection {run['deck@10'].min():.4f} m, largest tyre force {run['force_tyre'].max():.0f} N")
for contact in run.springs:
    print(f"contact {contact['name']}: {contact['lift_offs']} lift-offs, {contact['time_off']:.3f} s off contact")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

on_deck = (x >= 0) & (x <= 20)
fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(9, 5.5))
top.plot(x[on_deck], 1000 * run["deflection_tyre"][on_deck], label="deck under the wheel")
top.plot(x[on_deck], 1000 * run["deck@10"][on_deck], label="deck at midspan")
top.set_ylabel("deflection (mm)")
top.legend()
top.grid(True, alpha=0.3)
bottom.plot(x[on_deck], run["force_tyre"][on_deck] / 1000)
bottom.set_ylabel("tyre force (kN)")
bottom.set_xlabel("wheel position x (m)")
bottom.grid(True, alpha=0.3)
fig.suptitle("bridge_moving_mass from Python: mbfe.load(...).simulate(probes=['deck@10'])")
fig.tight_layout()
path = os.path.join(out_dir, "bridge_crossing.png")
fig.savefig(path, dpi=100)
print("wrote", path)
