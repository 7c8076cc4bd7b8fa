"""Ctrl-C in Python: `simulate` and `Simulator.advance_to` stop between steps
and raise KeyboardInterrupt, and what was computed is kept.

The signal must come from outside: a timer thread of the same interpreter
cannot run while the call holds the interpreter lock (advance_to keeps it), so
each case runs in a child interpreter that the test sends SIGINT, as a
terminal's Ctrl-C does. The run asked for is hours long (1e9 steps of 1 us);
the signal comes once it is under way."""
import json
import os
import signal
import subprocess
import sys
import time
import unittest

SOURCE = os.environ.get("MBFE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
MODEL = os.path.join(SOURCE, "models", "double_pendulum.yaml")

# Time the child spends in the run before the signal: long enough that it has
# left Python for the run (the rows before it are a few hundred), short enough
# to keep the test fast.
SECONDS_IN_THE_RUN = 0.3
# The child must stop within this after the signal (it takes milliseconds);
# beyond, the run went on and the test fails instead of hanging.
STOP_TIMEOUT = 20

CHILD = r"""
import json, signal, sys
import mbfe
# As an interactive interpreter has it, even if SIGINT came in ignored.
signal.signal(signal.SIGINT, signal.default_int_handler)
model = mbfe.load(sys.argv[1])
run = dict(integrator="rk4", step=1e-6, t_end=1000.0)
if sys.argv[2] == "simulate":
    print("ready", flush=True)
    try:
        model.simulate(every=1000, **run)
        print(json.dumps({"raised": False}))
    except KeyboardInterrupt as e:
        r = e.result
        print(json.dumps({"raised": True, "status": r.status, "steps": r.steps, "t_reached": r.t_reached,
                          "t": [float(x) for x in r.t], "columns": {c: len(r[c]) for c in r.columns}}))
else:
    sim = model.simulator(**run)
    print("ready", flush=True)
    try:
        sim.advance_to(1000.0)
        print(json.dumps({"raised": False}))
    except KeyboardInterrupt:
        stopped = {"time": sim.time, "steps": sim.steps, "report": sim.report()["status"]}
        after = sim.advance_to(1000.0)  # the run ended at the interrupt
        print(json.dumps({"raised": True, "after": after, "finished": sim.finished, **stopped}))
"""


def interrupted(what):
    """Runs `what` ("simulate" or "advance_to") in a child interpreter, sends it
    SIGINT once the run is under way, and returns what the child reported."""
    child = subprocess.Popen([sys.executable, "-c", CHILD, MODEL, what], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    try:
        ready = child.stdout.readline()
        if ready.strip() != "ready":
            child.kill()
            raise AssertionError("the child did not start the run: " + ready + child.stderr.read())
        time.sleep(SECONDS_IN_THE_RUN)
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=STOP_TIMEOUT)
    except subprocess.TimeoutExpired:
        child.kill()
        child.communicate()
        raise AssertionError("the run did not stop within %d s of SIGINT" % STOP_TIMEOUT)
    if child.returncode != 0:
        raise AssertionError("the child failed (%d): %s" % (child.returncode, err))
    return json.loads(out)


class CtrlCStopsARun(unittest.TestCase):
    def test_simulate_raises_with_the_rows_so_far(self):
        r = interrupted("simulate")
        self.assertTrue(r["raised"], "the run went to its end")
        self.assertEqual(r["status"], "interrupted")
        t = r["t"]
        self.assertGreaterEqual(len(t), 2)
        # Every column holds every row.
        self.assertEqual(set(r["columns"].values()), {len(t)})
        # A row every 1000 steps of 1 us from t = 0, then the state where the
        # run stopped, which is the time it reached.
        for k, tk in enumerate(t[:-1]):
            self.assertAlmostEqual(tk, k * 1e-3, delta=1e-9)
        self.assertEqual(t[-1], r["t_reached"])
        self.assertGreater(t[-1], t[-2])
        self.assertLess(t[-1], 1000.0)
        self.assertAlmostEqual(r["steps"] * 1e-6, r["t_reached"], delta=1e-9)

    def test_advance_to_raises_and_the_run_ends_there(self):
        r = interrupted("advance_to")
        self.assertTrue(r["raised"], "the run went to its end")
        self.assertEqual(r["report"], "interrupted")
        self.assertGreater(r["steps"], 0)
        self.assertLess(r["time"], 1000.0)
        self.assertAlmostEqual(r["steps"] * 1e-6, r["time"], delta=1e-9)
        # Interrupted is finished: a later advance_to takes no step.
        self.assertTrue(r["finished"])
        self.assertEqual(r["after"], r["time"])


if __name__ == "__main__":
    unittest.main()
