"""The Python module against the command line on the same models: the same
numbers from `mbfe.load(...).simulate/eval/step_limits` as from `mbfe
simulate/eval/stability`, and the same file:line:col message for bad input."""
import csv
import json
import os
import subprocess
import tempfile
import unittest

import numpy as np

import mbfe

SOURCE = os.environ.get("MBFE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("MBFE_CLI", os.path.join(SOURCE, "build", "bin", "mbfe"))


def model(name):
    return os.path.join(SOURCE, "models", name)


def cli(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


class SameAsTheCommandLine(unittest.TestCase):
    def test_rigid_simulation(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "p.csv")
            r = cli("simulate", model("double_pendulum.yaml"), "--integrator", "rk4", "--step", "1e-3",
                    "--t-end", "0.5", "--quiet", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            header, rows = read_csv(out)
        run = mbfe.load(model("double_pendulum.yaml")).simulate(integrator="rk4", step=1e-3, t_end=0.5)
        self.assertEqual(run.status, "completed")
        self.assertEqual(run.columns, header)
        for k, name in enumerate(header):
            # The CSV prints 17 significant digits: the same doubles.
            np.testing.assert_array_equal(run[name], rows[:, k], err_msg=name)

    def test_spatial_and_loop_models(self):
        for name, formulation in (("double_pendulum_3d.yaml", None), ("slider_crank_3d.yaml", "augmented"),
                                  ("four_bar.yaml", "partitioned")):
            with self.subTest(model=name), tempfile.TemporaryDirectory() as tmp:
                out = os.path.join(tmp, "s.csv")
                extra = ["--formulation", formulation] if formulation else []
                r = cli("simulate", model(name), "--t-end", "0.05", "--quiet", "--out", out, *extra)
                self.assertEqual(r.returncode, 0, r.stderr)
                header, rows = read_csv(out)
                kwargs = {"formulation": formulation} if formulation else {}
                run = mbfe.load(model(name)).simulate(t_end=0.05, **kwargs)
                self.assertEqual(run.status, "completed")
                self.assertEqual(run.columns, header)
                for k, column in enumerate(header):
                    np.testing.assert_array_equal(run[column], rows[:, k], err_msg=column)
        self.assertEqual(mbfe.load(model("slider_crank_3d.yaml")).coordinates,
                         ["crank", "rod_qw", "rod_qx", "rod_qy", "rod_qz", "slider"])

    def test_crossing_with_probe_and_springs(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "c.csv")
            r = cli("simulate", model("bridge_moving_mass.yaml"), "--probe", "deck@10", "--t-end", "0.3",
                    "--quiet", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            header, rows = read_csv(out)
            with open(out + ".json") as f:
                sidecar_springs = json.load(f)["springs"]
        run = mbfe.load(model("bridge_moving_mass.yaml")).simulate(t_end=0.3, probes=["deck@10"])
        self.assertEqual(run.columns, header)
        np.testing.assert_array_equal(run["deck@10"], rows[:, header.index("deck@10")])
        np.testing.assert_array_equal(run["force_tyre"], rows[:, header.index("force_tyre")])
        self.assertEqual(run.springs[0]["name"], "tyre")
        self.assertEqual(run.springs, sidecar_springs)

    def test_adjustment_estimate_as_in_the_sidecar(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "c.csv")
            # Under the cap (the shipped model is under policy mass, whose estimate is small).
            r = cli("simulate", model("bridge_moving_mass.yaml"), "--set", "beams.deck.adjustment.policy=cap",
                    "--t-end", "0.01", "--quiet", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out + ".json") as f:
                expected = json.load(f)["adjustment_estimate"]
        m = mbfe.load(model("bridge_moving_mass.yaml"), set={"beams.deck.adjustment.policy": "cap"})
        run = m.simulate(t_end=0.01)
        self.assertEqual(run.adjustment_estimate["max"], expected["max"])
        self.assertEqual(run.adjustment_estimate["where"], expected["where"])
        self.assertEqual(run.adjustment_estimate["points"][0]["estimate"], expected["points"][0]["estimate"])
        self.assertEqual(run.adjustment_estimate, expected)  # every field, as the sidecar has it
        self.assertTrue(any("adjustment estimate:" in n for n in run.notices))  # 4.3 %, above 1 %
        self.assertIsNone(m.simulate(t_end=0.01, adjust=False).adjustment_estimate)
        # 10 steps: the linearised run would take more than 4 times the run's, so it is skipped.
        self.assertIn("skipped", run.adjustment_estimate["linearised"]["not_estimated"])

    def test_linearised_estimate_as_in_the_sidecar(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "c.csv")
            # The whole run (1200 steps): the linearised run of both models is the estimate.
            r = cli("simulate", model("bridge_moving_mass.yaml"), "--set", "beams.deck.adjustment.policy=cap",
                    "--every", "100", "--quiet", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out + ".json") as f:
                expected = json.load(f)["adjustment_estimate"]
        run = mbfe.load(model("bridge_moving_mass.yaml"), set={"beams.deck.adjustment.policy": "cap"}).simulate()
        lin = run.adjustment_estimate["linearised"]
        self.assertEqual(lin["contact_force"], expected["linearised"]["contact_force"])
        self.assertEqual(lin["contacts"], expected["linearised"]["contacts"])
        self.assertEqual(lin["steps"], expected["linearised"]["steps"])
        # Every field but the wall time the linearised runs took.
        del lin["seconds"], expected["linearised"]["seconds"]
        self.assertEqual(run.adjustment_estimate, expected)
        self.assertEqual(run.adjustment_estimate["max"], lin["contact_force"]["relative"])
        self.assertEqual(lin["contact_force"]["contact"], "tyre")
        self.assertGreater(lin["contact_force"]["relative"], 0.05)  # the cap at 2000 rad/s: about 20 %

    def test_npy_output_reads_back_as_the_run(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "c.npy")
            r = cli("simulate", model("bridge_moving_mass.yaml"), "--probe", "deck@10", "--t-end", "0.3",
                    "--quiet", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            table = np.load(out)
            with open(out + ".json") as f:
                meta = json.load(f)
        names = [c["name"] for c in meta["columns"]]
        self.assertEqual(table.shape, (meta["rows"], len(names)))
        run = mbfe.load(model("bridge_moving_mass.yaml")).simulate(t_end=0.3, probes=["deck@10"])
        for k, name in enumerate(names):
            np.testing.assert_array_equal(table[:, k], run[name], err_msg=name)

    def test_npy_of_a_diverged_run_holds_every_row_written(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "d.npy")
            r = cli("simulate", model("double_pendulum.yaml"), "--integrator", "forward_euler", "--step", "0.2",
                    "--t-end", "1000", "--every", "1", "--quiet", "--out", out)
            self.assertEqual(r.returncode, 3, r.stderr)
            table = np.load(out)
            with open(out + ".json") as f:
                meta = json.load(f)
        self.assertEqual(meta["status"], "diverged")
        self.assertEqual(table.shape[0], meta["rows"])
        self.assertGreater(table.shape[0], 10)
        self.assertTrue(np.isfinite(table).all())

    def test_eval(self):
        r = cli("eval", model("double_pendulum.yaml"), "--q", "0.3,-0.2", "--qd", "1,0.5", "--json", "--quiet")
        self.assertEqual(r.returncode, 0, r.stderr)
        expected = json.loads(r.stdout)
        got = mbfe.load(model("double_pendulum.yaml")).eval([0.3, -0.2], [1.0, 0.5])
        for key in ("M", "F", "Q"):
            np.testing.assert_array_equal(got[key], np.array(expected[key]), err_msg=key)

    def test_eval_of_a_loop_model_has_the_loops(self):
        q = [0.3, 0.9899856611293864, 0.0, -0.12626445504008477, 0.06313222752004238, 0.48405728739343046]
        qd = [10.0, 0.1, -0.2, 0.3, 0.5]
        r = cli("eval", model("slider_crank_3d.yaml"), "--q", ",".join(repr(x) for x in q),
                "--qd", ",".join(repr(x) for x in qd), "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        expected = json.loads(r.stdout)
        got = mbfe.load(model("slider_crank_3d.yaml")).eval(q, qd)
        for key in ("M", "F", "Q"):
            np.testing.assert_array_equal(got[key], np.array(expected[key]), err_msg=key)
        self.assertEqual(sorted(got["loops"].keys()), ["J", "Phi", "gamma"])
        for key in ("Phi", "J", "gamma"):
            np.testing.assert_array_equal(got["loops"][key], np.array(expected["loops"][key]), err_msg=key)

    def test_eval_refuses_a_quaternion_off_unit_length(self):
        # The rod's quaternion (1, 0, 0, 1): norm sqrt(2).
        q = [0.3, 1.0, 0.0, 0.0, 1.0, 0.4]
        r = cli("eval", model("slider_crank_3d.yaml"), "--q", ",".join(repr(x) for x in q), "--json")
        self.assertEqual(r.returncode, 2, r.stdout)
        self.assertIn("the quaternion of body 'rod' (rod_qw .. rod_qz) has norm 1.414213562", r.stderr)
        with self.assertRaises(ValueError) as caught:
            mbfe.load(model("slider_crank_3d.yaml")).eval(q, [0.0] * 5)
        self.assertIn("the quaternion of body 'rod' (rod_qw .. rod_qz) has norm 1.414213562", str(caught.exception))

    def test_step_limits(self):
        r = cli("stability", model("bridge_moving_mass.yaml"), "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        expected = json.loads(r.stdout)
        got = mbfe.load(model("bridge_moving_mass.yaml")).step_limits()
        self.assertEqual(got["rk4"]["adjusted"], expected["adjusted"]["rk4"])
        self.assertEqual(got["forward_euler"]["adjusted"], 0.0)  # "none"
        self.assertEqual(got["trapezoid"]["original"], float("inf"))  # "unconditional"

    def test_bad_model_raises_with_the_located_message(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "bad.yaml")
            with open(path, "w") as f:
                f.write("model: bad\nbodies:\n  - name: a\n    parent: ground\n    joint: {type: hinge}\n")
            r = cli("eval", path)
            self.assertEqual(r.returncode, 2)
            with self.assertRaises(mbfe.ModelError) as caught:
                mbfe.load(path)
            self.assertEqual(str(caught.exception), r.stderr.strip())
            self.assertTrue(str(caught.exception).startswith(path + ":5:"), str(caught.exception))
        self.assertTrue(issubclass(mbfe.ModelError, ValueError))

    def test_set_overrides_as_the_command_line(self):
        # set={PATH: value} is --set PATH=VALUE: the same run, the same message.
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "s.csv")
            r = cli("simulate", model("double_pendulum.yaml"), "--set", "bodies.link2.mass=2.5", "--t-end", "0.3",
                    "--quiet", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            header, rows = read_csv(out)
        run = mbfe.load(model("double_pendulum.yaml"), set={"bodies.link2.mass": 2.5}).simulate(t_end=0.3)
        for k, name in enumerate(header):
            np.testing.assert_array_equal(run[name], rows[:, k], err_msg=name)
        r = cli("eval", model("double_pendulum.yaml"), "--set", "bodies.link2.mass=-1", "--json")
        self.assertEqual(r.returncode, 2)
        with self.assertRaises(mbfe.ModelError) as caught:
            mbfe.load(model("double_pendulum.yaml"), set={"bodies.link2.mass": -1})
        self.assertEqual(str(caught.exception), r.stderr.strip())
        self.assertIn("--set bodies.link2.mass=-1", str(caught.exception))
        with self.assertRaises(TypeError):
            mbfe.load(model("double_pendulum.yaml"), set={"bodies.link2.mass": object()})
        # A list is a YAML list: where the file wants a number, the model refuses it, as --set does.
        r = cli("eval", model("double_pendulum.yaml"), "--set", "bodies.link2.mass=[1, 2]", "--json")
        self.assertEqual(r.returncode, 2)
        with self.assertRaises(mbfe.ModelError) as caught:
            mbfe.load(model("double_pendulum.yaml"), set={"bodies.link2.mass": [1, 2]})
        self.assertEqual(str(caught.exception), r.stderr.strip())

    def test_set_lists_as_the_command_line(self):
        # A list replaces a list whole; an item of a list of numbers is reached by its index.
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "l.csv")
            r = cli("simulate", model("double_pendulum.yaml"), "--set", "bodies.link2.joint.at=[1.25, 0]",
                    "--t-end", "0.3", "--quiet", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            header, rows = read_csv(out)
        plain = mbfe.load(model("double_pendulum.yaml")).simulate(t_end=0.3)
        self.assertFalse(np.array_equal(plain["link1"], rows[:, header.index("link1")]))
        for given in ({"bodies.link2.joint.at": [1.25, 0]}, {"bodies.link2.joint.at": (1.25, 0.0)},
                      {"bodies.link2.joint.at": np.array([1.25, 0.0])}, {"bodies.link2.joint.at.0": 1.25}):
            with self.subTest(set=given):
                run = mbfe.load(model("double_pendulum.yaml"), set=given).simulate(t_end=0.3)
                for k, name in enumerate(header):
                    np.testing.assert_array_equal(run[name], rows[:, k], err_msg=name)

    def test_status_names_as_the_sidecar(self):
        # A step far beyond forward Euler's stable limit: 'diverged', as the
        # sidecar of the command line says; a run that ends well: 'completed'.
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "d.csv")
            r = cli("simulate", model("double_pendulum.yaml"), "--integrator", "forward_euler", "--step", "0.2",
                    "--t-end", "1000", "--quiet", "--out", out)
            self.assertEqual(r.returncode, 3, r.stderr)
            with open(out + ".json") as f:
                sidecar = json.load(f)
        pendulum = mbfe.load(model("double_pendulum.yaml"))
        run = pendulum.simulate(integrator="forward_euler", step=0.2, t_end=1000)
        self.assertEqual(sidecar["status"], "diverged")
        self.assertEqual(run.status, "diverged")
        self.assertEqual(run.message, sidecar["message"])
        self.assertTrue(run.message.startswith("diverged"), run.message)
        self.assertEqual(pendulum.simulate(t_end=0.1).status, "completed")

    def test_warnings_as_in_the_sidecar(self):
        # `angle: 180` meant as degrees, started as written: the wheel falls
        # past the deck; the same warnings as the command line's sidecar.
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "w.csv")
            r = cli("simulate", model("bridge_moving_mass.yaml"), "--set", "beams.deck.angle=180", "--start", "given",
                    "--t-end", "0.2", "--quiet", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out + ".json") as f:
                sidecar = json.load(f)
        run = mbfe.load(model("bridge_moving_mass.yaml"), set={"beams.deck.angle": 180}).simulate(
            t_end=0.2, static_start=False)
        self.assertEqual(run.warnings, sidecar["warnings"])
        self.assertEqual(len(run.warnings), 2)
        self.assertIn("never touched the beam during the run", run.warnings[1])
        self.assertFalse(run.springs[0]["touched"])

    def test_a_zero_mass_wheel_is_refused_as_the_command_line_refuses_it(self):
        # Started as written, the first step would divide by the zero mass.
        r = cli("simulate", model("bridge_moving_mass.yaml"), "--set", "bodies.wheel.mass=0", "--start", "given",
                "--quiet")
        self.assertEqual(r.returncode, 2, r.stderr)
        m = mbfe.load(model("bridge_moving_mass.yaml"), set={"bodies.wheel.mass": 0})
        with self.assertRaises(mbfe.ModelError) as caught:
            m.simulate(static_start=False)
        # The command line's last line (a warning about the joint comes first).
        self.assertEqual(str(caught.exception), r.stderr.strip().splitlines()[-1])
        self.assertIn("'wheel' moves no mass", str(caught.exception))

    def test_request_the_model_cannot_run(self):
        with self.assertRaises(ValueError):
            mbfe.load(model("double_pendulum.yaml")).simulate(probes=["deck@1"])


class BadInputIsRefusedWithAMessage(unittest.TestCase):
    """What the module took or said nothing about before: each as the command
    line does it."""

    def test_a_model_error_message_is_never_empty(self):
        # A name that is not UTF-8 (bytes) or holds a NUL made the message empty.
        with self.assertRaises(mbfe.ModelError) as caught:
            mbfe.parse(b"model: m\n", b"bad\xffname")
        self.assertEqual(str(caught.exception), "bad\ufffdname:1:8: model 'm' has no bodies and no beams")

    def test_a_path_with_a_nul_is_refused(self):
        # "ok.yaml\0junk" loaded ok.yaml.
        with self.assertRaises(ValueError) as caught:
            mbfe.load(model("double_pendulum.yaml") + "\0junk")
        self.assertIn("NUL", str(caught.exception))
        with self.assertRaises(ValueError):
            mbfe.parse("model: m\n", "a\0b")

    def test_every_follows_the_command_lines_rule(self):
        # every=0 ran (automatic rows) where --every 0 is refused.
        r = cli("simulate", model("double_pendulum.yaml"), "--every", "0")
        self.assertEqual(r.returncode, 2, r.stderr)
        m = mbfe.load(model("double_pendulum.yaml"))
        for every in (0, -3):
            with self.assertRaises(ValueError) as caught:
                m.simulate(t_end=0.01, every=every)
            self.assertIn("every must be a positive integer", str(caught.exception))
        self.assertEqual(len(m.simulate(t_end=0.01, every=5).t), 3)  # t = 0, 0.005, 0.01
        self.assertEqual(len(m.simulate(t_end=0.01).t), 11)  # absent: every step up to 10,000 rows

    def test_output_columns_have_names_of_their_own(self):
        # A body named t gave two columns t and r.t returned the body's angle.
        text = ("model: m\ngravity: [0, -9.81]\nbodies:\n"
                "  - {name: t, parent: ground, joint: {type: revolute}, mass: 1, inertia: 0.1}\n")
        with self.assertRaises(mbfe.ModelError) as caught:
            mbfe.parse(text, "t.yaml")
        self.assertTrue(str(caught.exception).startswith("t.yaml:4:12: body 't'"), str(caught.exception))
        # Two probes of one label: two columns of one name.
        with self.assertRaises(ValueError) as caught:
            mbfe.load(model("bridge_moving_mass.yaml")).simulate(t_end=0.01, probes=["deck@10", "deck@10"])
        self.assertIn("is given twice", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
