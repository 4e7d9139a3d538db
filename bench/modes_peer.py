#!/usr/bin/python3
"""bench/modes_peer.py - the scipy peer of bench/modes_bench.c: the same chains' modes (eigenvalues and
shapes) by scipy.linalg.eigh(K, M) on the dense matrices (an independent reference), and by
scipy.linalg.eigh_tridiagonal on M^-1/2 K M^-1/2 (LAPACK's stemr, the same algorithm as dashpot's chain
route) for a like-for-like number. Output: "key value" lines. Usage: modes_peer.py OUTDIR
"""
import sys
import time

import numpy as np
import scipy
import scipy.linalg


def timed(fn):
    reps, t0 = 0, time.perf_counter()
    while True:
        out = fn()
        reps += 1
        t = time.perf_counter() - t0
        if t >= 0.3 or reps >= 100000:
            return t / reps, out


for n in (10, 100, 1000):
    m, kd, ke = np.loadtxt(f"{sys.argv[1]}/chain{n}.txt", ndmin=2).T
    M = np.diag(m)
    K = np.diag(kd) + np.diag(ke[:-1], 1) + np.diag(ke[:-1], -1)
    t, (w, v) = timed(lambda: scipy.linalg.eigh(K, M))
    print(f"n{n}_eigh_seconds {t:.9g}")
    print(f"n{n}_eigh_sum_omega {np.sqrt(w).sum():.17g}")
    s = 1 / np.sqrt(m)
    t, (w2, v2) = timed(lambda: scipy.linalg.eigh_tridiagonal(kd * s * s, ke[:-1] * s[:-1] * s[1:]))
    print(f"n{n}_tri_seconds {t:.9g}")
print(f"scipy {scipy.__version__}")
