"""The analysis routes' answers: the daemon's JSON as a dict, with the numbers a researcher computes with as
numpy arrays beside it.

Each class is a ``dict`` subclass holding the document exactly as the daemon sent it (so every member the
docs describe is there, and ``json.dumps`` still works); its properties only read from it. ``null`` numbers
(a receptance at an undamped resonance, a map point with no root) become NaN in the arrays.
"""

import numpy as np


def _floats(values):
    return np.array([np.nan if v is None else v for v in values], dtype=float)


class Stability(dict):
    """POST /v1/stability for one law (docs/stability.md): ``verdict``, ``roots``, ``hurwitz_minors``, ...

    ``roots_complex``: the roots of the characteristic polynomial as a complex array (the ``roots`` member
    keeps the daemon's list of {re, im, error})."""

    @property
    def roots_complex(self):
        return np.array([complex(r["re"], r["im"]) for r in self.get("roots") or ()], dtype=complex)

    @property
    def coefficients(self):
        """The characteristic polynomial's coefficients, highest power first (numpy.roots' order)."""
        return np.array(self["polynomial"]["coefficients"], dtype=float)


class StabilityMap(dict):
    """POST /v1/stability with a ``map``: the verdict and spectral abscissa over a grid of two coefficients.

    ``x``, ``y``: the grid values of the two swept coefficients (``x_param``, ``y_param`` name them);
    ``abscissa``: shape (len(y), len(x)), NaN where the polynomial has no root; ``letters``: the verdict
    letters, same shape (S stable, M marginal, U unstable, B near boundary, I ill-posed; ``legend`` says so);
    ``counts``: points per letter. ``plot()`` draws the map."""

    @property
    def _map(self):
        return self["map"]

    @staticmethod
    def _axis(axis):
        # The daemon's grid: from + (to - from) * i / (steps - 1), i = 0 .. steps - 1.
        return axis["from"] + (axis["to"] - axis["from"]) * np.arange(axis["steps"]) / (axis["steps"] - 1)

    @property
    def x(self):
        return self._axis(self._map["x"])

    @property
    def y(self):
        return self._axis(self._map["y"])

    @property
    def x_param(self):
        return self._map["x"]["param"]

    @property
    def y_param(self):
        return self._map["y"]["param"]

    @property
    def abscissa(self):
        return np.array([_floats(row) for row in self._map["spectral_abscissa"]], dtype=float)

    @property
    def letters(self):
        return np.array([list(row) for row in self._map["verdict"]])

    @property
    def counts(self):
        return dict(self._map["counts"])

    @property
    def legend(self):
        return dict(self._map["legend"])

    def plot(self, ax=None):
        """The spectral abscissa as an image (blue stable, red unstable), the boundary abscissa = 0 as a
        contour; returns the matplotlib Figure."""
        from .plotting import plot_stability_map
        return plot_stability_map(self, ax=ax)


class Modes(dict):
    """POST /v1/modes (docs/modes.md): ``modes`` (each with omega, frequency, shape, ...), ``damped``, ...

    ``omega``: the natural angular frequencies, ascending; ``shapes``: the mass-normalized mode shapes as
    columns, shape (nodes, modes), so ``shapes[:, k]`` is mode k (Phi^T M Phi = I); ``damping_ratio``."""

    @property
    def omega(self):
        return np.array([m["omega"] for m in self["modes"]], dtype=float)

    @property
    def shapes(self):
        return np.array([m["shape"] for m in self["modes"]], dtype=float).T

    @property
    def damping_ratio(self):
        return _floats([m.get("damping_ratio") for m in self["modes"]])


class Response(dict):
    """POST /v1/response (docs/modes.md): the receptance H_ji(omega) at the requested frequencies.

    ``omega``, ``magnitude``, ``phase`` as arrays (NaN where the daemon wrote null: an undamped system
    exactly at a resonance), ``H`` = magnitude * exp(i phase); ``resonances`` and ``antiresonances`` stay the
    daemon's lists. ``plot()`` draws |H| on log-log axes."""

    @property
    def omega(self):
        return _floats([r["omega"] for r in self["rows"]])

    @property
    def magnitude(self):
        return _floats([r["magnitude"] for r in self["rows"]])

    @property
    def phase(self):
        return _floats([r["phase"] for r in self["rows"]])

    @property
    def H(self):
        return self.magnitude * np.exp(1j * self.phase)

    def plot(self, ax=None):
        from .plotting import plot_response
        return plot_response(self, ax=ax)
