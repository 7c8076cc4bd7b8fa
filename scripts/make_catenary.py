#!/usr/bin/env python3
"""Writes pantograph-catenary model files from a parameter table.

    scripts/make_catenary.py [TABLE.json] [--spans N] [--speed KMH] [--name NAME] [-o MODEL.yaml]
                             [--pantograph 2mass|3mass] [--pantographs 1|2] [--distance M]
                             [--pantograph-only] [--truncate OMEGA]

TABLE defaults to models/catenary/en50318_2002.json (what each value is and
where it comes from: docs/validation-en50318.md). Without -o, writes the
shipped models: models/pantograph_catenary_250.yaml and _300.yaml (the table's
spans, the wires truncated at the table's `truncation`) and
models/pantograph_catenary_2span.yaml (two spans at 300 km/h with the table's
`adjustment`, the version CI runs).

The model (docs/catenary.md):
  - messenger and contact wire as tensioned beams (`tension:`), E I from the
    table, area from the mass per length and density; messenger on spring
    supports at every support, contact wire on steady arms (spring + mass);
    both wires pinned at the first and last support (the anchors);
  - droppers as slack links at the table's positions in every span, the
    contact wire's pre-sag (a parabola, `presag` at mid-span) by form
    finding (`hold:`), clamp masses on both wires at the droppers;
  - Rayleigh damping giving the table's damping ratio at both ends of its band;
  - the pantograph: a carriage driven along the line at the speed (`motion:`),
    the frame (m2; k2, c2 to the carriage) and the head (m1; k1, c1 to the
    frame), weightless (gravity cancelled by a force on each), the static
    force pushing the frame up; the head's strip presses the contact wire
    from below (`slider_spring`, `side: below`, unilateral);
  - or, with --pantograph 3mass, the three-mass pantograph of
    models/catenary/pantograph_3mass.json (head m1 on k1, c1 over the upper
    frame m2; m2 on k2, c2 over the lower frame m3; m3 on k3, c3 over the
    carriage; the static force pushes the lower frame up);
  - with --pantographs 2, a second pantograph --distance metres behind the
    first (its bodies, loads and contact end in 2); the trailing one starts
    where a single one would, the run ends when the leading one reaches the
    last span's end less the start;
  - with --pantograph-only, the pantograph(s) alone on a carriage standing
    still (no wires, no contact): a rigid support, for checking a
    pantograph's own modes;
  - a static start: wires, droppers and pantograph in equilibrium at t = 0;
  - the modal adjustment of damping (the table's `adjustment`: cap, policy
    (`cap` unless the table names another: at the shipped step its EN 50318
    statistics are closer than the default `mass`'s, docs/damping-adjustment.md)
    and the explicit integrator and step it allows) on both wires, with that
    integrator as the model's default; the simulation line names the
    original model's implicit run beside it;
  - or, with --truncate OMEGA, both wires truncated at OMEGA rad/s (policy
    truncate: each wire moves in its modes up to OMEGA alone), the same
    integrator and step: on the full line the fastest way to the accuracy
    EN 50318 asks (docs/catenary.md, "Modal truncation"), so the shipped
    full-line models have it (the table's `truncation`).
"""
import argparse
import json
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def number(x):
    return repr(float(x))


def rayleigh(zeta, f1, f2):
    w1, w2 = 2 * math.pi * f1, 2 * math.pi * f2
    return 2 * zeta * w1 * w2 / (w1 + w2), 2 * zeta / (w1 + w2)


