#!/usr/bin/env python3
"""Writes the golden values of the second-order-section Butterworth filter
(tests/runtime/signal/butterworth_test.cpp) with SciPy (Debian python3-scipy
1.10.1):

    python3 tests/runtime/signal/make_sos_golden.py > tests/runtime/signal/sos_golden.csv

For every order 1..8 and every cut-off 0.4, 0.1, 1e-2, 1e-3 and 1e-4 of the
sample rate: the sections of scipy.signal.butter(order, cutoff, fs=1,
output='sos') on a line `# sos ORDER CUTOFF b0 b1 b2 a0 a1 a2 ...`, and
scipy.signal.sosfiltfilt (its defaults: odd extension, 3 (2 sections + 1 -
trailing zeros) samples of padding, steady-state initial conditions) of one
signal of 400 samples: a level of 100 with a slow ramp, a step, a few sines and
seeded noise. One row per sample: the input x, then one column per case in the
order of the `# sos` lines.
"""
import numpy as np
import scipy
from scipy import signal

ORDERS = range(1, 9)
CUTOFFS = [0.4, 0.1, 1e-2, 1e-3, 1e-4]  # of the sample rate
SAMPLES = 400

rng = np.random.default_rng(20240524)
n = np.arange(SAMPLES)
x = (100.0 + 0.05 * n + 20.0 * (n >= 150) + 10.0 * np.sin(2 * np.pi * 0.003 * n)
     + 5.0 * np.sin(2 * np.pi * 0.07 * n + 0.3) + 2.0 * np.sin(2 * np.pi * 0.31 * n)
     + rng.normal(0.0, 1.0, SAMPLES))

print("# scipy %s: scipy.signal.sosfiltfilt(scipy.signal.butter(order, cutoff, fs=1, output='sos'), x); "
      "python3 tests/runtime/signal/make_sos_golden.py" % scipy.__version__)
columns = [x]
names = ["x"]
for order in ORDERS:
    for cutoff in CUTOFFS:
        sos = signal.butter(order, cutoff, fs=1.0, output="sos")
        print("# sos %d %.17g " % (order, cutoff) + " ".join("%.17g" % v for v in sos.ravel()))
        columns.append(signal.sosfiltfilt(sos, x))
        names.append("y_%d_%g" % (order, cutoff))
print(",".join(names))
for i in range(SAMPLES):
    print(",".join("%.17g" % c[i] for c in columns))
