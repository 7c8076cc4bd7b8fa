#!/usr/bin/env python3
"""The generated spatial kernels (and the loop kernels, planar and spatial)
against SymPy: M, F, Q of M v' + F = Q by Kane's method, and the loops' Phi,
J and gamma, every derivative taken exactly by SymPy.

Kane's method with the velocity coordinates v as generalized speeds:
    M = sum_i m_i Jv_i^T Jv_i + Jw_i^T I_i Jw_i
    F = sum_i m_i Jv_i^T a_i + Jw_i^T (I_i alpha_i + w_i x I_i w_i)
    Q = sum_i Jv_i^T m_i g + Jp^T f + Jw^T tau - k (q - rest) - c v
with Jv_i the partial velocities of body i's centre of mass, Jw_i its partial
angular velocities, I_i = R_i I R_i^T, and a_i, alpha_i its accelerations at
v' = 0. All of them are derivatives along the paths q (+) s d of the forward
kinematics (written here from docs/model-format.md, independently of the
generator): d = e_j gives column j of the partial velocities, d = v the
accelerations, with the kinematics a SymPy expression of the one symbol s,
differentiated exactly and evaluated with 30 digits. (q (+) s d moves a
one-coordinate joint by s d, a free joint's x, y, z by s d, and turns a
quaternion joint's body by the rotation vector s d in the body frame, whose
angular velocity d is then constant: the motion with v' = 0.) The loops:
J = dPhi/ds along e_j, gamma = -d^2 Phi/ds^2 along v.

The models are random (seeded) trees of 3 to 5 bodies with random axes, joint
rotations, offsets and inertia tensors, revolute and prismatic joints mixed,
one tree with a spherical joint and a free one, and loop models (a spatial
one with each kind of constraint, and a planar one). `mbfe eval --json` gives
the generated kernels' values. Run by CTest (sympy_spatial_oracle) with
MBFE_CLI pointing at the built mbfe.

One file of about 500 lines because the oracle (the forward kinematics, Kane's
terms and the loop rows, written here) is most of it and serves this test alone.
"""
import json
import math
import os
import random
import subprocess
import tempfile
import unittest

import sympy as sp

DIGITS = 30          # SymPy's working precision: the oracle's own round-off is far below the tolerance
RELATIVE_TOL = 1e-12  # of the largest entry: a few thousand ulps of double arithmetic in the kernels
STATES = 3            # random states per model
s = sp.Symbol("s")

MBFE = os.environ.get("MBFE_CLI", "build/bin/mbfe")


def num(x):
    """A model number as SymPy sees it: the decimal written to the file."""
    return sp.Float(repr(float(x)), DIGITS)


def rounded(x):
    return float(f"{x:.6g}")


# ---- Random models --------------------------------------------------------


def random_inertia(rng, mass):
    """The inertia of a random box turned by a random rotation."""
    a, b, c = (rng.uniform(0.05, 0.6) for _ in range(3))
    principal = sp.diag(mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12, mass * (a * a + b * b) / 12)
    w, x, y, z = (rng.gauss(0, 1) for _ in range(4))
    r = quaternion_matrix([w, x, y, z])
    i = (r * principal * r.T).evalf(17)
    # Six digits, and a hair more on the diagonal so that rounding keeps it physical.
    return [rounded(float(i[0, 0]) * (1 + 1e-5)), rounded(float(i[1, 1]) * (1 + 1e-5)),
            rounded(float(i[2, 2]) * (1 + 1e-5)), rounded(float(i[0, 1])), rounded(float(i[0, 2])),
            rounded(float(i[1, 2]))]


def vector(rng, n=3, low=-1.0, high=1.0):
    return [rounded(rng.uniform(low, high)) for _ in range(n)]