def pantograph_text(pan, start_text, v, suffix, static_force, speed_text):
    """The bodies and loads of one pantograph (lines of YAML): a carriage
    driven from `start_text` at `speed_text` m/s (standing still when v is 0),
    then the two-mass (m1, m2) or three-mass (m1, m2, m3) chain up to the head,
    whose point `strip` touches the contact wire. Names end in `suffix`."""
    g = 9.81
    c, f, h = "carriage" + suffix, "frame" + suffix, "head" + suffix
    motion = "%s + %s*t" % (start_text, speed_text) if v != 0 else "0.0*t"
    b = []
    w = b.append
    w("  - name: %-20s# %s" % (c, "driven along the line" if v != 0 else "standing still: a rigid support"))
    w("    parent: ground")
    w("    joint: {type: prismatic, axis: [1, 0], at: [0, 0], motion: \"%s\"}" % motion)
    w("    mass: 0")
    w("    inertia: 0")
    three = "m3" in pan
    if three:
        lower = "lower" + suffix
        w("  - name: %-20s# m3, the lower frame" % lower)
        w("    parent: %s" % c)
        w("    joint: {type: prismatic, axis: [0, 1], at: [0, 0]}")
        w("    mass: %s" % number(pan["m3"]))
        w("    inertia: 0")
        w("  - name: %-20s# m2, the upper frame" % f)
        w("    parent: %s" % lower)
    else:
        w("  - name: %-20s# m2" % f)
        w("    parent: %s" % c)
    w("    joint: {type: prismatic, axis: [0, 1], at: [0, 0]}")
    w("    mass: %s" % number(pan["m2"]))
    w("    inertia: 0")
    w("  - name: %-20s# m1, its strip touches the contact wire" % h)
    w("    parent: %s" % f)
    w("    joint: {type: prismatic, axis: [0, 1], at: [0, 0]}")
    w("    mass: %s" % number(pan["m1"]))
    w("    inertia: 0")
    w("    points: {strip: [0, 0]}")
    tag = "_" + suffix if suffix else ""
    loads = []
    w = loads.append
    # Named, so that --set and a sweep reach them: loads.k1.stiffness,
    # loads.uplift.value (k1_2, uplift_2 ... on a second pantograph).
    if three:
        w("  - {name: %s, type: spring_damper, joint: %s, stiffness: %s, damping: %s, rest: 0.0}   # k3, c3" % ("k3" + tag, lower, number(pan["k3"]), number(pan["c3"])))
    w("  - {name: %s, type: spring_damper, joint: %s, stiffness: %s, damping: %s, rest: 0.0}   # k2, c2" % ("k2" + tag, f, number(pan["k2"]), number(pan["c2"])))
    w("  - {name: %s, type: spring_damper, joint: %s, stiffness: %s, damping: %s, rest: 0.0}    # k1, c1" % ("k1" + tag, h, number(pan["k1"]), number(pan["c1"])))
    if three:
        w("  - {name: %s, type: force, body: %s, value: [0, %s]}   # static force %g N + the lower frame's weight cancelled" % ("uplift" + tag, lower, number(static_force + pan["m3"] * g), static_force))
        w("  - {name: %s, type: force, body: %s, value: [0, %s]}   # the upper frame's weight cancelled" % ("frame_weight" + tag, f, number(pan["m2"] * g)))
    else:
        w("  - {name: %s, type: force, body: %s, value: [0, %s]}   # static force %g N + the frame's weight cancelled" % ("uplift" + tag, f, number(static_force + pan["m2"] * g), static_force))
    w("  - {name: %s, type: force, body: %s, value: [0, %s]}    # the head's weight cancelled" % ("head_weight" + tag, h, number(pan["m1"] * g)))
    return b, loads


