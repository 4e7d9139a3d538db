"""Pictures of results with matplotlib, imported only when a plot is asked for.

The figures are made with ``matplotlib.pyplot.subplots`` (so they show inline in Jupyter) but nothing here
calls ``show()`` or depends on a display: under the Agg backend (``MPLBACKEND=Agg``, or no display at all)
the returned Figure is saved with ``fig.savefig(...)``.

- One mass (and a network of one or two written nodes, a linear complementarity system, the right-hand
  solver): time series, one panel per column, with the stick phases shaded and the events marked as vertical
  lines (stick, slip, impact, ... each kind its colour).
- A network of three or more written nodes: a space-time picture, ``x`` or ``v`` of every written node
  against t as an image, with the stick/slip events of elements that join a node to the ground marked.
"""

import numpy as np

_EVENT_COLOURS = {"stick": "tab:blue", "slip": "tab:red", "impact": "tab:purple", "release": "tab:green",
                  "yield": "tab:orange", "unload": "tab:brown", "touch": "tab:pink", "separate": "tab:olive"}
_AXIS_LABELS = {"x": "x", "v": "v = x'", "Fs": "F_s", "Fd": "F_d", "Fc": "F_c", "Fn": "F_n (contact)",
                "u": "u", "w": "w", "q": "q", "qd": "q'", "qdd": "q''", "N": "N"}
_DEFAULT_PANELS = {"lcs": ("x", "u", "w")}


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise ImportError("plot() needs matplotlib (Debian: python3-matplotlib)") from e
    return plt


def plot_result(result, field="v", columns=None, events=True, fig=None):
    """A Figure of `result` (see the module's docstring). `columns`: the columns to draw as time series
    (default: x and v, or the model's own); `field`: the column of a network's space-time picture ("x" or
    "v"); `events`: mark the events; `fig`: draw into this Figure instead of a new one."""
    x = result["x"] if "x" in result else None
    if columns is None and result.kind == "network" and x is not None and x.ndim == 2 and x.shape[1] >= 3:
        return _space_time(result, field, events, fig)
    if columns is None:
        columns = _DEFAULT_PANELS.get(result.kind)
    if columns is None:
        candidates = ("x", "v") if "x" in result else ("q", "qd", "N")
        columns = [c for c in candidates if c in result]
    return _time_series(result, columns, events, fig)


def _numeric(data):
    return data.dtype != object


def _time_series(result, columns, events, fig):
    plt = _pyplot()
    columns = [c for c in columns if c in result and _numeric(result[c])]
    if not columns:
        raise ValueError("nothing to plot: the result has no numeric columns among %s" % (result.names,))
    if fig is None:
        fig, axes = plt.subplots(len(columns), 1, sharex=True, figsize=(8, 2.2 + 1.6 * len(columns)),
                                 squeeze=False)
        axes = axes[:, 0]
    else:
        axes = fig.subplots(len(columns), 1, sharex=True, squeeze=False)[:, 0]
    t = result.t
    bands = _stick_bands(result)
    for ax, name in zip(axes, columns):
        data = result[name]
        if data.ndim == 1:
            ax.plot(t, data, lw=1.2, color="black")
        else:
            for j, label in enumerate(result.labels(name)):
                ax.plot(t, data[:, j], lw=1.2, label="%s %s" % (name, label))
            if data.shape[1] <= 8:
                ax.legend(loc="upper right", fontsize="small")
        ax.set_ylabel(_AXIS_LABELS.get(name, name))
        for t0, t1 in bands:
            ax.axvspan(t0, t1, color="0.85", zorder=0, lw=0)
        if events:
            _event_lines(ax, result.events)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("t")
    title = _title(result)
    if bands:
        title += "; grey: sticking"
    axes[0].set_title(title, fontsize="medium")
    if events and result.events:
        handles = [plt.Line2D([], [], color=_EVENT_COLOURS.get(k, "0.4"), ls="--", label=k)
                   for k in sorted({e.get("kind") for e in result.events})]
        lines_legend = axes[0].get_legend()  # a second legend() would replace the columns' legend
        axes[0].legend(handles=handles, loc="lower right", fontsize="small", title="events")
        if lines_legend is not None:
            axes[0].add_artist(lines_legend)
    fig.tight_layout()
    return fig


def _stick_bands(result):
    """Stick intervals to shade: the one mass's, or a one-node network's single friction element's."""
    if "phase" not in result:
        return []
    phase = result.phase
    if phase.ndim == 1:
        return result.stick_intervals()
    # A network: shade only when one written element can stick (its phase column is not all null), so the
    # bands are unambiguous.
    can_stick = [j for j in range(phase.shape[1]) if any(p is not None for p in phase[:, j])]
    if len(can_stick) == 1:
        elements = result.elements or list(range(phase.shape[1]))
        return result.stick_intervals(elements[can_stick[0]])
    return []


def _event_lines(ax, evs, limit=400):
    # Past a few hundred events the lines are a grey wash; draw the first ones only.
    for e in evs[:limit]:
        ax.axvline(e["t"], color=_EVENT_COLOURS.get(e.get("kind"), "0.4"), ls="--", lw=0.8, alpha=0.8)