def random_tree(rng, name, bodies, kinds):
    """A spatial tree; kinds[i] is the joint type of body i."""
    model = {"name": name, "dimension": 3, "gravity": vector(rng, 2) + [-9.81], "bodies": [], "loads": [],
             "constraints": []}
    for i in range(bodies):
        mass = rounded(rng.uniform(0.2, 2.0))
        model["bodies"].append({
            "name": f"b{i}", "parent": -1 if i == 0 else rng.randrange(i), "type": kinds[i],
            "axis": vector(rng), "at": vector(rng), "rpy": vector(rng), "mass": mass,
            "inertia": random_inertia(rng, mass), "com": vector(rng), "point": vector(rng)})
        model["loads"].append({"type": "force", "body": i, "value": vector(rng)})
        model["loads"].append({"type": "torque", "body": i, "value": vector(rng)})
        if kinds[i] in ("revolute", "prismatic"):
            model["loads"].append({"type": "spring_damper", "body": i, "stiffness": rounded(rng.uniform(0.1, 3)),
                                   "damping": rounded(rng.uniform(0.1, 3)), "rest": rounded(rng.uniform(-1, 1))})
    return model


def to_yaml(model):
    def v(values):
        return "[" + ", ".join(repr(float(x)) for x in values) + "]"
    spatial = model["dimension"] == 3
    lines = [f"model: {model['name']}", f"dimension: {model['dimension']}", f"gravity: {v(model['gravity'])}",
             "bodies:"]
    for b in model["bodies"]:
        parent = "ground" if b["parent"] < 0 else model["bodies"][b["parent"]]["name"]
        joint = f"type: {b['type']}, at: {v(b['at'])}"
        if b["type"] in ("revolute", "prismatic") and (spatial or b["type"] == "prismatic"):
            joint += f", axis: {v(b['axis'])}"
        if spatial:
            joint += f", rotation: {v(b['rpy'])}"
        inertia = v(b["inertia"]) if spatial else repr(b["inertia"])
        lines.append(f"  - {{name: {b['name']}, parent: {parent}, joint: {{{joint}}}, mass: {b['mass']!r}, "
                     f"inertia: {inertia}, com: {v(b['com'])}, points: {{p: {v(b['point'])}}}}}")
    if model["loads"]:
        lines.append("loads:")
    for load in model["loads"]:
        body = model["bodies"][load["body"]]["name"]
        if load["type"] == "force":
            lines.append(f"  - {{type: force, body: {body}, point: p, value: {v(load['value'])}}}")
        elif load["type"] == "torque":
            value = v(load["value"]) if spatial else repr(load["value"])
            lines.append(f"  - {{type: torque, body: {body}, value: {value}}}")
        else:
            lines.append(f"  - {{type: spring_damper, joint: {body}, stiffness: {load['stiffness']!r}, "
                         f"damping: {load['damping']!r}, rest: {load['rest']!r}}}")
    if model["constraints"]:
        lines.append("constraints:")
    for c in model["constraints"]:
        ends = []
        for key in ("a", "b"):
            body, at = c[key]
            ends.append(f"{key}: {{body: {'ground' if body < 0 else model['bodies'][body]['name']}, at: {v(at)}}}")
        axis = f", axis: {v(c['axis'])}" if "axis" in c else ""
        lines.append(f"  - {{name: {c['name']}, type: {c['type']}, {ends[0]}, {ends[1]}{axis}}}")
    return "\n".join(lines) + "\n"


# ---- Kinematics along a path q (+) s d ------------------------------------
#
# Along q (+) s d every joint angle is a + b s (b = 0 for a joint that does
# not move), so the kinematics are polynomials in s and in the cosine C_j and
# sine S_j of each joint's angle: SymPy polynomials (exact arithmetic on
# 30-digit numbers, no expression swell). d/ds is the chain rule,
#   d/ds = d/ds|explicit + sum_j b_j (C_j d/dS_j - S_j d/dC_j),
# and s = 0 puts C_j = cos a, S_j = sin a.

DOMAIN = sp.RealField(prec=100)


def counts(kind):
    """Position and velocity coordinates of a joint."""
    return {"revolute": (1, 1), "prismatic": (1, 1), "spherical": (4, 3), "free": (7, 6)}[kind]


def layout(model):
    first_q, first_v, nq, nv = [], [], 0, 0
    for b in model["bodies"]:
        first_q.append(nq)
        first_v.append(nv)
        nq += counts(b["type"])[0]
        nv += counts(b["type"])[1]
    return first_q, first_v, nq, nv


