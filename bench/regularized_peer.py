#!/usr/bin/python3
"""bench/regularized_peer.py - SciPy's solve_ivp (Radau, LSODA) on the regularized ODE bench/regularized_bench.c
gives dashpot: m = k = phi0 = 1, x(0) = 4.5, x'(0) = 0, x'' = -x - clamp(n x', -1, 1) (paper (17)-(18) with
Coulomb's g_n), t in [0, 30], samples every 0.1 (t_eval), rtol = atol = 1e-10, the analytic Jacobian.

One line per (method, n): method n steps rejected fevals jevals seconds x_end
seconds: best of several solve_ivp calls; steps: counted in a second, untimed pass through the same
OdeSolver class that solve_ivp drives (solve_ivp does not report them); rejected is not reported by
SciPy (-1). Usage: regularized_peer.py [N_MAX]
"""
import sys
import time

import numpy as np
from scipy.integrate import LSODA, Radau, solve_ivp

T, DT, TOL = 30.0, 0.1, 1e-10


def problem(n):
    def f(t, y):
        return [y[1], -y[0] - min(max(n * y[1], -1.0), 1.0)]

    def jac(t, y):
        return [[0.0, 1.0], [-1.0, -n if abs(n * y[1]) < 1.0 else 0.0]]

    return f, jac


def count_steps(cls, f, jac):
    s = cls(f, 0.0, np.array([4.5, 0.0]), T, rtol=TOL, atol=TOL, jac=jac)
    steps = 0
    while s.status == "running":
        s.step()
        steps += 1
    if s.status != "finished":
        raise RuntimeError("step counting failed")
    return steps


def bench(name, cls, n):
    f, jac = problem(n)
    t_eval = np.linspace(0.0, T, int(round(T / DT)) + 1)
    best, spent, reps, sol = float("inf"), 0.0, 0, None
    while reps < 2 or (spent < 0.5 and reps < 50):
        t0 = time.perf_counter()
        sol = solve_ivp(f, (0.0, T), [4.5, 0.0], method=name, t_eval=t_eval, rtol=TOL, atol=TOL, jac=jac)
        t = time.perf_counter() - t0
        if not sol.success:
            raise RuntimeError(f"{name} n={n}: {sol.message}")
        best, spent, reps = min(best, t), spent + t, reps + 1
    steps = count_steps(cls, f, jac)
    print(f"{name} {n:g} {steps} -1 {sol.nfev} {sol.njev} {best:.6e} {sol.y[0, -1]:.12f}", flush=True)


def main():
    nmax = float(sys.argv[1]) if len(sys.argv) > 1 else 1e5
    for name, cls in (("Radau", Radau), ("LSODA", LSODA)):
        n = 10.0
        while n <= nmax * 1.0001:
            bench(name, cls, n)
            n *= 10


if __name__ == "__main__":
    main()
