"""scripts/gallery.py - draws the README's gallery (docs/images/*.png) from the CLI's output.

Usage: gallery.py DASHPOT_BINARY OUT_DIR (scripts/gallery.sh and `make gallery` call it with build/dashpot
and docs/images). Every picture is one or a few `dashpot` runs of the documents below, drawn with
matplotlib (Debian's python3-matplotlib). Nothing is random, the PNGs carry no time stamp nor version
string, so the same build and the same Debian packages give the same bytes.
"""
import csv
import io
import json
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

BIN, OUT = sys.argv[1], sys.argv[2]
os.makedirs(OUT, exist_ok=True)
plt.rcParams.update({"font.size": 9, "axes.titlesize": 10, "figure.dpi": 100, "savefig.dpi": 100,
                     "axes.grid": True, "grid.alpha": 0.3, "legend.fontsize": 8, "legend.framealpha": 0.8})


def dashpot(cmd, doc, fmt):
    """Runs `dashpot CMD -` (with `--format FMT` if given) on the document; returns its standard output."""
    args = [BIN, cmd, "-"] + (["--format", fmt] if fmt else []) + (["--quiet"] if cmd == "simulate" else [])
    return subprocess.run(args, input=json.dumps(doc), capture_output=True, text=True, check=True).stdout


def rows(doc):
    """The CSV rows of a simulation, as a dict of columns (floats; '' for empty fields)."""
    table = list(csv.DictReader(io.StringIO(dashpot("simulate", doc, "csv"))))
    return {k: [float(r[k]) if r[k] not in ("", "stick", "slip") else r[k] for r in table] for k in table[0]}


def records(doc, cmd="simulate"):
    return [json.loads(line) for line in dashpot(cmd, doc, "ndjson").splitlines()]


def save(fig, name):
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, name), metadata={"Software": None})
    plt.close(fig)
    print(os.path.join(OUT, name))


def stick_spans(t, phase):
    """The [t0, t1] intervals where the phase column says stick."""
    spans, start = [], None
    for ti, p in zip(t, phase):
        if p == "stick" and start is None:
            start = ti
        elif p != "stick" and start is not None:
            spans.append((start, ti))
            start = None
    if start is not None:
        spans.append((start, t[-1]))
    return spans


# 1. The thesis' Fig. 4.2: Coulomb friction, x0 = 1..5, with and without the relaxation gamma (algorithm 4.1).
fig, axes = plt.subplots(1, 2, figsize=(7.2, 3.4), sharey=True)
for ax, relaxed in zip(axes, (False, True)):
    for x0 in (1, 2, 3, 4, 5):
        damper = {"law": "coulomb", "phi0": 1}
        if relaxed:
            damper["relaxation"] = {"kind": "rational", "a": 0.5, "b": 1}
        r = rows({"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": damper},
                  "initial": {"x": x0, "v": 0},
                  "solver": {"kind": "stick-slip", "variant": "thesis", "dt": 1e-3, "t_end": 10, "Z": 100,
                             "eps": 1e-4},
                  "output": {"every": 10}})
        ax.plot(r["x"], r["v"], lw=1, label=f"x0 = {x0}")
    ax.axvspan(-1, 1, color="0.85", zorder=0)
    ax.set_xlabel("x")
    ax.set_title("γ = 0.5 v/(1 + |v|)" if relaxed else "Coulomb friction, γ = 0")
axes[0].set_ylabel("v = x'")
axes[0].legend(loc="lower left")
fig.suptitle("Phase portraits of the thesis' Fig. 4.2 (grey: the equilibria |x| ≤ φ0/k)", fontsize=10)
save(fig, "coulomb.png")

# 2. Stick-slip on a belt: static threshold phi1 above the kinetic phi0, a limit cycle.
r = rows({"model": {"mass": 1, "spring": {"law": "linear", "k": 1},
                    "damper": {"law": "generalized-coulomb", "phi0": 0.8, "phi1": 1, "belt_velocity": 0.4}},
          "initial": {"x": 0, "v": 0.4},
          "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 30, "theta": 0.5},
          "output": {"every": 10}})
fig, (a1, a2) = plt.subplots(1, 2, figsize=(7.2, 3.2), gridspec_kw={"width_ratios": [1.6, 1]})
for t0, t1 in stick_spans(r["t"], r["phase"]):
    a1.axvspan(t0, t1, color="tab:orange", alpha=0.15, lw=0)
a1.plot(r["t"], r["x"], label="x")
a1.plot(r["t"], r["v"], label="v")
a1.axhline(0.4, color="0.4", ls=":", lw=1)
a1.set_xlabel("t")
a1.set_title("Riding the belt (shaded: stick), slipping back")
a1.legend(loc="lower right")
a2.plot(r["x"], r["v"], lw=1, color="tab:purple")
a2.set_xlabel("x")
a2.set_ylabel("v")
a2.set_title("Limit cycle")
save(fig, "belt.png")

