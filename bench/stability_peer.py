#!/usr/bin/python3
"""bench/stability_peer.py - the numpy/scipy peer of bench/stability_bench.c doing the same work.

Reads the laws the C bench wrote (7 doubles each: m, 1, l1, l2, u0, u1, u2), builds
p = m l2 z^4 + m l1 z^3 + (m + u2) z^2 + u1 z + u0 and decides stability two ways:
  eigvals  - the roots as eigenvalues of the companion matrices, batched (numpy.linalg.eigvals on an
             (N, 4, 4) stack: LAPACK dgeev per matrix, no Python loop), verdict from max Re z;
  hurwitz  - the degree-4 Hurwitz minors (thesis (1.7)) as vectorised array arithmetic (only possible
             because the degree is fixed at 4; no rounding guard).
and the same 1000 x 1000 map (sweeping mu[0] and mu[2]) with batched eigvals; scipy.linalg.eigvals is timed
on a sample to show the per-call cost. Output: "key value" lines.
Usage: stability_peer.py LAWS.bin MAP_STEPS
"""
import sys
import time

import numpy as np
import scipy.linalg


def charpoly(laws):
    m, l1, l2, u0, u1, u2 = (laws[:, k] for k in (0, 2, 3, 4, 5, 6))
    return np.stack([m * l2, m * l1, m + u2, u1, u0], axis=1)


def companion(a):
    n = a.shape[1] - 1
    c = np.zeros((a.shape[0], n, n))
    c[:, 0, :] = -a[:, 1:] / a[:, :1]
    c[:, np.arange(1, n), np.arange(0, n - 1)] = 1.0
    return c


def abscissa(a, chunk=200000):
    out = np.empty(a.shape[0])
    for s in range(0, a.shape[0], chunk):
        out[s:s + chunk] = np.linalg.eigvals(companion(a[s:s + chunk])).real.max(axis=1)
    return out


def hurwitz4(a):
    a0, a1, a2, a3, a4 = a.T
    d3 = a1 * (a2 * a3 - a1 * a4) - a0 * a3 * a3
    return (a1 > 0) & (a1 * a2 - a0 * a3 > 0) & (d3 > 0) & (a4 * d3 > 0)


def main():
    laws = np.fromfile(sys.argv[1]).reshape(-1, 7)
    steps = int(sys.argv[2])
    a = charpoly(laws)

    t0 = time.perf_counter()
    stable = int((abscissa(a) < 0).sum())
    t_eig = time.perf_counter() - t0
    t0 = time.perf_counter()
    stable_h = int(hurwitz4(a).sum())
    t_h = time.perf_counter() - t0

    sample = a[:20000]
    t0 = time.perf_counter()
    for row in sample:
        scipy.linalg.eigvals(companion(row[None, :])[0])
    t_scipy = (time.perf_counter() - t0) / len(sample)

    x = np.linspace(0.01, 3, steps)
    y = np.linspace(-0.5, 2, steps)
    t0 = time.perf_counter()
    X, Y = np.meshgrid(x, y)
    grid = np.tile(np.array([1, 1, 0.9, 0.25, 1, 1.2, 0.6]), (steps * steps, 1))
    grid[:, 4] = X.ravel()
    grid[:, 6] = Y.ravel()
    map_stable = int((abscissa(charpoly(grid)) < 0).sum())
    t_map = time.perf_counter() - t0

    print(f"laws {len(a)}\neigvals_seconds {t_eig:.4f}\neigvals_stable {stable}")
    print(f"hurwitz_seconds {t_h:.4f}\nhurwitz_stable {stable_h}")
    print(f"scipy_per_call_seconds {t_scipy:.3e}")
    print(f"map_points {steps * steps}\nmap_seconds {t_map:.4f}\nmap_stable {map_stable}")
    print(f"numpy {np.__version__}\nscipy {scipy.__version__}")


if __name__ == "__main__":
    main()
