"""Independent references the tests compare the daemon's numbers with: closed forms from the sources, written
here in Python from their formulas (not from dashpot's C code), and textbook linear algebra in numpy.
"""

import itertools
import math

import numpy as np


def coulomb_free_oscillation(x0, m, k, phi0):
    """The closed form of m x'' + k x + phi0 Sgn(x') = 0, x(0) = x0, x'(0) = 0 (Babováková 2012, (4.14)-(4.15);
    docs/mathematics.md section 4).

    While the mass moves it swings harmonically, omega = sqrt(k/m), about the centre c = sgn(x_j) phi0/k of
    the arc that starts at the turning point x_j (moving towards the origin, the friction pushes back towards
    x_j's side); each arc is half a period, and ends at the turning point 2c - x_j. The mass stops for good at
    the first turning point with |x_j| <= phi0/k. Returns (turning points [(t_j, x_j)], the state function).
    """
    omega = math.sqrt(k / m)
    half = math.pi / omega
    turns = [(0.0, x0)]
    while abs(turns[-1][1]) > phi0 / k:
        t, x = turns[-1]
        c = math.copysign(phi0 / k, x)
        turns.append((t + half, 2 * c - x))

    def state(t):
        """(x, v) at time t >= 0."""
        for (tj, xj), (tn, _) in zip(turns, turns[1:]):
            if t < tn:
                c = math.copysign(phi0 / k, xj)
                s = omega * (t - tj)
                return c + (xj - c) * math.cos(s), -(xj - c) * omega * math.sin(s)
        return turns[-1][1], 0.0

    return turns, state


def lcp_solutions(M, q):
    """Every solution of w = M z + q, 0 <= z _|_ w >= 0, by trying all 2^m complementary bases (numpy)."""
    M, q = np.asarray(M, float), np.asarray(q, float)
    m = len(q)
    found = []
    for basis in itertools.product([False, True], repeat=m):  # True: z_i may be > 0 (then w_i = 0)
        idx = [i for i in range(m) if basis[i]]
        z = np.zeros(m)
        if idx:
            sub = M[np.ix_(idx, idx)]
            if abs(np.linalg.det(sub)) < 1e-12:
                continue
            z[idx] = np.linalg.solve(sub, -q[idx])
        w = M @ z + q
        if (z >= -1e-12).all() and (w >= -1e-12).all():
            if not any(np.allclose(z, s, atol=1e-12) for s in found):
                found.append(z)
    return found


def rlc_ideal_diode(R, L, C, i0):
    """The series RLC circuit with an ideal diode, q(0) = 0, i(0) = i0 > 0, underdamped (Cibulka 2014,
    Example 1.9; docs/lcs.md): the current is the damped oscillation until its first zero t*, then the
    diode blocks and the charge stays q*. Returns (t*, q*, state function t -> (q, i))."""
    alpha = R / (2 * L)
    wd = math.sqrt(1 / (L * C) - alpha ** 2)

    def free(t):
        e = math.exp(-alpha * t)
        q = i0 * e * math.sin(wd * t) / wd
        i = i0 * e * (math.cos(wd * t) - alpha / wd * math.sin(wd * t))
        return q, i

    t_star = math.atan2(wd, alpha) / wd
    q_star = free(t_star)[0]
    return t_star, q_star, (lambda t: free(t) if t < t_star else (q_star, 0.0))
