"""A simulation's answer as numpy arrays: the Result of Client.simulate.

The daemon streams a run as NDJSON: a meta line, one line per sample, event lines, a summary line. Every
member of a sample other than ``type`` becomes a column here, whatever the model: a number per sample gives an
array of shape (samples,) (one mass: ``t``, ``x``, ``v``, ``Fs``, ``Fd``, ``Fc``); an array per sample gives
shape (samples, width) (a network's ``x``, ``v`` over its written nodes and ``Fs``, ``Fd``, ``phase``, ``Fn``
over its written elements; a linear complementarity system's ``x``, ``u``, ``w``; the right-hand solver's
``q``, ``qd``, ``qdd``, ``N``, ``mode``, ``margin``). So a new kind of row needs no change here.

Columns are collected into ``array('d')`` buffers while the stream arrives (8 bytes a number, not a Python
float object per number) and become numpy arrays when it ends. ``null`` in a numeric column is NaN; a column
with strings (``phase``: "stick"/"slip", ``mode``) is an object array holding "stick", "slip" and None.
"""

import math
from array import array

import numpy as np


class _Column:
    """One column while the stream arrives: floats in an array('d') until a string shows up, then objects.

    ``fast`` is the bound append (a number per sample) or extend (an array per sample) of the buffer; it
    raises TypeError for a null or a string, and ``slow`` then redoes that sample's value properly. This
    keeps the common case, all numbers, to one C call per value.
    """

    __slots__ = ("name", "width", "numbers", "objects", "fast")

    def __init__(self, name, first):
        self.name = name
        self.width = len(first) if isinstance(first, list) else None
        self.numbers = array("d")
        self.objects = None  # a list once the column turned out to hold strings
        self.fast = self.numbers.append if self.width is None else self.numbers.extend

    def slow(self, value, index):
        """Adds sample `index`'s value after `fast` refused it (it may have appended part of an array)."""
        if self.width is None:
            if isinstance(value, list):
                raise ValueError("column %r: a number in the first sample, an array in sample %d"
                                 % (self.name, index))
            del self.numbers[index:]
            if value is None:
                self.numbers.append(math.nan)
            elif isinstance(value, str):
                self._to_objects()
                self.objects.append(value)
            else:
                raise ValueError("column %r, sample %d: %r is not a number" % (self.name, index, value))
            return
        if not isinstance(value, list):
            raise ValueError("column %r: an array in the first sample, %r in sample %d" % (self.name, value, index))
        del self.numbers[index * self.width:]
        if any(isinstance(a, str) for a in value):
            self._to_objects()
            self.objects.extend(value)
        else:
            self.numbers.extend([math.nan if a is None else a for a in value])

    def _to_objects(self):
        # Before the first string, NaN stood for null: the daemon never writes NaN, so this is exact.
        self.objects = [None if math.isnan(a) else a for a in self.numbers]
        self.numbers = None
        self.fast = self.objects.append if self.width is None else self.objects.extend

    def finish(self, samples):
        data = self.objects if self.objects is not None else self.numbers
        expected = samples * (self.width or 1)
        if len(data) != expected:
            raise ValueError("column %r: %d values for %d samples of width %d (the rows changed width)"
                             % (self.name, len(data), samples, self.width or 1))
        if self.objects is not None:
            out = np.empty(len(self.objects), dtype=object)
            out[:] = self.objects
        else:
            out = np.frombuffer(self.numbers, dtype=np.float64).copy() if len(self.numbers) else np.empty(0)
        return out.reshape(samples) if self.width is None else out.reshape(samples, self.width)