def model_text(p, spans, kmh, name, table_path, pantograph=None, pantographs=1, distance=0.0, only=False,
               truncate=None):
    """The model file's text. `pantograph` replaces the table's (a three-mass
    one has m3); `pantographs` 2 puts a second one `distance` m behind the
    first; `only` writes the pantograph(s) alone on a standing carriage;
    `truncate` (rad/s) truncates both wires there instead of the table's
    adjustment."""
    L = p["span_length"]
    length = spans * L
    le = p["element_length"]
    elements = int(round(length / le))
    if abs(elements * le - length) > 1e-9:
        sys.exit("make_catenary: the element length must divide the line")
    for s in p["droppers"]["positions"]:
        if abs(round(s / le) * le - s) > 1e-9:
            sys.exit("make_catenary: dropper at %g m is not at a node (element %g m)" % (s, le))
    alpha, beta = rayleigh(p["damping_ratio"], *p["damping_band_hz"])
    v = kmh / 3.6
    cw, mw = p["contact_wire"], p["messenger"]
    pan, con = p["pantograph"], p["contact"]
    static_force = pan["static_force"]
    if pantograph is not None:
        pan = pantograph
    kind = "three-mass" if "m3" in pan else "two-mass"
    g = 9.81
    start = p["start"]
    second = None
    if pantographs == 2:
        if not 0.0 < distance < length - 2 * start:
            sys.exit("make_catenary: --distance must be between 0 and %g m (the line less twice the start)" % (length - 2 * start))
        second = start
        start = start + distance
    t_end = (length - 2 * p["start"] - (distance if second is not None else 0.0)) / v
    if only:
        return pantograph_only_text(pan, name, static_force, pantographs, distance)
    out = []
    w = out.append
    w("# Written by scripts/make_catenary.py from %s (%d spans, %g km/h%s):"
      % (os.path.relpath(table_path, ROOT), spans, kmh, (", --truncate %s" % number(truncate)) if truncate else ""))
    w("# edit the table and rerun the script rather than this file.")
    w("model: %s" % name)
    w("description: >-")
    w("  A simple catenary of %d spans of %g m (messenger and contact wire, droppers, steady arms)" % (spans, L))
    if pantograph is None and second is None:
        w("  and a two-mass pantograph running along it at %g km/h, after the EN 50318:2002 reference" % kmh)
        w("  model as the open literature reproduces it (docs/validation-en50318.md says which values are")
        w("  sourced and which assumed). Static start; the contact force is force_strip.")
        if truncate and truncate == p.get("truncation", {}).get("omega_limit"):
            # What docs/catenary.md measured of the table's truncation, not of any other.
            w("  The wires are truncated at %s rad/s (%d Hz, policy truncate): of the ways of running it"
              % (number(truncate), round(truncate / (2 * math.pi))))
            w("  compared in docs/catenary.md (\"Modal truncation\"), the fastest that keeps every EN 50318")
            w("  statistic within 0.3 % of the mean contact force of the original model's implicit run")
            w("  (0.21 % at 300 km/h; the cap at 1500 rad/s: 0.30 %, 1.5 times slower). The original model:")
            w("  --adjust off --integrator generalized_alpha --step %s." % number(p["step"]))
        elif truncate:
            w("  The wires are truncated at %s rad/s (policy truncate)." % number(truncate))
    else:
        w("  and %s %s pantograph%s running along it at %g km/h%s, after the EN 50318:2002 reference"
          % ("two" if second is not None else "a", kind, "s" if second is not None else "", kmh,
             (" %g m apart" % distance) if second is not None else ""))
        w("  catenary as the open literature reproduces it (docs/validation-en50318.md; the pantograph:")
        w("  docs/catenary.md, \"Pantographs\"). Static start; the contact force is force_strip%s."
          % (" (leading) and force_strip2 (trailing)" if second is not None else ""))
    w("gravity: [0, -9.81]")
    bodies, loads = pantograph_text(pan, number(start), v, "", static_force, speed_text=number(v))
    if second is not None:
        b2, l2 = pantograph_text(pan, number(second), v, "2", static_force, speed_text=number(v))
        bodies += b2
        loads += l2
    out.extend(["bodies:"] + bodies + ["loads:"] + loads)
    supports = [i * L for i in range(spans + 1)]
    anchor_end = length  # anchors: pinned at both ends of each wire
    adj = p.get("adjustment")
    adjusted = adj is not None
    w("beams:")
    for wire, props, y in (("messenger", mw, p["encumbrance"]), ("contact_wire", cw, 0.0)):
        area = props["mass_per_length"] / props["density"]
        inertia = props["EI"] / props["youngs_modulus"]
        w("  - name: %s" % wire)
        w("    origin: [0, %s]" % number(y))
        w("    length: %s" % number(length))
        w("    elements: %d" % elements)
        w("    section: {area: %s, inertia: %s}" % (number(area), number(inertia)))
        w("    material: {youngs_modulus: %s, density: %s}" % (number(props["youngs_modulus"]), number(props["density"])))
        w("    tension: %s" % number(props["tension"]))
        w("    damping: {rayleigh: {alpha: %s, beta: %s}}" % (number(alpha), number(beta)))
        if truncate:
            w("    adjustment: {omega_limit: %s, policy: truncate}" % number(truncate))
        elif adjusted:
            w("    adjustment: {omega_limit: %s, margin: %s, policy: %s}" %
              (number(adj["omega_limit"]), number(adj["margin"]), adj.get("policy", "cap")))
        w("    supports:")
        for s in supports:
            if s == 0.0 or s == anchor_end:
                w("      - {at: %s, type: pinned}" % number(s))
            elif wire == "messenger":
                w("      - {at: %s, type: spring, stiffness: %s}" % (number(s), number(p["messenger_support"]["stiffness"])))
            else:
                w("      - {at: %s, type: spring, stiffness: %s, mass: %s}" % (number(s), number(p["steady_arm"]["stiffness"]), number(p["steady_arm"]["mass"])))
        clamp = p["clamps"][wire]
        w("    masses:")
        for i in range(spans):
            for d in p["droppers"]["positions"]:
                w("      - {at: %s, mass: %s}" % (number(i * L + d), number(clamp)))
    w("links:")
    k = p["droppers"]["stiffness"]
    for i in range(spans):
        for j, d in enumerate(p["droppers"]["positions"]):
            s = i * L + d
            sag = -p["presag"] * 4.0 * d * (L - d) / (L * L)
            w("  - {name: d%d_%d, a: {beam: contact_wire, at: %s}, b: {beam: messenger, at: %s}, stiffness: %s, slack: %s, hold: %s}"
              % (i + 1, j + 1, number(s), number(s), number(k), "true" if p["droppers"]["slack"] else "false", number(sag)))
    w("contacts:")
    w("  - {name: strip, type: slider_spring, body: head, point: strip, beam: contact_wire, stiffness: %s, damping: %s, unilateral: true, side: below}"
      % (number(con["stiffness"]), number(con["damping"])))
    if second is not None:
        w("  - {name: strip2, type: slider_spring, body: head2, point: strip, beam: contact_wire, stiffness: %s, damping: %s, unilateral: true, side: below}"
          % (number(con["stiffness"]), number(con["damping"])))
    w("initial: {static: true}")
    if truncate:
        explicit = adj or {"integrator": "rk4", "step": 1.0e-3}  # the step the table's adjustment runs at
        w("simulation: {integrator: %s, step: %s, t_end: %s}   # truncated; the original: --adjust off --integrator generalized_alpha --step %s"
          % (explicit["integrator"], number(explicit["step"]), number(t_end), number(p["step"])))
    elif adjusted:
        w("simulation: {integrator: %s, step: %s, t_end: %s}   # adjusted; the original: --adjust off --integrator generalized_alpha --step %s"
          % (adj["integrator"], number(adj["step"]), number(t_end), number(p["step"])))
    else:
        w("simulation: {integrator: generalized_alpha, step: %s, t_end: %s}" % (number(p["step"]), number(t_end)))
    return "\n".join(out) + "\n"


