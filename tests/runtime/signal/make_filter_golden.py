#!/usr/bin/env python3
"""Writes the golden values of tests/runtime/signal/butterworth_test.cpp with
SciPy (Debian python3-scipy 1.10.1):

    python3 tests/runtime/signal/make_filter_golden.py > tests/runtime/signal/filter_golden.csv

A contact-force-like signal (mean 110 N, span and dropper harmonics, a 60 Hz
component the 20 Hz filter removes, a dip to zero), sampled at 1 kHz for 2 s,
filtered by scipy.signal.filtfilt with scipy.signal.butter(4, 20 Hz): one row
per sample, t, the input, the output. The header comment says what made it.
"""
import numpy as np
import scipy
from scipy import signal

fs = 1000.0
t = np.arange(0, 2000) / fs
x = (110.0 + 30.0 * np.sin(2 * np.pi * 1.5 * t) + 15.0 * np.sin(2 * np.pi * 6.9 * t + 0.4)
     + 10.0 * np.sin(2 * np.pi * 60.0 * t) + 5.0 * np.sin(2 * np.pi * 18.0 * t + 1.1))
x[700:720] = 0.0  # a contact loss: the unfiltered force is zero
b, a = signal.butter(4, 20.0 / (fs / 2))
y = signal.filtfilt(b, a, x)
print("# scipy %s: scipy.signal.filtfilt(*scipy.signal.butter(4, 20 / 500), x); "
      "python3 tests/runtime/signal/make_filter_golden.py" % scipy.__version__)
print("# b = " + " ".join("%.17g" % v for v in b))
print("# a = " + " ".join("%.17g" % v for v in a))
print("t,x,y")
for ti, xi, yi in zip(t, x, y):
    print("%.17g,%.17g,%.17g" % (ti, xi, yi))