class ResultBuilder:
    """Collects a stream's records (dicts with "type") into a Result; Client.simulate feeds it."""

    def __init__(self, spec=None):
        self.spec = spec
        self.meta = None
        self.summary = None
        self.events = []
        self.quakes = []
        self.samples = 0
        self._columns = None  # list of _Column, in the first sample's member order

    def add(self, record):
        kind = record.get("type")
        if kind == "sample":
            if self._columns is None:
                self._columns = [_Column(k, v) for k, v in record.items() if k != "type"]
            cols = self._columns
            if len(record) != len(cols) + 1:
                raise ValueError("sample %d has members %s, the first had %s"
                                 % (self.samples, sorted(record), sorted(c.name for c in cols)))
            index = self.samples
            for c in cols:
                value = record[c.name]
                try:
                    c.fast(value)
                except TypeError:
                    c.slow(value, index)
            self.samples += 1
        elif kind == "event":
            self.events.append({k: v for k, v in record.items() if k != "type"})
        elif kind == "quake":
            self.quakes.append({k: v for k, v in record.items() if k != "type"})
        elif kind == "meta":
            self.meta = {k: v for k, v in record.items() if k != "type"}
        elif kind == "summary":
            self.summary = {k: v for k, v in record.items() if k != "type"}

    def result(self):
        columns = {}
        for c in self._columns or ():
            columns[c.name] = c.finish(self.samples)
        if "t" not in columns:
            columns["t"] = np.empty(0)
        return Result(self.meta or {}, columns, self.events, self.summary or {}, self.spec, self.quakes)