def pantograph_only_text(pan, name, static_force, pantographs, distance):
    """The pantograph(s) alone, each on a carriage standing still: no wires,
    no contact, the static force balanced by the lowest spring."""
    out = ["# Written by scripts/make_catenary.py --pantograph-only: the pantograph on a rigid support.",
           "model: %s" % name,
           "description: >-",
           "  A %s pantograph (docs/catenary.md, \"Pantographs\") on a carriage standing still:"
           % ("three-mass" if "m3" in pan else "two-mass"),
           "  its own modes, without the catenary.",
           "gravity: [0, -9.81]"]
    bodies, loads = pantograph_text(pan, "0.0", 0.0, "", static_force, speed_text="0.0")
    if pantographs == 2:
        b2, l2 = pantograph_text(pan, "0.0", 0.0, "2", static_force, speed_text="0.0")
        bodies += b2
        loads += l2
    out += ["bodies:"] + bodies + ["loads:"] + loads
    out.append("initial: {static: true}")
    out.append("simulation: {integrator: rk4, step: 1.0e-4, t_end: 1.0}")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("table", nargs="?", default=os.path.join(ROOT, "models", "catenary", "en50318_2002.json"))
    ap.add_argument("--spans", type=int)
    ap.add_argument("--speed", type=float, help="km/h")
    ap.add_argument("--name")
    ap.add_argument("-o", "--out")
    ap.add_argument("--pantograph", choices=["2mass", "3mass"], default="2mass",
                    help="2mass: the table's (EN 50318); 3mass: models/catenary/pantograph_3mass.json")
    ap.add_argument("--pantographs", type=int, choices=[1, 2], default=1, help="one pantograph or two")
    ap.add_argument("--distance", type=float, default=0.0,
                    help="m between two pantographs (with --pantographs 2)")
    ap.add_argument("--pantograph-only", action="store_true",
                    help="the pantograph(s) alone on a carriage standing still (no catenary)")
    ap.add_argument("--truncate", type=float, metavar="OMEGA",
                    help="truncate both wires at OMEGA rad/s (policy truncate) instead of the table's adjustment")
    a = ap.parse_args()
    if a.truncate is not None and not a.truncate > 0:
        ap.error("--truncate OMEGA must be > 0 (rad/s)")
    with open(a.table) as f:
        p = json.load(f)
    if a.pantographs == 2 and not a.distance > 0:
        ap.error("--pantographs 2 needs --distance M (> 0)")
    if a.pantographs == 1 and a.distance:
        ap.error("--distance needs --pantographs 2")
    pantograph = None
    if a.pantograph == "3mass":
        with open(os.path.join(ROOT, "models", "catenary", "pantograph_3mass.json")) as f:
            pantograph = json.load(f)["pantograph"]
    custom = pantograph is not None or a.pantographs == 2 or a.pantograph_only
    if custom and not a.out:
        ap.error("--pantograph 3mass, --pantographs 2 and --pantograph-only write one model: give -o")
    if a.out:
        spans = a.spans or p["spans"]
        kmh = a.speed or p["speeds_kmh"][0]
        name = a.name or "pantograph_catenary"
        with open(a.out, "w") as f:
            f.write(model_text(p, spans, kmh, name, a.table, pantograph, a.pantographs, a.distance,
                               a.pantograph_only, a.truncate))
        return
    for kmh in p["speeds_kmh"]:
        path = os.path.join(ROOT, "models", "pantograph_catenary_%d.yaml" % kmh)
        with open(path, "w") as f:
            f.write(model_text(p, p["spans"], kmh, "pantograph_catenary_%d" % kmh, a.table,
                               truncate=p.get("truncation", {}).get("omega_limit")))
        print("make_catenary: wrote", os.path.relpath(path, ROOT))
    path = os.path.join(ROOT, "models", "pantograph_catenary_2span.yaml")
    with open(path, "w") as f:
        f.write(model_text(p, 2, max(p["speeds_kmh"]), "pantograph_catenary_2span", a.table))
    print("make_catenary: wrote", os.path.relpath(path, ROOT))


if __name__ == "__main__":
    main()
