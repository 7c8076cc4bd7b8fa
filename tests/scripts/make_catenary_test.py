#!/usr/bin/env python3
"""scripts/make_catenary.py's pantographs: the models it writes parse (mbfe
generate reads and validates them), and the three-mass pantograph on a rigid
support has the natural frequencies of the closed form.

Oracle: for the chain roof -k3- m3 -k2- m2 -k1- m1 in absolute coordinates
(x3, x2, x1), det(K - lambda M) = 0 with
  K = [[k2 + k3, -k2, 0], [-k2, k1 + k2, -k1], [0, -k1, k1]],  M = diag(m3, m2, m1),
a cubic in lambda = omega^2 whose coefficients are written out below by hand
and whose roots are the squared natural frequencies. mbfe's side: M from
`mbfe eval` and K = -dQ/dq by central differences of its Q, in mbfe's own
(relative) joint coordinates; the eigenvalues of M^-1 K do not depend on the
coordinates.

Run by CTest (test make_catenary_pantographs) with MBFE_CLI set to the mbfe
binary."""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "make_catenary.py")
CLI = os.environ.get("MBFE_CLI", os.path.join(ROOT, "build", "bin", "mbfe"))

# The springs are linear, so central differences of Q are exact up to
# rounding: 1e-3 m steps on forces of ~100 N leave ~1e-13 relative.
FREQUENCY_TOL = 1e-8  # relative, per frequency
FD_STEP = 1e-3        # m


def make(out, *args):
    subprocess.run([sys.executable, SCRIPT, "-o", out, *args], check=True)


def mbfe(*args):
    run = subprocess.run([CLI, *args], capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit("mbfe %s failed (%d): %s" % (" ".join(args), run.returncode, run.stderr))
    return run.stdout


def closed_form_frequencies(p):
    """The three natural frequencies (rad/s) of the chain, from the cubic's roots."""
    m1, m2, m3 = p["m1"], p["m2"], p["m3"]
    k1, k2, k3 = p["k1"], p["k2"], p["k3"]
    # det(K - lambda M) = c3 l^3 + c2 l^2 + c1 l + c0, expanded by hand:
    # c3 = -m1 m2 m3; c0 = det K = k1 k2 k3; c2 is the sum over pairs of
    # masses of their product times the stiffness on the diagonal of the
    # third: m1 m2 (k2 + k3) + m1 m3 (k1 + k2) + m2 m3 k1.
    c3 = -m1 * m2 * m3
    c2 = m1 * m2 * (k2 + k3) + m1 * m3 * (k1 + k2) + m2 * m3 * k1
    # The l^1 coefficient is minus the sum of each mass times the determinant of
    # the stiffness left when its row and column are struck out:
    #   m1 * det([[k2 + k3, -k2], [-k2, k1 + k2]]) = m1 (k1 k2 + k1 k3 + k2 k3)
    #   m2 * det([[k2 + k3, 0], [0, k1]])          = m2 k1 (k2 + k3)
    #   m3 * det([[k1 + k2, -k1], [-k1, k1]])      = m3 k1 k2
    c1 = -(m1 * (k1 * k2 + k1 * k3 + k2 * k3) + m2 * k1 * (k2 + k3) + m3 * k1 * k2)
    c0 = k1 * k2 * k3
    roots = np.roots([c3, c2, c1, c0])
    assert np.all(np.abs(roots.imag) < 1e-9 * np.abs(roots.real)), roots
    return np.sort(np.sqrt(roots.real))


def mbfe_frequencies(model, free):
    """sqrt of the eigenvalues of M^-1 K over the coordinates `free`, from mbfe eval."""
    n = json.loads(mbfe("eval", model, "--json"))
    count = len(n["Q"])

    def q_at(i, h):
        q = [0.0] * count
        q[i] = h
        return json.loads(mbfe("eval", model, "--q", ",".join(repr(x) for x in q), "--json"))["Q"]

    M = np.array(n["M"])[np.ix_(free, free)]
    K = np.zeros((len(free), len(free)))
    for col, i in enumerate(free):
        plus, minus = np.array(q_at(i, FD_STEP)), np.array(q_at(i, -FD_STEP))
        K[:, col] = -(plus - minus)[free] / (2 * FD_STEP)
    lam = np.linalg.eigvals(np.linalg.solve(M, K))
    return np.sort(np.sqrt(lam.real))


def main():
    failures = []
    with tempfile.TemporaryDirectory() as d:
        # Every kind of model the options write parses and validates.
        cases = {
            "two_mass": ["--spans", "2", "--speed", "300"],
            "three_mass": ["--spans", "2", "--speed", "300", "--pantograph", "3mass"],
            "two_pantographs": ["--spans", "2", "--speed", "300", "--pantographs", "2", "--distance", "30"],
            "two_three_mass": ["--spans", "2", "--speed", "250", "--pantograph", "3mass", "--pantographs", "2",
                               "--distance", "45.5"],
        }
        for name, args in cases.items():
            path = os.path.join(d, name + ".yaml")
            make(path, "--name", name, *args)
            mbfe("generate", path, "-o", os.path.join(d, name))
        # Two pantographs: the trailing one starts where a single one would, the leading one 30 m ahead.
        text = open(os.path.join(d, "two_pantographs.yaml")).read()
        if '"32.0 + 83.33333333333333*t"' not in text or '"2.0 + 83.33333333333333*t"' not in text:
            failures.append("two pantographs: expected carriages at 32 m and 2 m")
        if "name: strip2" not in text:
            failures.append("two pantographs: no contact strip2")

        path = os.path.join(d, "alone.yaml")
        make(path, "--name", "alone", "--pantograph", "3mass", "--pantograph-only")
        with open(os.path.join(ROOT, "models", "catenary", "pantograph_3mass.json")) as f:
            p = json.load(f)["pantograph"]
        expected = closed_form_frequencies(p)
        got = mbfe_frequencies(path, [1, 2, 3])  # coordinate 0 is the standing carriage
        for e, g in zip(expected, got):
            if abs(g - e) > FREQUENCY_TOL * e:
                failures.append("3-mass frequency %.12g rad/s, closed form %.12g" % (g, e))
        print("3-mass pantograph on a rigid support: f =", ", ".join("%.6g Hz" % (x / (2 * np.pi)) for x in got),
              "(closed form:", ", ".join("%.6g Hz" % (x / (2 * np.pi)) for x in expected) + ")")
    if failures:
        sys.exit("\n".join(failures))
    print("make_catenary pantographs: ok")


if __name__ == "__main__":
    main()