class Path:
    """The generators of the polynomials along one path (a sparse SymPy
    polynomial ring over 30-digit numbers), and d/ds."""

    def __init__(self, joints):
        names = ["s"] + [f"{kind}{j}" for j in range(joints) for kind in ("C", "S")]
        self.ring, *self.gens = sp.ring(",".join(names), DOMAIN)
        self.rate = [0] * joints      # b_j
        self.start = [0] * joints     # a_j

    def const(self, x):
        """A number, or a SymPy expression of s, as a polynomial."""
        return self.ring.from_expr(x) if isinstance(x, sp.Expr) and x.has(s) else self.ring(DOMAIN(x))

    def angle(self, j, a, b):
        """(cos, sin) of a + b s as polynomials: the generators C_j, S_j."""
        self.start[j], self.rate[j] = a, b
        return self.gens[1 + 2 * j], self.gens[2 + 2 * j]

    def derivative(self, p):
        out = p.diff(self.gens[0])
        for j, b in enumerate(self.rate):
            if b != 0:
                c, sn = self.gens[1 + 2 * j], self.gens[2 + 2 * j]
                out += (p.diff(sn) * c - p.diff(c) * sn) * DOMAIN(b)
        return out

    def at_zero(self, p, order):
        """The order-th derivative in s at s = 0."""
        for _ in range(order):
            p = self.derivative(p)
        values = [0] + [f(DOMAIN(a)) for a in self.start for f in (sp.cos, sp.sin)]
        values = [DOMAIN(v) for v in values]
        total = DOMAIN(0)
        for monomial, coefficient in p.terms():
            term = coefficient
            for value, power in zip(values, monomial):
                if power:
                    term *= value ** power
            total += term
        return sp.Float(total, DIGITS)


def mat_mul(a, b):
    return [[sum((a[i][k] * b[k][j] for k in range(3)), b[0][0] * 0) for j in range(3)] for i in range(3)]


def mat_vec(a, v):
    return [sum((a[i][k] * v[k] for k in range(3)), v[0] * 0) for i in range(3)]


def as_poly(path, m):
    """A numeric 3x3 matrix or 3-vector as constant polynomials."""
    if isinstance(m[0], list):
        return [[path.const(x) for x in row] for row in m]
    return [path.const(x) for x in m]


def axis_rotation(axis, c, s_):
    """c I + s [axis]x + (1 - c) axis axis^T (c, s_: numbers or polynomials)."""
    x, y, z = axis
    one = c * 0 + 1
    return [[c + (one - c) * (x * x), (one - c) * (x * y) - s_ * z, (one - c) * (x * z) + s_ * y],
            [(one - c) * (x * y) + s_ * z, c + (one - c) * (y * y), (one - c) * (y * z) - s_ * x],
            [(one - c) * (x * z) - s_ * y, (one - c) * (y * z) + s_ * x, c + (one - c) * (z * z)]]


