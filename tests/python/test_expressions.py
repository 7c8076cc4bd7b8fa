"""Hostile and undefined expressions in t through the Python module: each is
an mbfe.ModelError with the command line's file:line:col message, and the
interpreter survives (a sum of 60,000 terms used to overflow its stack)."""
import os
import subprocess
import tempfile
import unittest

import mbfe

SOURCE = os.environ.get("MBFE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("MBFE_CLI", os.path.join(SOURCE, "build", "bin", "mbfe"))

RIGID = """model: m
bodies:
  - name: wheel
    parent: ground
    joint: {{type: revolute, at: [0, 0]}}
    mass: 1
    inertia: 1
loads:
  - {{type: torque, body: wheel, value: "{value}"}}
"""

BEAM = """model: m
beams:
  - name: deck
    origin: [0, 0]
    length: 10.0
    elements: 10
    section: {{area: 0.01, inertia: 1.0e-4}}
    material: {{youngs_modulus: 2.1e11, density: 7850}}
    supports: [{{at: 0.0, type: pinned}}, {{at: 10.0, type: pinned}}]
    loads:
      - {{type: point, at: 5.0, value: "{value}"}}
"""


class Expressions(unittest.TestCase):
    def refused(self, template, value, expected):
        """mbfe.load refuses the model with the message `mbfe eval` prints."""
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "m.yaml")
            with open(path, "w") as f:
                f.write(template.format(value=value))
            with self.assertRaises(mbfe.ModelError) as caught:
                mbfe.load(path)
            message = str(caught.exception)
            self.assertTrue(message.startswith(path + ":"), message)
            self.assertIn(expected, message)
            r = subprocess.run([CLI, "eval" if template is RIGID else "modal", path], capture_output=True,
                               text=True, env=dict(os.environ, MBFE_CACHE_DIR=os.path.join(tmp, "cache")))
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertEqual(message, r.stderr.strip())

    def test_sixty_thousand_term_sum(self):
        self.refused(RIGID, "+".join(["t"] * 60000), "a tree deeper than 1000")

    def test_hundred_thousand_term_beam_load(self):
        self.refused(BEAM, "+".join(["t"] * 100000), "a tree deeper than 1000")

    def test_constants_without_a_value(self):
        for value, expected in [("1/0", "division by zero"), ("0/0", "division by zero"), ("log(0)", "log of 0"),
                                ("sqrt(-1)", "sqrt of a negative number"), ("0^0", "0^0 is undefined"),
                                ("exp(1000)", "overflows a double")]:
            with self.subTest(value=value):
                self.refused(RIGID, value, expected)
                self.refused(BEAM, value, expected)

    def test_undefined_for_every_t(self):
        self.refused(RIGID, "1/(t-t)", "a division by zero for every t")


if __name__ == "__main__":
    unittest.main()
