"""Quakes (docs/quakes.md): r.quakes as numpy arrays against a closed form (two blocks sliding to rest:
moments v0^2 / (2 phi), durations v0 / phi), the Carlson–Langer document builder against the law it asks for,
the Gutenberg–Richter fit against a made-up power law, and the plot."""

import numpy as np

import dashpot
from dashpot.quakes import gutenberg_richter


def test_quakes_are_arrays_with_the_closed_form(client):
    spec = {"model": {"masses": [1, 1],
                      "elements": [{"between": ["ground", 0], "damper": {"law": "coulomb", "phi0": 0.5}},
                                   {"between": ["ground", 1], "damper": {"law": "coulomb", "phi0": 0.5}}]},
            "initial": {"v": [1, 2.003]}, "solver": {"dt": 0.01, "t_end": 6},
            "output": {"quakes": True, "samples": False, "events": False}}
    q = client.simulate(spec).quakes
    assert q["size"].dtype == np.int64 and q["open"].dtype == bool and q["moment"].dtype == np.float64
    assert q["hypocentre"].tolist() == [0, 1] and q["size"].tolist() == [1, 1] and not q["open"].any()
    assert np.allclose(q["moment"], [1, 2.003 ** 2 / (2 * 0.5)], rtol=0, atol=1e-12)
    assert np.allclose(q["duration"], [2, 2.003 / 0.5], rtol=0, atol=1e-12)
    assert np.allclose(q["magnitude"], np.log(q["moment"]), rtol=0, atol=1e-15)


def test_no_quakes_gives_empty_arrays(client):
    r = client.simulate({"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "none"}},
                         "solver": {"dt": 0.1, "t_end": 1}})
    assert all(len(v) == 0 for v in r.quakes.values()) and "moment" in r.quakes


def test_carlson_langer_document_and_plot(client, tmp_path):
    doc = dashpot.carlson_langer(24, l=1, sigma=0.01, alpha=1, nu=0.01, dt=0.05, t_end=1500)
    el = doc["model"]["elements"][0]["damper"]
    # phi(v) = (1 - sigma)/(1 + 2 alpha v/(1 - sigma)) = phi0 - a v/(b + v) for v > 0 (docs/quakes.md)
    for v in (0.01, 0.3, 2.0):
        law = el["phi0"] - el["relaxation"]["a"] * v / (el["relaxation"]["b"] + v)
        assert abs(law - 0.99 / (1 + 2 * v / 0.99)) < 1e-15
    r = client.simulate(doc)
    q = r.quakes
    assert len(q["moment"]) > 50 and q["size"].max() <= 24 and (q["first"] <= q["hypocentre"]).all()
    # long run: about the plate's speed (the moments also count back-slip: docs/quakes.md)
    rate = q["moment"].sum() / (24 * 1500)
    assert abs(rate - 0.01) < 0.1 * 0.01, rate
    fig = r.plot_quakes()
    fig.savefig(tmp_path / "gr.png")
    assert (tmp_path / "gr.png").stat().st_size > 1000


def test_gutenberg_richter_fit_recovers_a_power_law():
    # counts 10^(4 - 0.5 mu) at mu = 0..6: magnitudes repeated that many times
    mu = np.concatenate([np.full(int(round(10 ** (4 - 0.5 * m))), m + 0.5) for m in range(7)])
    centres, counts, slope, intercept = gutenberg_richter(mu, bins=np.arange(0, 8))
    assert counts.sum() == len(mu)
    assert abs(slope + 0.5) < 0.01, slope
    _, _, none, _ = gutenberg_richter([1.0])
    assert np.isnan(none)