def quaternion_matrix(wxyz):
    w, x, y, z = wxyz
    n = sp.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return sp.Matrix([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                      [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                      [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def rpy_matrix(rpy):
    r, p, y = (num(a) for a in rpy)
    rz = sp.Matrix(axis_rotation([0, 0, 1], sp.cos(y), sp.sin(y)))
    ry = sp.Matrix(axis_rotation([0, 1, 0], sp.cos(p), sp.sin(p)))
    rx = sp.Matrix(axis_rotation([1, 0, 0], sp.cos(r), sp.sin(r)))
    return rz * ry * rx


def unit(values):
    v = [num(x) for x in values]
    n = sp.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def frames(model, q, d):
    """The Path and per body (R, o) along q (+) s d, polynomials."""
    first_q, first_v, _, _ = layout(model)
    spatial = model["dimension"] == 3
    path = Path(len(model["bodies"]))
    out = []
    for i, b in enumerate(model["bodies"]):
        if b["parent"] < 0:
            rp, op = as_poly(path, [[1, 0, 0], [0, 1, 0], [0, 0, 1]]), as_poly(path, [0, 0, 0])
        else:
            rp, op = out[b["parent"]]
        joint = mat_mul(rp, as_poly(path, rpy_matrix(b["rpy"]).tolist())) if spatial else rp
        at = [num(x) for x in (b["at"] if spatial else b["at"][:2] + [0])]
        k, j = first_q[i], first_v[i]
        o = [a + b_ for a, b_ in zip(op, mat_vec(rp, as_poly(path, at)))]
        r = joint
        if b["type"] == "revolute":
            axis = unit(b["axis"]) if spatial else [0, 0, 1]
            c, sn = path.angle(i, num(q[k]), num(d[j]))
            r = mat_mul(joint, axis_rotation(axis, c, sn))
        elif b["type"] == "prismatic":
            axis = unit(b["axis"] if spatial else b["axis"][:2] + [0])
            shift = path.const(num(q[k]) + s * num(d[j]))
            o = [a + shift * u for a, u in zip(o, mat_vec(rp, as_poly(path, axis)))]
        else:
            if b["type"] == "free":
                x = [path.const(num(q[k + c]) + s * num(d[j + c])) for c in range(3)]
                o = [a + b_ for a, b_ in zip(o, mat_vec(joint, x))]
                k, j = k + 3, j + 3
            turn = [num(d[j + c]) for c in range(3)]
            size = sp.sqrt(sum(x * x for x in turn))
            rel = as_poly(path, quaternion_matrix([num(q[k + c]) for c in range(4)]).tolist())
            if size != 0:
                c, sn = path.angle(i, 0, size)  # turning by s |d| about d
                rel = mat_mul(rel, axis_rotation([x / size for x in turn], c, sn))
            r = mat_mul(joint, rel)
        out.append((r, o))
    return path, out


def at_zero(path, m, order):
    """A polynomial, list or matrix of them: the order-th derivative at s = 0, as SymPy numbers."""
    if isinstance(m, list) and isinstance(m[0], list):
        return sp.Matrix([[path.at_zero(x, order) for x in row] for row in m])
    if isinstance(m, list):
        return sp.Matrix([path.at_zero(x, order) for x in m])
    return path.at_zero(m, order)


def vee(w):
    """The axial vector of the skew part of w."""
    return sp.Matrix([w[2, 1] - w[1, 2], w[0, 2] - w[2, 0], w[1, 0] - w[0, 1]]) / 2


def point_of(path, frame, at):
    r, o = frame
    return [a + b for a, b in zip(o, mat_vec(r, as_poly(path, [num(x) for x in at])))]


def dot(a, b):
    return sum((x * y for x, y in zip(a, b)), a[0] * 0)


def loop_rows(model, path, fr):
    """Phi along the path, from the definitions of docs/model-format.md."""
    rows = []
    identity = as_poly(path, [[1, 0, 0], [0, 1, 0], [0, 0, 1]])
    for c in model["constraints"]:
        ends = []
        for key in ("a", "b"):
            body, at = c[key]
            frame = (identity, as_poly(path, [0, 0, 0])) if body < 0 else fr[body]
            ends.append((frame[0], point_of(path, frame, at if len(at) == 3 else at + [0])))
        (ra, pa), (rb, pb) = ends
        d = [y - x for x, y in zip(pa, pb)]
        turn = lambda r, v: mat_vec(r, as_poly(path, v))
        if model["dimension"] != 3:
            if c["type"] != "prismatic":
                rows += [pa[0] - pb[0], pa[1] - pb[1]]
            else:
                axis = unit(c["axis"] + [0])
                n = [-axis[1], axis[0], 0]
                rows += [dot(turn(ra, n), d), dot(turn(ra, n), turn(rb, axis))]
            continue
        if "axis" in c:
            axis = unit(c["axis"])
            least = min(range(3), key=lambda k: (abs(float(axis[k])), k))
            e = [1 if k == least else 0 for k in range(3)]
            n1 = [axis[1] * e[2] - axis[2] * e[1], axis[2] * e[0] - axis[0] * e[2], axis[0] * e[1] - axis[1] * e[0]]
            length = sp.sqrt(sum(x * x for x in n1))
            n1 = [x / length for x in n1]
            n2 = [axis[1] * n1[2] - axis[2] * n1[1], axis[2] * n1[0] - axis[0] * n1[2], axis[0] * n1[1] - axis[1] * n1[0]]
        if c["type"] != "prismatic":
            rows += [pa[k] - pb[k] for k in range(3)]
        if c["type"] == "revolute":
            rows += [dot(turn(ra, axis), turn(rb, n1)), dot(turn(ra, axis), turn(rb, n2))]
        if c["type"] == "prismatic":
            rows += [dot(turn(ra, n1), d), dot(turn(ra, n2), d), dot(turn(ra, axis), turn(rb, n1)),
                     dot(turn(ra, axis), turn(rb, n2)), dot(turn(ra, n1), turn(rb, n2))]
    return rows


def inertia_matrix(b, spatial):
    if not spatial:
        return sp.diag(0, 0, num(b["inertia"]))
    xx, yy, zz, xy, xz, yz = (num(x) for x in b["inertia"])
    return sp.Matrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])


def oracle(model, q, v):
    """M, F, Q and the loops' Phi, J, gamma at (q, v), by Kane's method."""
    _, first_v, _, nv = layout(model)
    spatial = model["dimension"] == 3
    bodies = model["bodies"]
    com = [b["com"] if spatial else b["com"][:2] + [0] for b in bodies]
    pts = [b["point"] if spatial else b["point"][:2] + [0] for b in bodies]
    zero = [0.0] * nv
    path0, fr0 = frames(model, q, zero)
    rot0 = [at_zero(path0, r, 0) for r, _ in fr0]
    jv = [sp.zeros(3, nv) for _ in bodies]  # centre of mass
    jp = [sp.zeros(3, nv) for _ in bodies]  # point p
    jw = [sp.zeros(3, nv) for _ in bodies]
    phi = [at_zero(path0, row, 0) for row in loop_rows(model, path0, fr0)]
    jacobian = sp.zeros(len(phi), nv)
    for j in range(nv):
        path, fr = frames(model, q, [1.0 if k == j else 0.0 for k in range(nv)])
        for i, frame in enumerate(fr):
            jv[i][:, j] = at_zero(path, point_of(path, frame, com[i]), 1)
            jp[i][:, j] = at_zero(path, point_of(path, frame, pts[i]), 1)
            jw[i][:, j] = vee(at_zero(path, frame[0], 1) * rot0[i].T)
        for r, row in enumerate(loop_rows(model, path, fr)):
            jacobian[r, j] = at_zero(path, row, 1)
    path, fr = frames(model, q, v)
    vv = sp.Matrix([num(x) for x in v])
    m_mat, f_vec, q_vec = sp.zeros(nv, nv), sp.zeros(nv, 1), sp.zeros(nv, 1)
    gravity = sp.Matrix([num(x) for x in (model["gravity"] if spatial else model["gravity"][:2] + [0])])
    for i, b in enumerate(bodies):
        mass = num(b["mass"])
        inertia = rot0[i] * inertia_matrix(b, spatial) * rot0[i].T
        accel = at_zero(path, point_of(path, fr[i], com[i]), 2)
        alpha = vee(at_zero(path, fr[i][0], 2) * rot0[i].T)
        omega = jw[i] * vv
        m_mat += mass * jv[i].T * jv[i] + jw[i].T * inertia * jw[i]
        f_vec += mass * jv[i].T * accel + jw[i].T * (inertia * alpha + omega.cross(inertia * omega))
        q_vec += jv[i].T * (mass * gravity)
    first_q, _, _, _ = layout(model)
    for load in model["loads"]:
        i = load["body"]
        if load["type"] == "force":
            value = load["value"] if spatial else load["value"][:2] + [0]
            q_vec += jp[i].T * sp.Matrix([num(x) for x in value])
        elif load["type"] == "torque":
            value = load["value"] if spatial else [0, 0, load["value"]]
            q_vec += jw[i].T * sp.Matrix([num(x) for x in value])
        else:
            j, k = first_v[i], first_q[i]
            q_vec[j] += -num(load["stiffness"]) * (num(q[k]) - num(load["rest"])) - num(load["damping"]) * num(v[j])
    gamma = [-at_zero(path, row, 2) for row in loop_rows(model, path, fr)]
    to_float = lambda m: [[float(x) for x in m.row(r)] for r in range(m.rows)]
    return {"M": to_float(m_mat), "F": [float(x) for x in f_vec], "Q": [float(x) for x in q_vec],
            "loops": {"Phi": [float(x) for x in phi], "J": to_float(jacobian), "gamma": [float(x) for x in gamma]}}


def random_state(rng, model):
    q, v = [], []
    for b in model["bodies"]:
        nq, nv = counts(b["type"])
        block = [rounded(rng.uniform(-3, 3)) for _ in range(nq)]
        if b["type"] in ("spherical", "free"):
            quat = [rng.gauss(0, 1) for _ in range(4)]
            size = math.sqrt(sum(x * x for x in quat))
            block[nq - 4:] = [x / size for x in quat]  # unit to double precision, as an integrator keeps it
        q += block
        v += [rounded(rng.uniform(-2, 2)) for _ in range(nv)]
    return q, v


class SympyOracle(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory()

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    def check(self, model, seed):
        path = os.path.join(self.folder.name, model["name"] + ".yaml")
        with open(path, "w") as f:
            f.write(to_yaml(model))
        rng = random.Random(seed)
        for _ in range(STATES):
            q, v = random_state(rng, model)
            run = subprocess.run([MBFE, "eval", path, "--q", ",".join(repr(x) for x in q), "--qd",
                                  ",".join(repr(x) for x in v), "--json"], capture_output=True, text=True)
            self.assertEqual(run.returncode, 0, run.stderr)
            got = json.loads(run.stdout)
            want = oracle(model, q, v)
            for key in ("M", "F", "Q"):
                self.assert_close(got[key], want[key], f"{model['name']} {key} at q={q}, v={v}")
            if model["constraints"]:
                for key in ("Phi", "J", "gamma"):
                    self.assert_close(got["loops"][key], want["loops"][key], f"{model['name']} {key} at q={q}, v={v}")

    def assert_close(self, got, want, what):
        flat = lambda x: [y for row in x for y in (row if isinstance(row, list) else [row])]
        g, w = flat(got), flat(want)
        self.assertEqual(len(g), len(w), what)
        scale = max(1.0, max(abs(x) for x in w))
        error = max(abs(a - b) for a, b in zip(g, w)) / scale
        self.assertLess(error, RELATIVE_TOL, f"{what}\n got {got}\nwant {want}")

    def test_revolute_prismatic_trees(self):
        rng = random.Random(11)
        self.check(random_tree(rng, "sympy_tree3", 3, ["revolute", "prismatic", "revolute"]), 1)
        self.check(random_tree(rng, "sympy_tree5", 5, ["revolute", "revolute", "prismatic", "revolute", "prismatic"]), 2)

    def test_quaternion_joints(self):
        rng = random.Random(12)
        self.check(random_tree(rng, "sympy_quaternions", 4, ["free", "revolute", "spherical", "prismatic"]), 3)

    def test_spatial_loops(self):
        rng = random.Random(13)
        model = random_tree(rng, "sympy_spatial_loops", 4, ["revolute", "spherical", "prismatic", "revolute"])
        model["constraints"] = [
            {"name": "ball", "type": "point", "a": (0, vector(rng)), "b": (2, vector(rng))},
            {"name": "hinge", "type": "revolute", "a": (1, vector(rng)), "b": (3, vector(rng)), "axis": vector(rng)},
            {"name": "slide", "type": "prismatic", "a": (-1, vector(rng)), "b": (1, vector(rng)), "axis": vector(rng)}]
        self.check(model, 4)

    def test_planar_loops(self):
        rng = random.Random(14)
        model = random_tree(rng, "sympy_planar_loops", 4, ["revolute", "revolute", "prismatic", "revolute"])
        model["dimension"] = 2
        model["gravity"] = [model["gravity"][0], -9.81]
        for b in model["bodies"]:
            b["inertia"] = rounded(rng.uniform(0.01, 0.2))
            b["at"], b["com"], b["point"], b["axis"] = (x[:2] for x in (b["at"], b["com"], b["point"], b["axis"]))
        for load in model["loads"]:
            if load["type"] == "force":
                load["value"] = load["value"][:2]
            if load["type"] == "torque":
                load["value"] = load["value"][2]
        model["constraints"] = [
            {"name": "pin", "type": "point", "a": (1, vector(rng, 2)), "b": (3, vector(rng, 2))},
            {"name": "hinge", "type": "revolute", "a": (-1, vector(rng, 2)), "b": (2, vector(rng, 2))},
            {"name": "slide", "type": "prismatic", "a": (0, vector(rng, 2)), "b": (3, vector(rng, 2)),
             "axis": vector(rng, 2)}]
        self.check(model, 5)


if __name__ == "__main__":
    unittest.main()