# 3. An elastic-plastic (Jenkins) spring near resonance: hysteresis loops.
r = rows({"model": {"mass": 1, "spring": {"law": "elastoplastic", "k": 1, "yield": 0.5},
                    "damper": {"law": "linear", "c": 0.05},
                    "forcing": {"kind": "harmonic", "amplitude": 0.6, "omega": 0.8}},
          "initial": {"x": 0, "v": 0},
          "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 60, "theta": 0.5},
          "output": {"every": 10}})
fig, (a1, a2) = plt.subplots(1, 2, figsize=(7.2, 3.2), gridspec_kw={"width_ratios": [1.6, 1]})
a1.plot(r["t"], r["x"], label="x")
a1.plot(r["t"], r["p"], label="plastic offset p")
a1.set_xlabel("t")
a1.set_title("Jenkins spring k = 1, yield 0.5, F = 0.6 cos 0.8t")
a1.legend(loc="upper left")
a2.plot(r["x"], r["Fs"], lw=1, color="tab:red")
a2.set_xlabel("x")
a2.set_ylabel("spring force Fs")
a2.set_title("Hysteresis")
save(fig, "hysteresis.png")

# 4. A bouncing ball: located impacts accumulating at t_inf, then rest on the table.
g, e = 9.81, 0.8
ball = {"model": {"masses": [1],
                  "elements": [{"between": ["ground", 0], "contact": {"distance": 0, "restitution": e}}],
                  "forcing": [{"node": 0, "kind": "constant", "value": -g}]},
        "initial": {"x": [1], "v": [0]},
        "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 5, "theta": 0.5},
        "output": {"every": 5}}
rec = records(ball)
samples = [o for o in rec if o["type"] == "sample"]
impacts = [o for o in rec if o.get("kind") == "impact"]
t_inf = math.sqrt(2 / g) + 2 * e * math.sqrt(2 * g) / (g * (1 - e))
fig, ax = plt.subplots(figsize=(7.2, 3.0))
ax.plot([s["t"] for s in samples], [s["x"][0] for s in samples], label="height x")
ax.plot([i["t"] for i in impacts], [0] * len(impacts), "|", color="tab:red", ms=10,
        label=f"{len(impacts)} located impacts")
ax.axvline(t_inf, color="0.4", ls="--", lw=1, label=f"t∞ = {t_inf:.4f} (closed form)")
ax.set_xlabel("t")
ax.set_title(f"Ball dropped on a table, restitution e = {e}: impacts accumulate, then it rests")
ax.legend(loc="upper right")
save(fig, "ball.png")

# 5. A Burridge-Knopoff chain of 60 blocks (the browser page's preset): slip fronts in space and time.
n, V, kp, kc, alpha, vf = 60, 0.1, 1, 0.5, 0.5, 0.05
elements, x0 = [], []
for i in range(n):
    phi0 = round(1 + math.sin(7.3 * i) ** 2, 3)
    elements.append({"between": ["ground", i], "spring": {"law": "linear", "k": kp},
                     "damper": {"law": "coulomb", "phi0": phi0, "belt_velocity": -V,
                                "relaxation": {"kind": "rational", "a": round(alpha * phi0, 4), "b": vf}}})
    x0.append(round(-(phi0 / kp) * (0.3 + 0.65 * math.sin(3.1 * i) ** 2), 3))
elements += [{"between": [i, i + 1], "spring": {"law": "linear", "k": kc}} for i in range(n - 1)]
rec = records({"model": {"masses": [1] * n, "elements": elements},
               "initial": {"x": x0, "v": [-V] * n},
               "solver": {"kind": "stick-slip", "dt": 0.01, "t_end": 100, "theta": 0.5},
               "output": {"every": 10, "elements": [0]}})
samples = [o for o in rec if o["type"] == "sample"]
speed = [[v + V for v in s["v"]] for s in samples]  # speed relative to the plate; 0 where stuck to the ground
fig, ax = plt.subplots(figsize=(7.2, 3.0))
im = ax.imshow(list(map(list, zip(*speed))), aspect="auto", origin="lower", cmap="magma",
               extent=(samples[0]["t"], samples[-1]["t"], -0.5, n - 0.5), interpolation="nearest")
fig.colorbar(im, ax=ax, label="block speed + V")
ax.set_xlabel("t")
ax.set_ylabel("block")
ax.grid(False)
ax.set_title("Burridge–Knopoff chain, 60 blocks, velocity-weakening friction: slip events")
save(fig, "burridge-knopoff.png")

