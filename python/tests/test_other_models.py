"""Contacts, linear complementarity and the analysis routes against closed forms: the bouncing ball's impact
times (Newton's restitution law), the RLC circuit with an ideal diode (Cibulka 2014, Example 1.9), every
solution of an LCP by enumeration of its bases, the roots and verdicts of a stability analysis and map
(Babováková 2012, model 1.2 and its condition (1.10)), the convergence study against the closed form, and
a well-posedness report of Pražák & Rajagopal 2016's counterexample."""

import math

import numpy as np
import pytest

from references import coulomb_free_oscillation, lcp_solutions, rlc_ideal_diode

G, E = 9.81, 0.5
BALL = {"model": {"masses": [1], "elements": [{"between": ["ground", 0], "contact": {"distance": 0, "restitution": E}}],
                  "forcing": [{"node": 0, "kind": "constant", "value": -G}]},
        "initial": {"x": [1], "v": [0]},
        "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 2, "theta": 0.5}, "output": {"every": 10}}


def test_bouncing_ball_impacts_are_newtons(client):
    """Dropped from 1: the first impact at t1 = sqrt(2/g) with speed v1 = sqrt(2 g); impact j rebounds at
    e^j v1 and the next comes 2 e^j v1 / g later; they accumulate at t_inf = t1 + 2 e v1 / (g (1 - e)),
    after which the ball rests on the table, held by Fn = -m g."""
    r = client.simulate(BALL)
    assert r.x.shape == r.Fn.shape == (len(r), 1)
    impacts = [e for e in r.events if e["kind"] == "impact"]
    t1, v1 = math.sqrt(2 / G), math.sqrt(2 * G)
    t_inf = t1 + 2 * E * v1 / (G * (1 - E))
    t = t1
    for j, impact in enumerate(impacts):
        # located inside the step: to rounding of the arcs' roots, far below dt = 1e-3
        assert abs(impact["t"] - t) < 1e-10 and abs(impact["du"] + E ** j * v1) < 1e-10
        assert abs(impact["du_after"] - E ** (j + 1) * v1) < 1e-10
        t += 2 * E ** (j + 1) * v1 / G
    assert len(impacts) > 30 and abs(impacts[-1]["t"] - t_inf) < 1e-9
    rest = r.t > t_inf + 1e-3
    assert np.all(np.abs(r.x[rest, 0]) < 1e-12) and np.all(r.v[rest, 0] == 0)
    assert np.allclose(r.Fn[rest, 0], -G, rtol=1e-12)
    frame = r.events_frame()
    assert len(frame) == len(r.events) and {"kind", "element", "t", "du", "du_after", "impulse"} <= set(frame.columns)


def test_rlc_circuit_with_an_ideal_diode(client):
    """x = (charge q, current i), 0 <= u = -v_D _|_ i >= 0. The current is the damped oscillation until its
    first zero t*, then the diode blocks: i = 0 and -v_D = q*/C for good. theta = 1/2 is second order while
    u = 0 (error ~ 4e-7 at dt = 1e-3: bounded here by 1e-6) and first order in the charge it stops at."""
    dt = 1e-3
    R, L, C = 0.5, 1.0, 0.25
    spec = {"model": {"lcs": {"A": [[0, 1], [-1 / (L * C), -R / L]], "B": [[0], [1 / L]], "C": [[0, 1]], "D": [[0]]},
                      "laws": [{"law": "complementarity"}]},
            "initial": {"x": [0, 1]}, "solver": {"kind": "stick-slip", "dt": dt, "t_end": 3, "theta": 0.5}}
    r = client.simulate(spec)
    assert r.kind == "lcs" and r.x.shape == (3001, 2) and r.u.shape == r.w.shape == (3001, 1)
    t_star, q_star, state = rlc_ideal_diode(R, L, C, 1.0)
    reference = np.array([state(t) for t in r.t])
    before, blocked = r.t < t_star, r.t > t_star + dt
    assert np.max(np.abs(r.x[before] - reference[before])) < 1e-6
    assert np.all(r.x[blocked, 1] == 0) and np.max(np.abs(r.x[blocked, 0] - q_star)) < 10 * dt ** 2 + dt * 1e-3
    assert np.allclose(r.u[blocked, 0], r.x[blocked, 0] / C, rtol=1e-12)
    assert np.all(r.u >= 0) and np.all(r.w >= 0) and np.all(r.u * r.w == 0)  # complementarity, exactly


def test_lcp_solutions_are_every_solution(client):
    """w = Mz + q, 0 <= z _|_ w >= 0 with M = [[1, 2], [3, 1]] (not a P-matrix: det = -5) and q = (-1, -1):
    the daemon's list is exactly the solutions found by trying every complementary basis in numpy."""
    M, q = [[1, 2], [3, 1]], [-1, -1]
    answer = client.lcp({"M": M, "q": q})
    ours = lcp_solutions(M, q)
    theirs = [np.array(s["z"]) for s in answer["solutions"]]
    assert answer["count"] == len(ours) == len(theirs) == 3
    for z in ours:
        assert any(np.allclose(z, s, atol=1e-12) for s in theirs)
    assert answer["theory"]["p_matrix"] is False and answer["theory"]["minor_witness"]["minor"] == -5
    z = np.array(answer["lemke"]["z"])
    w = np.array(M) @ z + q
    assert np.allclose(w, answer["lemke"]["w"], atol=1e-12) and abs(z @ w) < 1e-12


def test_stability_roots_and_verdict(client):
    """Model 1.2: p(z) = lambda m z^3 + m z^2 + mu2 z + mu1; numpy.roots as the reference, and the thesis'
    condition (1.10) mu2 - lambda mu1 > 0 for the verdict."""
    s = client.stability({"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]}})
    assert s.coefficients.tolist() == [0.5, 1, 1, 1]
    ours = np.sort_complex(np.roots([0.5, 1, 1, 1]))
    assert np.allclose(np.sort_complex(s.roots_complex), ours, rtol=1e-12, atol=1e-14)
    assert abs(s["spectral_abscissa"] - ours.real.max()) < 1e-12
    assert s["verdict"] == "asymptotically stable" and s["model"]["value"] == 0.5  # 1 - 0.5 * 1


def test_stability_map_against_the_closed_form(client):
    """A map of model 1.2 over mu2 = mu[1] and lambda = lambda[1]: every point's letter is the sign of
    (1.10) (M on the diagonal mu2 = lambda mu1, where the value is exactly 0) and its spectral abscissa is
    the largest real part of numpy's roots."""
    smap = client.stability({"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]},
                             "map": {"x": {"param": "mu[1]", "from": 0, "to": 2, "steps": 9},
                                     "y": {"param": "lambda[1]", "from": 0.25, "to": 1.75, "steps": 4}}})
    assert smap.abscissa.shape == smap.letters.shape == (4, 9)
    for j, lam in enumerate(smap.y):
        for i, mu2 in enumerate(smap.x):
            value = mu2 - lam * 1.0
            expected = "S" if value > 1e-12 else "U" if value < -1e-12 else "M"
            assert smap.letters[j, i] == expected, (mu2, lam)
            assert abs(smap.abscissa[j, i] - np.roots([lam, 1, mu2, 1]).real.max()) < 1e-12
    assert smap.counts == {"S": 16, "M": 4, "U": 16, "B": 0, "I": 0}


def test_convergence_errors_are_the_distance_to_the_closed_form(client):
    """The regularized scheme's study reports, per n, the largest distance to the exact solution on the
    samples; a regularized run with the same n, compared here with the closed form, gives that number, and
    the errors fall like 1/n (Pražák & Rajagopal 2016, (17))."""
    model = {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 1}}
    solver = {"kind": "regularized", "n": [10, 100, 1000], "t_end": 10, "dt": 0.5}
    study = client.convergence({"model": model, "initial": {"x": 4.5, "v": 0}, "solver": solver})
    _, state = coulomb_free_oscillation(4.5, 1, 1, 1)
    for row in study["rows"]:
        r = client.simulate({"model": model, "initial": {"x": 4.5, "v": 0}, "solver": dict(solver, n=row["n"])})
        exact = np.array([state(t)[0] for t in r.t])
        assert abs(np.max(np.abs(r.x - exact)) - row["err_x"]) < 1e-12
    assert 0.9 < study["rate_x"] < 1.1


def test_wellposedness_names_the_failing_hypothesis(client):
    """Generalized Coulomb with phi1 > phi0 is not monotone: no uniqueness, and the report points to the
    counterexample of Pražák & Rajagopal 2016, (24)-(25)."""
    report = client.wellposedness({"model": {"mass": 1, "spring": {"law": "linear", "k": 1},
                                             "damper": {"law": "generalized-coulomb", "phi0": 0.5, "phi1": 1}}})
    assert report["uniqueness"]["guaranteed"] is False
    assert any(c["holds"] is False and "monotone" in c["hypothesis"] for c in report["checks"])
    assert "(24)" in report["counterexample"]


@pytest.mark.parametrize("route", ["stability", "modes", "lcp"])
def test_analysis_routes_raise_problems_with_pointers(client, route):
    import dashpot
    bad = {"stability": {"mass": -1, "law": {"lambda": [1], "mu": [1]}},
           "modes": {"model": {"masses": [1, -1]}},
           "lcp": {"M": [[1, 2], [3, 4]], "q": [1]}}[route]
    with pytest.raises(dashpot.ProblemError) as info:
        getattr(client, route)(bad)
    expected = {"stability": "/mass", "modes": "/model/masses/1", "lcp": "/q"}[route]
    assert info.value.status == 422 and expected in info.value.pointers
