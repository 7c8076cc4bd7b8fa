#!/usr/bin/env python3
"""Writes spatial model files for measuring the generator (docs/performance.md).

    scripts/make_spatial_tree.py chain N [--free K] [-o MODEL.yaml]
    scripts/make_spatial_tree.py free N [-o MODEL.yaml]
    scripts/make_spatial_tree.py humanoid [-o MODEL.yaml]

chain N: N links of 0.4 m hinged in series, the hinge axes taking turns about
z, y and x (every body turns in 3D), each link a slender box of 1 kg along
its z axis; with --free K, the first K links on free joints instead.

free N: N links in series, each on a free joint (6 degrees of freedom)
relative to the one before, the most coordinates N bodies can have and the
longest paths to the ground: the costliest model of N bodies to generate and
compile (scripts/compile_cost.sh).

humanoid: a branching tree of 35 joints shaped like a humanoid robot, a free
joint at the pelvis (6 degrees of freedom) and 34 revolute joints: a torso
of 3 (yaw, pitch, roll), a neck of 2 and a head of 1, two arms of 7
(shoulder 3, elbow 1, wrist 3) with a gripper joint, two legs of 6 (hip 3,
knee 1, ankle 2). 40 velocity coordinates. Masses of a 64 kg robot, each
link a box along its z axis; the shoulders' joint frames are turned
(`rotation`).

Without -o the model goes to standard output.
"""
import argparse
import sys

AXES = {"x": "[1, 0, 0]", "y": "[0, 1, 0]", "z": "[0, 0, 1]"}


def box_inertia(mass, a, b, c):
    """Ixx Iyy Izz Ixy Ixz Iyz of a box a x b x c along x, y, z."""
    ixx, iyy, izz = (mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12, mass * (a * a + b * b) / 12)
    return f"[{ixx:.6g}, {iyy:.6g}, {izz:.6g}, 0, 0, 0]"


def body(name, parent, joint, mass, inertia, com, tip=None):
    line = (f"  - {{name: {name}, parent: {parent}, joint: {joint}, mass: {mass}, inertia: {inertia}, "
            f"com: {com}")
    if tip:
        line += f", points: {{tip: {tip}}}"
    return line + "}"


def chain(n, free=0):
    lines = [f"model: spatial_chain_{n}",
             f"description: A spatial chain of {n} links hinged about z, y, x in turn"
             + (f", the first {free} on free joints" if free else "") + ". "
             "Written by scripts/make_spatial_tree.py.",
             "dimension: 3", "gravity: [0, 0, -9.81]", "bodies:"]
    order = "zyx"
    for i in range(n):
        parent = "ground" if i == 0 else f"link{i}"
        at = "[0, 0, 0]" if i == 0 else "[0, 0, 0.4]"
        joint = (f"{{type: free, at: {at}}}" if i < free else
                 f"{{type: revolute, axis: {AXES[order[i % 3]]}, at: {at}}}")
        lines.append(body(f"link{i + 1}", parent, joint, 1.0, box_inertia(1.0, 0.05, 0.05, 0.4), "[0, 0, 0.2]",
                          "[0, 0, 0.4]"))
    return "\n".join(lines) + "\n"


def free_chain(n):
    lines = [f"model: free_chain_{n}",
             f"description: {n} links in series, each on a free joint relative to the one before. "
             "Written by scripts/make_spatial_tree.py.",
             "dimension: 3", "gravity: [0, 0, -9.81]", "bodies:"]
    for i in range(n):
        parent = "ground" if i == 0 else f"link{i}"
        at = "[0, 0, 0]" if i == 0 else "[0, 0, 0.4]"
        lines.append(body(f"link{i + 1}", parent, f"{{type: free, at: {at}}}", 1.0,
                          box_inertia(1.0, 0.05, 0.05, 0.4), "[0, 0, 0.2]", "[0, 0, 0.4]"))
    return "\n".join(lines) + "\n"


def humanoid():
    lines = ["model: humanoid_35",
             "description: A humanoid-shaped tree of 35 joints (a free pelvis and 34 revolute joints). "
             "Written by scripts/make_spatial_tree.py.",
             "dimension: 3", "gravity: [0, 0, -9.81]", "bodies:"]
    lines.append(body("pelvis", "ground", "{type: free, at: [0, 0, 0.9]}", 8.0, box_inertia(8.0, 0.2, 0.3, 0.15),
                      "[0, 0, 0]"))

    def serial(prefix, parent, at, joints, mass, length, rotation="[0, 0, 0]"):
        """A serial limb: joints = list of axis letters; the first at `at`, the rest at the end of the last link."""
        names = []
        for k, axis in enumerate(joints):
            name = f"{prefix}{k + 1}"
            # Joints of one group share a point (a 3-axis hip, shoulder or wrist): a short link between them.
            link = length if k == len(joints) - 1 else 0.02
            offset = at if k == 0 else f"[0, 0, {-previous:.4g}]"
            rot = rotation if k == 0 else "[0, 0, 0]"
            ax = AXES[axis] if axis in AXES else AXES["y"]
            joint = f"{{type: revolute, axis: {ax}, at: {offset}, rotation: {rot}}}"
            m = mass if abs(link) > 0.05 else 0.3
            lines.append(body(name, parent, joint, m, box_inertia(m, 0.06, 0.06, max(abs(link), 0.04)),
                              f"[0, 0, {-link / 2:.4g}]", f"[0, 0, {-link:.4g}]"))
            names.append(name)
            parent, previous = name, link
        return names

    torso = serial("torso", "pelvis", "[0, 0, 0.1]", ["z", "y", "x"], 20.0, -0.45)
    serial("neck", torso[-1], "[0, 0, -0.45]", ["z", "y", "x"], 4.0, -0.2)
    for side, y in (("l", 0.2), ("r", -0.2)):
        arm = serial(f"{side}shoulder", torso[-1], f"[0, {y}, -0.4]", ["y", "x", "z"], 2.0, 0.3,
                     rotation="[0.1, 0, 0]" if y > 0 else "[-0.1, 0, 0]")
        elbow = serial(f"{side}elbow", arm[-1], "[0, 0, -0.3]", ["y"], 1.5, 0.25)
        wrist = serial(f"{side}wrist", elbow[-1], "[0, 0, -0.25]", ["z", "y", "x"], 0.5, 0.08)
        serial(f"{side}grip", wrist[-1], "[0, 0, -0.08]", ["x"], 0.2, 0.06)
        hip = serial(f"{side}hip", "pelvis", f"[0, {y / 2}, -0.05]", ["z", "x", "y"], 5.0, 0.4)
        knee = serial(f"{side}knee", hip[-1], "[0, 0, -0.4]", ["y"], 3.0, 0.4)
        serial(f"{side}ankle", knee[-1], "[0, 0, -0.4]", ["y", "x"], 1.0, 0.08)
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("kind", choices=["chain", "free", "humanoid"])
    parser.add_argument("n", nargs="?", type=int, help="links of a chain")
    parser.add_argument("--free", type=int, default=0, help="chain: the first K links on free joints")
    parser.add_argument("-o", "--output")
    args = parser.parse_args()
    if args.kind != "humanoid" and not args.n:
        parser.error(args.kind + " needs N")
    if args.kind == "chain":
        text = chain(args.n, args.free)
    else:
        text = free_chain(args.n) if args.kind == "free" else humanoid()
    if args.output:
        with open(args.output, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
