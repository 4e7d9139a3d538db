"""Networks of masses: the shapes of the arrays (samples x written nodes, samples x written elements), their
names against the daemon's own CSV header, a linear chain against its modal solution (numpy), a one-node
network against the one-mass model, and the modes and receptance routes against numpy's eigensolver and a
direct solve."""

import copy
import io

import numpy as np
import requests

from specs import CHAIN, coulomb_spec


def test_network_arrays_have_one_column_per_written_node_and_element(client):
    r = client.simulate(CHAIN)
    samples = 20000 // 100 + 1
    assert r.kind == "network" and r.nodes == [0, 2] and r.elements == [0]
    assert r.t.shape == (samples,)
    assert r.x.shape == r.v.shape == (samples, 2)
    assert r.Fs.shape == r.Fd.shape == r.phase.shape == (samples, 1)
    # The first row of docs/networks.md: x = (1, 2) for nodes 0 and 2, node 0 slipping against phi0 = 0.3.
    assert r.x[0].tolist() == [1, 2] and r.Fd[0, 0] == -0.3 and r.phase[0, 0] == "slip"
    # Node 0 is held exactly (v = 0, no creep) while its element sticks.
    stuck = r.phase[:, 0] == "stick"
    assert stuck.any() and np.all(r.v[stuck, 0] == 0) and np.all(np.abs(r.Fd[stuck, 0]) <= 0.3)
    # Events name their element; the first stick is the one docs/networks.md shows.
    assert r.events[0]["kind"] == "stick" and r.events[0]["element"] == 0
    assert abs(r.events[0]["t"] - 13.239434242304677) < 1e-9


def test_frame_columns_are_the_daemons_csv_columns(client):
    """to_frame() names columns as the daemon's CSV does (x0, x2, v0, v2, Fs0, ...) and holds the same
    numbers: the CSV, parsed by pandas, is an independent reading of the same run."""
    import pandas as pd
    csv = requests.post(client.url + "/v1/simulate", json=CHAIN, headers={"Accept": "text/csv"}, timeout=30)
    csv.raise_for_status()
    # round_trip: the exact doubles (the daemon writes the shortest digits that read back as the same double)
    expected = pd.read_csv(io.StringIO(csv.text), float_precision="round_trip")
    frame = client.simulate(CHAIN).to_frame()
    assert list(frame.columns) == list(expected.columns) == ["t", "x0", "x2", "v0", "v2", "Fs0", "Fd0", "phase0"]
    numeric = [c for c in frame.columns if c != "phase0"]
    assert np.array_equal(frame[numeric].to_numpy(dtype=float), expected[numeric].to_numpy(dtype=float))
    assert list(frame["phase0"]) == list(expected["phase0"])


def test_linear_chain_matches_its_modal_solution(client):
    """Three masses on linear springs, free vibration: x(t) = Phi (a cos(w t) + b sin(w t) / w) with
    K Phi = M Phi diag(w^2) from numpy. The trapezoidal rule (theta = 1/2) is energy-conserving with a phase
    error of w^3 dt^2 t / 12 per mode; the tolerance is that bound summed over the modes' amplitudes."""
    m = np.array([1.0, 2.0, 1.5])
    k = [1.0, 2.0, 3.0]
    x0, v0 = np.array([1.0, -0.5, 2.0]), np.array([0.0, 0.3, 0.0])
    dt, t_end = 1e-3, 10.0
    spec = {"model": {"masses": m, "elements": [
        {"between": ["ground", 0], "spring": {"law": "linear", "k": k[0]}},
        {"between": [0, 1], "spring": {"law": "linear", "k": k[1]}},
        {"between": [1, 2], "spring": {"law": "linear", "k": k[2]}}]},
        "initial": {"x": x0, "v": v0}, "solver": {"dt": dt, "t_end": t_end, "theta": 0.5}, "output": {"every": 10}}
    r = client.simulate(spec)
    K = np.array([[k[0] + k[1], -k[1], 0], [-k[1], k[1] + k[2], -k[2]], [0, -k[2], k[2]]])
    Mh = np.diag(m ** -0.5)
    lam, Y = np.linalg.eigh(Mh @ K @ Mh)
    w, Phi = np.sqrt(lam), Mh @ Y  # Phi^T M Phi = I
    a, b = Phi.T @ (m * x0), Phi.T @ (m * v0)
    exact = (np.cos(np.outer(r.t, w)) * a + np.sin(np.outer(r.t, w)) * b / w) @ Phi.T
    amplitude = np.hypot(a, b / w)
    bound = np.sum(np.abs(Phi).max(axis=0) * amplitude * w ** 3) * dt ** 2 * t_end / 12
    error = np.max(np.abs(r.x - exact))
    assert error < bound and error > bound / 100, (error, bound)  # an O(dt^2) error, not zero by accident

    modes = client.modes(spec)
    assert np.allclose(modes.omega, w, rtol=1e-12, atol=0)
    assert np.allclose(modes.shapes.T @ np.diag(m) @ modes.shapes, np.eye(3), atol=1e-12)


def test_one_node_network_is_the_one_mass_model(client):
    """docs/networks.md: one node and one element ["ground", 0] is the one-mass equation, equal with located
    events to 1e-12."""
    one = coulomb_spec(solver={"kind": "stick-slip", "dt": 1e-3, "t_end": 10, "theta": 0.5}, output={"every": 50})
    net = copy.deepcopy(one)
    net["model"] = {"masses": [1.0], "elements": [{"between": ["ground", 0], "spring": one["model"]["spring"],
                                                   "damper": one["model"]["damper"]}]}
    net["initial"] = {"x": [4.5], "v": [0.0]}
    r1, rn = client.simulate(one), client.simulate(net)
    assert rn.x.shape == (len(r1), 1)
    assert np.max(np.abs(rn.x[:, 0] - r1.x)) < 1e-12 and np.max(np.abs(rn.v[:, 0] - r1.v)) < 1e-12
    assert list(rn.phase[:, 0]) == list(r1.phase)


def test_receptance_against_a_direct_solve(client):
    """H(w) = [(K - w^2 M + i w C)^-1]_ji solved by numpy at each frequency, Rayleigh damping C = aM + bK."""
    m = np.array([1.0, 1.0, 1.0])
    spec = {"model": {"masses": m, "elements": [
        {"between": ["ground", 0], "spring": {"law": "linear", "k": 4}},
        {"between": [0, 1], "spring": {"law": "linear", "k": 4}},
        {"between": [1, 2], "spring": {"law": "linear", "k": 4}, "damper": {"law": "coulomb", "phi0": 0.3}}]},
        "damping": {"rayleigh": {"alpha": 0.05, "beta": 0.01}},
        "force_node": 0, "response_node": 2, "omega": {"from": 0.1, "to": 10, "points": 200, "spacing": "log"}}
    resp = client.response(spec)
    assert resp["left_out"] == [2]  # the Coulomb damper is not linear: left out of the analysis
    K = 4 * np.array([[2, -1, 0], [-1, 2, -1], [0, -1, 1]])
    M = np.diag(m)
    C = 0.05 * M + 0.01 * K
    H = np.array([np.linalg.solve(K - w * w * M + 1j * w * C, np.eye(3)[0])[2] for w in resp.omega])
    assert resp.omega.shape == (200,)
    assert np.allclose(resp.H, H, rtol=1e-10, atol=0)
    lam = np.sqrt(np.linalg.eigvalsh(K))  # M = I
    assert np.allclose([r["omega"] for r in resp["resonances"]], lam, rtol=1e-12)
