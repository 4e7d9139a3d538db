"""One mass with Coulomb friction against the closed form of Babováková 2012, (4.14)-(4.15): where and when
the mass stops, the whole trajectory, and the order of the stick-slip solver through the stick."""

import math

import numpy as np
import pytest

from references import coulomb_free_oscillation
from specs import coulomb_spec

# (x0, m, k, phi0): the README's decay (stops at 0.5 at t = 2 pi), and one whose last swing does not cross
# zero (turning points 5.3, -4.6, ..., -0.4, then -0.3 on the same side: |x| <= phi0/k = 0.35 there).
CASES = [(4.5, 1.0, 1.0, 1.0), (5.3, 0.5, 2.0, 0.7)]


@pytest.mark.parametrize("x0,m,k,phi0", CASES)
def test_analytic_solver_is_the_closed_form(client, x0, m, k, phi0):
    turns, state = coulomb_free_oscillation(x0, m, k, phi0)
    t_stop, x_stop = turns[-1]
    t_end = math.ceil(t_stop) + 1
    r = client.simulate(coulomb_spec(x0, m, k, phi0, {"kind": "analytic", "dt": 1e-3, "t_end": t_end}))
    assert r.meta["solver"] == "analytic"
    assert r.t.shape == r.x.shape == r.v.shape == r.phase.shape == (t_end * 1000 + 1,)
    # The analytic solver evaluates the same closed form: rounding only (the harmonic arcs' cos and sin).
    assert abs(r.x[-1] - x_stop) < 1e-12
    stick = [e for e in r.events if e["kind"] == "stick"]
    assert len(stick) == 1 and abs(stick[0]["t"] - t_stop) < 1e-12 and abs(stick[0]["x"] - x_stop) < 1e-12
    reference = np.array([state(t) for t in r.t])
    scale = abs(x0)
    assert np.max(np.abs(r.x - reference[:, 0])) < 1e-12 * scale
    assert np.max(np.abs(r.v - reference[:, 1])) < 1e-12 * scale * math.sqrt(k / m)
    # Sticking from t_stop on, slipping before; the summary's stick time is the rest of the run.
    assert set(r.phase[r.t > t_stop + 1e-9]) == {"stick"} and set(r.phase[r.t < t_stop - 1e-9]) == {"slip"}
    assert abs(r.summary["stick_time"] - (t_end - t_stop)) < 1e-12
    assert r.stick_intervals() == [(stick[0]["t"], t_end)]


@pytest.mark.parametrize("x0,m,k,phi0", CASES)
def test_stick_slip_theta_half_is_second_order_through_the_stick(client, x0, m, k, phi0):
    """theta = 1/2 with located events: the stop position to rounding, the stop instant and the trajectory
    to O(dt^2); halving dt divides the errors by 4 (the observed order within 0.1 of 2)."""
    turns, state = coulomb_free_oscillation(x0, m, k, phi0)
    t_stop, x_stop = turns[-1]
    t_end = math.ceil(t_stop) + 1
    errors = []
    for dt in (2e-3, 1e-3):
        r = client.simulate(coulomb_spec(x0, m, k, phi0, {"kind": "stick-slip", "dt": dt, "t_end": t_end,
                                                          "theta": 0.5}))
        # x at the turning point is where the trapezoidal rule's velocity reaches exactly zero: the stop
        # position is right to rounding even where the instant is off by O(dt^2) (measured: 2e-13).
        assert abs(r.x[-1] - x_stop) < 1e-9
        (stick,) = [e for e in r.events if e["kind"] == "stick"]
        reference = np.array([state(t) for t in r.t])
        errors.append((abs(stick["t"] - t_stop), np.max(np.abs(r.x - reference[:, 0]))))
    for coarse, fine in zip(*errors):
        assert fine < 5e-5 * abs(x0) and 1.9 < math.log2(coarse / fine) < 2.1, errors


def test_stick_intervals_from_the_phase_when_no_events_are_written(client):
    r = client.simulate(coulomb_spec(output={"every": 10, "events": False}))
    assert r.events == []
    (interval,) = r.stick_intervals()
    # Resolved to the written samples (every 10 steps of 1e-3): 2 pi rounded up to the next one.
    assert 0 <= interval[0] - 2 * math.pi <= 0.01 + 1e-9 and interval[1] == 10


def test_json_text_and_numpy_values_in_the_spec(client):
    """A spec may be JSON text, or a dict holding numpy numbers; both give the same run as the plain dict."""
    import json
    plain = coulomb_spec(solver={"kind": "analytic", "dt": 0.5, "t_end": 10})
    as_text = client.simulate(json.dumps(plain))
    with_numpy = dict(plain, initial={"x": np.float64(4.5), "v": np.int64(0)})
    for r in (as_text, client.simulate(with_numpy)):
        assert np.array_equal(r.x, client.simulate(plain).x)