def _title(result):
    meta = result.meta
    parts = [meta.get("solver", "")]
    if result.kind == "one-mass":
        parts.append("spring %s, damper %s" % (meta.get("spring", "?"), meta.get("damper", "?")))
    else:
        parts.append(result.kind)
    if "dt" in meta:
        parts.append("dt = %g" % meta["dt"])
    return ", ".join(p for p in parts if p)


def _space_time(result, field, events, fig):
    plt = _pyplot()
    if field not in result or result[field].ndim != 2:
        raise ValueError("field %r is not a per-node column of this result" % field)
    data = result[field]
    t = result.t
    if fig is None:
        fig, ax = plt.subplots(figsize=(9, 4.5))
    else:
        ax = fig.subplots()
    n = data.shape[1]
    steps = np.diff(t)
    uniform = len(t) > 1 and np.allclose(steps, steps[0], rtol=1e-6, atol=0)
    if uniform:  # an image; its pixels centred on the samples and the written nodes
        half = steps[0] / 2
        image = ax.imshow(data.T, aspect="auto", origin="lower", interpolation="nearest", cmap="viridis",
                          extent=(t[0] - half, t[-1] + half, -0.5, n - 0.5))
    else:  # uneven sampling (a run's shorter last step): cells at the true times
        image = ax.pcolormesh(t, np.arange(n), data.T, shading="nearest", cmap="viridis")
    fig.colorbar(image, ax=ax, label=_AXIS_LABELS.get(field, field))
    nodes = result.nodes or list(range(n))
    ax.set_ylabel("node" if nodes == list(range(n)) else "node (column of output.nodes)")
    ax.set_xlabel("t")
    if events:
        _event_dots(ax, result, nodes)
    ax.set_title(_title(result) + ": %s of %d nodes" % (field, n), fontsize="medium")
    fig.tight_layout()
    return fig


def _event_dots(ax, result, nodes, limit=20000):
    """Marks the events of elements between the ground and one written node at (t, that node's row)."""
    elements = (result.spec or {}).get("model", {}).get("elements") if isinstance(result.spec, dict) else None
    if not elements:
        return
    row = {node: i for i, node in enumerate(nodes)}
    points = {}
    for e in result.events[:limit]:
        k = e.get("element")
        if k is None or k >= len(elements):
            continue
        ends = elements[k].get("between", [])
        node = [end for end in ends if end != "ground"]
        if len(ends) == 2 and "ground" in ends and len(node) == 1 and node[0] in row:
            points.setdefault(e.get("kind"), []).append((e["t"], row[node[0]]))
    on_image = {"stick": "white", "slip": "red"}  # the line colours vanish on viridis' dark end
    for kind, pts in sorted(points.items()):
        pts = np.array(pts)
        ax.plot(pts[:, 0], pts[:, 1], ls="none", marker=".", ms=2.5,
                color=on_image.get(kind, _EVENT_COLOURS.get(kind, "white")), label=kind)
    if points:
        ax.legend(loc="upper right", fontsize="small", markerscale=4, title="events")


def plot_stability_map(smap, ax=None):
    plt = _pyplot()
    from matplotlib.colors import TwoSlopeNorm
    if ax is None:
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
    else:
        fig = ax.figure
    x, y, a = smap.x, smap.y, smap.abscissa
    finite = a[np.isfinite(a)]
    # White at the boundary (abscissa 0); each side takes its colour scale from its own extreme.
    low = finite.min() if finite.size and finite.min() < 0 else -max(np.max(np.abs(finite)) if finite.size else 1, 1e-300)
    high = finite.max() if finite.size and finite.max() > 0 else -low
    image = ax.pcolormesh(x, y, a, shading="nearest", cmap="RdBu_r", norm=TwoSlopeNorm(0, low, high))
    fig.colorbar(image, ax=ax, label="spectral abscissa (< 0 stable)")
    if finite.size and np.nanmin(a) < 0 < np.nanmax(a) and len(x) > 1 and len(y) > 1:
        ax.contour(x, y, a, levels=[0], colors="black", linewidths=1)
    ax.set_xlabel(smap.x_param)
    ax.set_ylabel(smap.y_param)
    counts = smap.counts
    ax.set_title("stability map: %d stable, %d unstable, %d marginal"
                 % (counts.get("S", 0), counts.get("U", 0), counts.get("M", 0)), fontsize="medium")
    fig.tight_layout()
    return fig


def plot_response(response, ax=None):
    plt = _pyplot()
    if ax is None:
        fig, ax = plt.subplots(figsize=(7, 4))
    else:
        fig = ax.figure
    ax.loglog(response.omega, response.magnitude, color="black", lw=1.2)
    for r in response.get("resonances", ()):
        ax.axvline(r["omega"], color="tab:red", ls="--", lw=0.8)
    for r in response.get("antiresonances", ()):
        ax.axvline(r["omega"], color="tab:blue", ls=":", lw=0.8)
    ax.set_xlabel("omega (rad/s)")
    ax.set_ylabel("|H|")
    ax.set_title("receptance of node %s to a force at node %s (red: resonances, blue: antiresonances)"
                 % (response.get("response_node"), response.get("force_node")), fontsize="medium")
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    return fig
