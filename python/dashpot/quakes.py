"""Quakes: the slip-event catalogue of a network run (``"output": {"quakes": true}``, docs/quakes.md).

``carlson_langer(n, ...)`` builds the Carlson–Langer chain (Carlson & Langer 1989) as a document: unit masses
on unit springs to the plate, springs l^2 between neighbours, friction
phi(v) = (1 - sigma) / (1 + 2 alpha |v| / (1 - sigma)) with static threshold 1, seen from the plate (the
ground moves at -nu). ``quake_arrays(records)`` turns the run's quake lines into numpy arrays, one per
member; ``gutenberg_richter(magnitudes)`` is the histogram of the magnitudes mu = ln(moment) and a
least-squares line through log10 of its non-empty counts; ``plot_quakes`` draws both.
"""

import random

import numpy as np

#: The members of a quake line, in the order the daemon writes them.
QUAKE_MEMBERS = ("t", "duration", "size", "hypocentre", "first", "last", "moment", "magnitude", "peak_rate",
                 "open")
_INTEGER = {"size", "hypocentre", "first", "last"}


def carlson_langer(n, l=3.0, sigma=0.01, alpha=2.5, nu=0.01, dt=0.05, t_end=5000.0, seed=1, x0=None):
    """The Carlson–Langer chain of `n` blocks as a simulation document (a dict), quakes on, samples and
    events off. `x0`: the initial offsets from the plate (default: uniform in [-1, 0), seeded by `seed`)."""
    if x0 is None:
        rng = random.Random(seed)
        x0 = [-rng.random() for _ in range(n)]
    c = 1.0 - sigma
    friction = {"law": "generalized-coulomb", "phi0": c, "phi1": 1, "belt_velocity": -nu,
                "relaxation": {"kind": "rational", "a": c, "b": c / (2 * alpha)}}
    elements = [{"between": ["ground", j], "spring": {"law": "linear", "k": 1}, "damper": dict(friction)}
                for j in range(n)]
    elements += [{"between": [j, j + 1], "spring": {"law": "linear", "k": l * l}} for j in range(n - 1)]
    return {"model": {"masses": [1] * n, "elements": elements}, "initial": {"x": list(x0)},
            "solver": {"kind": "stick-slip", "dt": dt, "t_end": t_end},
            "output": {"quakes": True, "samples": False, "events": False}}


def quake_arrays(quakes):
    """The quake lines (dicts) as a dict of numpy arrays, one per member: integers for size, hypocentre,
    first, last; booleans for open; floats otherwise (a null magnitude is NaN)."""
    out = {}
    for name in QUAKE_MEMBERS:
        values = [q.get(name) for q in quakes]
        if name in _INTEGER:
            out[name] = np.array(values, dtype=np.int64)
        elif name == "open":
            out[name] = np.array(values, dtype=bool)
        else:
            out[name] = np.array([np.nan if v is None else v for v in values], dtype=np.float64)
    return out


def gutenberg_richter(magnitudes, bins=30, fit=None):
    """The magnitude-frequency distribution: (centres, counts, slope, intercept) of a histogram of the finite
    `magnitudes` (`bins`: a count or the edges, as numpy.histogram takes them) and the least-squares line
    log10(count) = intercept + slope * mu over its non-empty bins, within [fit[0], fit[1]) when `fit` is
    given. slope and intercept are NaN with fewer than two bins to fit."""
    mu = np.asarray(magnitudes, dtype=np.float64)
    mu = mu[np.isfinite(mu)]
    if mu.size == 0:
        return np.empty(0), np.empty(0), np.nan, np.nan
    counts, edges = np.histogram(mu, bins=bins)
    centres = 0.5 * (edges[:-1] + edges[1:])
    use = counts > 0
    if fit is not None:
        use &= (centres >= fit[0]) & (centres < fit[1])
    if use.sum() < 2:
        return centres, counts, np.nan, np.nan
    slope, intercept = np.polyfit(centres[use], np.log10(counts[use]), 1)
    return centres, counts, float(slope), float(intercept)


def plot_quakes(result, bins=30, fit=None, ax=None):
    """The Gutenberg–Richter plot of a result's quakes: log10 of the count per magnitude bin against
    mu = ln(moment), with the fitted line and its slope in the legend. Returns the Figure."""
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise ImportError("plot_quakes() needs matplotlib (Debian: python3-matplotlib)") from e
    q = result.quakes
    centres, counts, slope, intercept = gutenberg_richter(q["magnitude"], bins=bins, fit=fit)
    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 4))
    else:
        fig = ax.figure
    use = counts > 0
    ax.plot(centres[use], np.log10(counts[use]), "o", color="tab:blue", label="%d quakes" % len(q["moment"]))
    if np.isfinite(slope):
        ax.plot(centres[use], intercept + slope * centres[use], "-", color="tab:red",
                label="slope %.3g per unit of mu" % slope)
    ax.set_xlabel("magnitude mu = ln(moment)")
    ax.set_ylabel("log10 count per bin")
    ax.set_title("Gutenberg–Richter: magnitude-frequency")
    ax.legend()
    return fig
