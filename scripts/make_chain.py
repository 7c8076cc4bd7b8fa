#!/usr/bin/env python3
"""Writes models/chain_N.yaml: a planar chain of N uniform links hinged in series.

Each link is 0.5 m long with mass 1 kg, so its inertia about the centre of mass
is m L^2 / 12. Usage: scripts/make_chain.py N [OUTPUT.yaml] (default
models/chain_N.yaml next to this script's parent directory).
"""
import pathlib
import sys

LENGTH = 0.5  # m
MASS = 1.0    # kg


def chain_yaml(n: int) -> str:
    inertia = MASS * LENGTH ** 2 / 12.0
    lines = [
        f"model: chain_{n}",
        f"description: A planar chain of {n} uniform links ({LENGTH} m, {MASS} kg each) "
        "hinged in series, released from rest at 0.3 rad. Written by scripts/make_chain.py.",
        "gravity: [0, -9.81]",
        "bodies:",
    ]
    for i in range(1, n + 1):
        parent = "ground" if i == 1 else f"link{i - 1}"
        at = "[0, 0]" if i == 1 else f"[{LENGTH}, 0]"
        lines += [
            f"  - name: link{i}",
            f"    parent: {parent}",
            f"    joint: {{type: revolute, at: {at}}}",
            f"    mass: {MASS}",
            f"    inertia: {inertia!r}",
            f"    com: [{LENGTH / 2}, 0]",
            f"    points: {{tip: [{LENGTH}, 0]}}",
        ]
    lines += [
        "initial: {q: {link1: 0.3}}",
        "simulation: {integrator: rk4, step: 1.0e-3, t_end: 1.0}",
    ]
    return "\n".join(lines) + "\n"


def main() -> None:
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    n = int(sys.argv[1])
    if n < 1:
        sys.exit("N must be >= 1")
    root = pathlib.Path(__file__).resolve().parent.parent
    out = pathlib.Path(sys.argv[2]) if len(sys.argv) == 3 else root / "models" / f"chain_{n}.yaml"
    out.write_text(chain_yaml(n))


if __name__ == "__main__":
    main()