# 6. Modes and receptance of a 3-mass chain (the friction element left out of the linear analysis).
chain = {"model": {"masses": [1, 2, 1.5], "elements": [
    {"between": ["ground", 0], "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.3}},
    {"between": [0, 1], "spring": {"law": "linear", "k": 2}},
    {"between": [1, 2], "spring": {"law": "linear", "k": 1}, "damper": {"law": "linear", "c": 0.1}}]},
    "force_node": 0, "response_node": 0, "omega": {"from": 0.1, "to": 3, "points": 400, "spacing": "log"}}
modes = json.loads(dashpot("modes", chain, None))["modes"]
resp = records(chain, "response")
meta, points = resp[0], resp[1:]
fig, (a1, a2) = plt.subplots(1, 2, figsize=(7.2, 3.2), gridspec_kw={"width_ratios": [1, 1.6]})
for m in modes:
    a1.plot(range(3), m["shape"], "o-", label=f"ω = {m['omega']:.4f}")
a1.set_xticks(range(3))
a1.set_xlabel("node")
a1.set_title("Mode shapes (φᵀMφ = 1)")
a1.legend(loc="lower left")
a2.loglog([p["omega"] for p in points], [p["magnitude"] for p in points], color="k", lw=1)
for r_ in meta["resonances"]:
    a2.axvline(r_["omega"], color="tab:red", lw=1, ls="--")
for a_ in meta["antiresonances"]:
    a2.axvline(a_["omega"], color="tab:blue", lw=1, ls=":")
a2.set_xlabel("ω")
a2.set_title("|H₀₀(ω)|: resonances (red), antiresonances (blue)")
save(fig, "modes.png")

# 7. A stability map of the model of the thesis' §1.2, F_V + λ F_V' = μ1 x + μ2 x', against its condition (1.10).
doc = {"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]},
       "map": {"x": {"param": "mu[1]", "from": 0, "to": 3, "steps": 240},
               "y": {"param": "lambda[1]", "from": 0.05, "to": 2, "steps": 160}}}
m = json.loads(dashpot("stability", doc, "json"))["map"]
ab = [[float("nan") if a is None else a for a in row] for row in m["spectral_abscissa"]]
lim = max(abs(a) for row in ab for a in row if a == a)
shade = [[math.copysign(math.sqrt(abs(a) / lim), a) for a in row] for row in ab]  # as the SVG map shades it
fig, ax = plt.subplots(figsize=(7.2, 3.2))
im = ax.imshow(shade, origin="lower", aspect="auto", cmap="coolwarm", vmin=-1, vmax=1,
               extent=(0, 3, 0.05, 2), interpolation="nearest")
fig.colorbar(im, ax=ax, label="spectral abscissa, √ scale\n(blue: stable, red: unstable)")
ax.plot([0.05, 2], [0.05, 2], color="k", lw=1.5, label="(1.10): μ2 − λ μ1 = 0")
ax.set_xlabel("μ2")
ax.set_ylabel("λ")
ax.grid(False)
ax.legend(loc="upper left")
ax.set_title("Stability of F_V + λ F_V' = x + μ2 x' (the model of the thesis' §1.2, m = 1)")
save(fig, "stability.png")

# 8. Friction whose normal force depends on the motion: Matrosov & Finogenko's piston and hinge.
rec = records({"model": {"kind": "piston-hinge", "m1": 1, "m2": 1, "J_C": 0.1, "r": 0.5, "alpha": 0.3,
                         "f1": 0.2, "f2": 0.02},
               "initial": {"x": [0, 0.8], "v": [0, 0]},
               "solver": {"kind": "right-hand", "t_end": 3, "dt": 0.01}})
samples = [o for o in rec if o["type"] == "sample"]
events = [o for o in rec if o["type"] == "event"]
t = [s["t"] for s in samples]
fig, (a1, a2) = plt.subplots(1, 2, figsize=(7.2, 3.2))
a1.plot(t, [s["q"][0] for s in samples], label="piston x")
a1.plot(t, [s["q"][1] for s in samples], label="body angle β")
a2.plot(t, [s["N"][0] for s in samples], label="N1 (tube)")
a2.plot(t, [s["N"][1] for s in samples], label="|N2| (hinge)")
for ax in (a1, a2):
    for ev in events:
        ax.axvline(ev["t"], color="0.5", lw=0.8, ls=":")
    ax.set_xlabel("t")
    ax.legend(loc="best")
a1.set_title("Piston held by friction, then sliding")
a2.set_title("Normal forces follow the accelerations")
save(fig, "painleve.png")

# 9. Circuits as linear complementarity systems: series RLC with an ideal and with a breakdown diode.
fig, ax = plt.subplots(figsize=(7.2, 3.0))
A = [[0, 1], [-4, -0.5]]
for label, lcs, law, style in (
        ("ideal diode", {"B": [[0], [1]], "C": [[0, 1]], "D": [[0]]}, {"law": "complementarity"}, "-"),
        ("breakdown diode, V_b = 0.5", {"B": [[0], [-1]], "C": [[0, -1]]},
         {"law": "interval", "min": -0.5, "max": 0}, "--")):
    r = rows({"model": {"lcs": dict(A=A, **lcs), "laws": [law]}, "initial": {"x": [0, 1]},
              "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 6, "theta": 0.5},
              "output": {"every": 10}})
    ax.plot(r["t"], r["x0"], style, color="tab:blue", label=f"charge q, {label}")
    ax.plot(r["t"], r["x1"], style, color="tab:green", label=f"current i, {label}")
ax.set_xlabel("t")
ax.set_title("Series RLC (R = 0.5, L = 1, C = 0.25) with a diode: complementarity and interval laws")
ax.legend(loc="upper right", ncol=2)
save(fig, "diode.png")
