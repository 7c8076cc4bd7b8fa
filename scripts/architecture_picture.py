#!/usr/bin/env python3
"""Draws docs/images/runtime_rooms.png: the runtime's folders and what each may
use (read from scripts/check-layers.sh, the table the layer check enforces),
and the objects of one coupled run.

    python3 scripts/architecture_picture.py [OUT.png]
"""
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.patches import FancyBboxPatch

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "docs", "images", "runtime_rooms.png")

# The table of runtime_allowed_for() in check-layers.sh: folder -> folders it may use.
text = open(os.path.join(root, "scripts", "check-layers.sh")).read()
table = text[text.index("runtime_allowed_for() {"):]
table = table[: table.index("esac")]
uses = {}
for name, allowed in re.findall(r'^\s*(\w+)\) echo "([^"]*)"', table, re.M):
    uses[name] = [a for a in allowed.split() if a != name]

# Level: the longest chain of uses below a folder.
level = {}
def depth(f):
    if f not in level:
        level[f] = 0 if not uses[f] else 1 + max(depth(u) for u in uses[f])
    return level[f]
for f in uses:
    depth(f)
# Draw only the uses that no longer chain implies (transitive reduction).
def reach(f, seen=None):
    seen = set() if seen is None else seen
    for u in uses[f]:
        if u not in seen:
            seen.add(u)
            reach(u, seen)
    return seen
direct = {f: [u for u in uses[f] if not any(u in reach(v) for v in uses[f] if v != u)] for f in uses}

holds = {
    "errors": "InvalidInput, InvalidRequest,\nnumerical faults",
    "abi": "the C interface of a\ngenerated solver",
    "platform": "the thread budget",
    "linalg": "small LU, Woodbury,\nmodal blocks",
    "fem": "beam element, assembly,\nloads in time",
    "integrators": "integrators, FixedStepRun\n(the stepwise driver)",
    "signal": "Butterworth, contact\nstatistics",
    "modal": "eigen-analysis, slicing,\nstate spectra",
    "stability": "stable step of each\nintegrator",
    "damping": "the adjustment policies,\nbeams analysed",
    "structure": "LowRankStructure (one operator\nper adjusted structure), links",
    "multibody": "the rigid part: kernels\nas a system",
    "coupled": "CoupledModel + CoupledData,\nforce elements, formulations",
    "simulation": "AssembledModel, Simulator,\none ModelRun per kind",
    "advisor": "the spectrum of a model,\nstep limits",
}

fig, ax = plt.subplots(figsize=(13, 8.2))
ax.set_xlim(0, 13)
ax.set_ylim(-0.6, max(level.values()) + 1.0)
ax.axis("off")
rows = {}
for f, l in sorted(level.items(), key=lambda kv: (kv[1], kv[0])):
    rows.setdefault(l, []).append(f)
pos = {}
width, height = 2.35, 0.62
for l, names in rows.items():
    span = 8.6
    for i, f in enumerate(names):
        x = 0.3 + (i + 0.5) * span / len(names)
        pos[f] = (x, l)
box_width = {f: min(width, 8.6 / len(rows[l]) - 0.15) for f, (_, l) in pos.items()}
for f, (x, y) in pos.items():
    for u in direct[f]:
        ux, uy = pos[u]
        ax.annotate("", xy=(ux, uy + height / 2), xytext=(x, y - height / 2),
                    arrowprops=dict(arrowstyle="->", color="#8899aa", lw=1.0, shrinkA=0, shrinkB=0))
for f, (x, y) in pos.items():
    core = f in ("coupled", "structure", "simulation")
    ax.add_patch(FancyBboxPatch((x - box_width[f] / 2, y - height / 2), box_width[f], height, boxstyle="round,pad=0.02",
                                fc="#ffe9b3" if core else "#e8eef6", ec="#445566", lw=1.0))
    ax.text(x, y + 0.13, f + "/", ha="center", va="center", fontsize=10, weight="bold")
    ax.text(x, y - 0.1, holds.get(f, ""), ha="center", va="center", fontsize=7.2)
ax.text(0.3, max(level.values()) + 0.75, "runtime/: a folder per job, a library per folder; an arrow "
        "points at what a folder uses (and, through it, what that uses)", fontsize=10)

# One coupled run, on the right.
x0 = 9.35
steps = [
    ("api: Model", "the parsed model and its\ngenerated solver (cached)"),
    ("AssembledModel", "beams assembled and analysed\nonce; makes the CoupledModel"),
    ("CoupledModel (const)", "kernels, beams, structures,\nconstraints, force elements"),
    ("CoupledData (per run)", "every scratch vector; no heap\nallocation after the first step"),
    ("Simulator", "advance_to(t), state, set_state,\noutputs, set_beam_load, report"),
    ("observers", "CSV / NPY / sidecar / VTK\nwriters (api/), Python arrays"),
]
ys = [max(level.values()) + 0.2 - i * (max(level.values()) + 0.5) / len(steps) for i in range(len(steps))]
for i, ((title, what), y) in enumerate(zip(steps, ys)):
    ax.add_patch(FancyBboxPatch((x0, y - 0.3), 3.4, 0.6, boxstyle="round,pad=0.02", fc="#eaf5e6", ec="#446644"))
    ax.text(x0 + 1.7, y + 0.12, title, ha="center", va="center", fontsize=9.5, weight="bold")
    ax.text(x0 + 1.7, y - 0.11, what, ha="center", va="center", fontsize=7.2)
    if i + 1 < len(steps):
        ax.annotate("", xy=(x0 + 1.7, ys[i + 1] + 0.3), xytext=(x0 + 1.7, y - 0.3),
                    arrowprops=dict(arrowstyle="->", color="#446644"))
ax.text(x0, max(level.values()) + 0.75, "one coupled run", fontsize=10)
fig.tight_layout()
fig.savefig(out, dpi=110)
print(out)