class Result:
    """One simulation: ``meta``, the sample columns as numpy arrays, ``events``, ``summary``.

    ``r.t`` has shape (samples,). Every other sample member is an attribute and an item (``r.x``,
    ``r["Fs"]``): shape (samples,) when it is a number per sample, (samples, width) when it is an array per
    sample, width being the written nodes (``x``, ``v``) or elements (``Fs``, ``Fd``, ``phase``, ``Fn``) of a
    network, in the order ``r.nodes`` and ``r.elements`` give. ``r.names`` lists the columns in the order the
    daemon wrote them. ``r.events`` is a list of dicts (``kind``, ``t``, and the event's own members),
    ``r.meta`` the meta line (solver, parameters, well-posedness report), ``r.summary`` the summary line
    (``final`` state, ``steps``, ``stick_time``, ...), ``r.spec`` the request sent (when it was a dict).
    """

    def __init__(self, meta, columns, events, summary, spec=None, quakes=()):
        self.meta = meta
        self.summary = summary
        self.events = events
        self.spec = spec
        self._columns = columns
        self._quakes = list(quakes)
        self._quake_arrays = None

    # ---- the columns ----
    @property
    def names(self):
        """The sample columns, in the order the daemon wrote them."""
        return list(self._columns)

    def __getitem__(self, name):
        return self._columns[name]

    def __contains__(self, name):
        return name in self._columns

    def __getattr__(self, name):
        columns = self.__dict__.get("_columns")
        if columns is not None and name in columns:
            return columns[name]
        raise AttributeError("%r: not a column of this result (columns: %s)"
                             % (name, ", ".join(columns or ()) or "none"))

    def __len__(self):
        return len(self._columns["t"])

    @property
    def kind(self):
        """"one-mass", "network", "lcs", or the right-hand model's name (meta's ``model``)."""
        return self.meta.get("model", "one-mass")

    @property
    def nodes(self):
        """The node numbers of the node columns (a network's ``output.nodes``), or None."""
        return (self.meta.get("columns") or {}).get("nodes")

    @property
    def elements(self):
        """The element numbers of the element columns (a network's ``output.elements``), or None."""
        return (self.meta.get("columns") or {}).get("elements")

    def labels(self, name):
        """Labels of the columns of a 2-D column `name`: node or element numbers, the right-hand solver's
        coordinate names, else 0, 1, ..."""
        data = self._columns[name]
        if data.ndim == 1:
            return [name]
        groups = self.meta.get("columns") or {}
        by_group = {"x": "nodes", "v": "nodes", "Fs": "elements", "Fd": "elements", "phase": "elements",
                    "Fn": "elements", "p": "p", "qd": "q", "qdd": "q", "mode": "q"}
        labels = groups.get(name) or groups.get(by_group.get(name, ""))
        if labels is None or len(labels) != data.shape[1]:
            labels = list(range(data.shape[1]))
        return labels

    def __repr__(self):
        t = self._columns["t"]
        span = " t in [%g, %g]," % (t[0], t[-1]) if len(t) else ""
        return "<dashpot.Result %s: %d samples,%s %d events; columns %s>" % (
            self.kind, len(t), span, len(self.events), " ".join(
                "%s%s" % (k, "" if v.ndim == 1 else "[%d]" % v.shape[1]) for k, v in self._columns.items()))

    # ---- derived views ----
    def stick_intervals(self, element=None):
        """The time intervals [(t0, t1), ...] in which the damper sticks.

        One mass: leave `element` None. A network: the element's number. Built from the stick/slip events
        (the instants the solver located) and the first sample's phase; when the run was asked for no events
        (``output.events: false``), from the samples' phase, to the sample spacing.
        """
        t = self._columns["t"]
        if not len(t):
            return []
        phase = self._columns.get("phase")
        series = None  # this damper's phase at every sample, when the run wrote it
        if phase is not None and phase.ndim == 1:
            if element is not None:
                raise ValueError("a one-mass result has no elements")
            series = phase
        elif phase is not None:
            if element is None:
                raise ValueError("a network result: say which element")
            written = self.elements or list(range(phase.shape[1]))
            if element in written:
                series = phase[:, written.index(element)]
        output = self.spec.get("output", {}) if isinstance(self.spec, dict) else {}
        events = [e for e in self.events if e.get("kind") in ("stick", "slip") and e.get("element") == element]
        if output.get("events", True) is False:
            return self._intervals_from_phase(t, series)
        if series is not None:
            stuck = series[0] == "stick"
        else:  # the element's phase was not written: its first event says what it was doing before
            stuck = bool(events) and events[0]["kind"] == "slip"
        intervals, start = [], (t[0] if stuck else None)
        for e in events:
            if e["kind"] == "stick" and start is None:
                start = e["t"]
            elif e["kind"] == "slip" and start is not None:
                intervals.append((start, e["t"]))
                start = None
        if start is not None:
            intervals.append((start, t[-1]))
        return intervals

    @staticmethod
    def _intervals_from_phase(t, phase):
        if phase is None:
            return []
        intervals, start = [], None
        for ti, p in zip(t, phase):
            if p == "stick" and start is None:
                start = ti
            elif p != "stick" and start is not None:
                intervals.append((start, ti))
                start = None
        if start is not None:
            intervals.append((start, t[-1]))
        return intervals

    def events_frame(self):
        """The events as a pandas DataFrame (one row per event, one column per member); needs pandas."""
        try:
            import pandas as pd
        except ImportError as e:
            raise ImportError("events_frame() needs pandas (Debian: python3-pandas)") from e
        columns = []
        for e in self.events:
            for k in e:
                if k not in columns:
                    columns.append(k)
        return pd.DataFrame(self.events, columns=columns or ["kind", "t"])

    def to_frame(self):
        """The samples as a pandas DataFrame with one column per number, named as the daemon's CSV names
        them (``x0``, ``x2``, ``Fs0``, ... for a network); needs pandas."""
        try:
            import pandas as pd
        except ImportError as e:
            raise ImportError("to_frame() needs pandas (Debian: python3-pandas)") from e
        data = {}
        for name, values in self._columns.items():
            if values.ndim == 1:
                data[name] = values
            else:
                for j, label in enumerate(self.labels(name)):
                    data["%s%s" % (name, label)] = values[:, j]
        return pd.DataFrame(data)

    @property
    def quakes(self):
        """The quake lines of a run with ``output.quakes`` (docs/quakes.md) as a dict of numpy arrays, one per
        member (``t``, ``duration``, ``size``, ``hypocentre``, ``first``, ``last``, ``moment``, ``magnitude``,
        ``peak_rate``, ``open``), in the order the daemon wrote them; empty arrays without quakes."""
        if self._quake_arrays is None:
            from .quakes import quake_arrays
            self._quake_arrays = quake_arrays(self._quakes)
        return self._quake_arrays

    def plot_quakes(self, bins=30, fit=None, ax=None):
        """The Gutenberg–Richter plot of the quakes (dashpot.quakes.plot_quakes); needs matplotlib."""
        from .quakes import plot_quakes
        return plot_quakes(self, bins=bins, fit=fit, ax=ax)

    def plot(self, field="v", columns=None, events=True, fig=None):
        """A matplotlib Figure of the run (see dashpot.plotting.plot_result); needs matplotlib."""
        from .plotting import plot_result
        return plot_result(self, field=field, columns=columns, events=events, fig=fig)
