#!/usr/bin/env python3
"""bench/contact_cases.py - the cases of bench/contact.sh and their checks, in one place so that
Siconos' peer (bench/contact_peer.cpp, a text case) and dashpot (a network document) are given the same
model from one definition, and both are judged by the same code.

  contact_cases.py write CASE DIR [steps=N] [theta=T]   writes DIR/CASE.txt (peer) and DIR/CASE.json (dashpot)
  contact_cases.py ball-check ROWS e h                 the peer's ball against the closed form
  contact_cases.py compare ROWS NDJSON                 peer rows against dashpot's samples, max |dx|, |dv|
Exit status 1 when a check fails, with the reason on stderr.
"""
import json
import math
import sys

G = 9.81


def ball(e):
    """The bouncing ball: m = 1 released at x = 1 above a floor at 0, gravity g, restitution e."""
    return {"masses": [1.0], "x0": [1.0], "v0": [0.0], "springs": [], "dampers": [],
            "forces": [(0, -G)], "contacts": [("ground", 0, 0.0, e)], "h": 1e-3, "steps": 3000}


def pair():
    """Two masses on top of each other, joined by a zero-length spring k = 10: the lower one (node 0) over
    the floor (contact, e = 0.8), the upper one (node 1) kept d = 0.5 above it by a contact (e = 0.5)."""
    return {"masses": [1.0, 0.5], "x0": [1.0, 2.0], "v0": [0.0, 0.0], "springs": [(0, 1, 10.0)],
            "dampers": [], "forces": [(0, -G), (1, -0.5 * G)],
            "contacts": [("ground", 0, 0.0, 0.8), (0, 1, 0.5, 0.5)], "h": 1e-3, "steps": 4000}


def chain(n):
    """n blocks on ground springs kg = 1, neighbour springs kc = 10, each with a stop x_i >= d_i,
    d_i = -(0.9 + 0.3 sin 2.3 i) (e = 0.5), pushed down by a load -2 on every block (rest at -2 without
    stops), x_i(0) = 0.5 cos 1.3 i: in 2000 steps 72 blocks reach their stop (about 135 impacts)."""
    springs = [("ground", i, 1.0) for i in range(n)] + [(i, i + 1, 10.0) for i in range(n - 1)]
    contacts = [("ground", i, -(0.9 + 0.3 * math.sin(2.3 * i)), 0.5) for i in range(n)]
    return {"masses": [1.0] * n, "x0": [0.5 * math.cos(1.3 * i) for i in range(n)], "v0": [0.0] * n,
            "springs": springs, "dampers": [], "forces": [(i, -2.0) for i in range(n)],
            "contacts": contacts, "h": 1e-3, "steps": 2000}


CASES = {"ball_e0.9": lambda: ball(0.9), "ball_e0.5": lambda: ball(0.5), "ball_e0": lambda: ball(0.0),
         "pair": pair, "chain100": lambda: chain(100)}


def peer_text(c, theta):
    lines = ["masses " + " ".join(repr(m) for m in c["masses"]),
             "x0 " + " ".join(repr(x) for x in c["x0"]), "v0 " + " ".join(repr(v) for v in c["v0"])]
    lines += ["spring %s %s %r" % s for s in c["springs"]] + ["damper %s %s %r" % d for d in c["dampers"]]
    lines += ["force %d %r" % f for f in c["forces"]] + ["contact %s %s %r %r" % k for k in c["contacts"]]
    lines += ["h %r" % c["h"], "steps %d" % c["steps"], "theta %r" % theta]
    return "\n".join(lines) + "\n"


def dashpot_document(c, theta, every=1):
    elements = [{"between": [a, b], "spring": {"law": "linear", "k": k}} for a, b, k in c["springs"]]
    elements += [{"between": [a, b], "damper": {"law": "linear", "c": k}} for a, b, k in c["dampers"]]
    elements += [{"between": [a, b], "contact": {"distance": d, "restitution": e}}
                 for a, b, d, e in c["contacts"]]
    model = {"masses": c["masses"], "elements": elements,
             "forcing": [{"node": i, "kind": "constant", "value": f} for i, f in c["forces"]]}
    solver = {"kind": "stick-slip", "dt": c["h"], "t_end": c["steps"] * c["h"], "theta": theta,
              "events": "none"}
    return {"model": model, "initial": {"x": c["x0"], "v": c["v0"]}, "solver": solver,
            "output": {"every": every}}


def write(name, directory, args):
    c = CASES[name]()
    opts = dict(a.split("=", 1) for a in args)
    c["steps"] = int(opts.get("steps", c["steps"]))
    theta = float(opts.get("theta", 0.5))
    every = int(opts.get("every", 1))
    with open("%s/%s.txt" % (directory, name), "w") as f:
        f.write(peer_text(c, theta))
    with open("%s/%s.json" % (directory, name), "w") as f:
        json.dump(dashpot_document(c, theta, every), f)


def read_rows(path):
    with open(path) as f:
        return [[float(w) for w in line.split()] for line in f if line.strip()]


def exact_impacts(e, x0=1.0, count=4):
    """Impact instants of the exact ball: t1 = sqrt(2 x0 / g), then flights of 2 e^k V / g."""
    v = math.sqrt(2 * G * x0)
    t = [math.sqrt(2 * x0 / G)]
    for _ in range(count - 1):
        v *= e
        t.append(t[-1] + 2 * v / G)
    return t, math.sqrt(2 * G * x0)


def ball_check(path, e, h):
    """Moreau-Jean without location puts an impact in the step whose start has x + h v / 2 <= 0, so the
    first impact's step ends between h/2 and 3h/2 after the exact instant (for a ball at rest before it,
    the theta = 1/2 flight is exact). Each impact restitutes e times the velocity of the step's start (up
    to g h off the exact one) from a position up to h |v| inside the floor, which moves the next flight by
    a few h either way: the k-th impact is allowed |late| <= 2 k h (first order; a factor 2 in g or e moves
    the second impact by 0.1 s or more).
    The law itself holds to rounding: the velocity after an impact step is -e times the one before it."""
    rows, fails = read_rows(path), []
    steps = [(a, b) for a, b in zip(rows, rows[1:]) if a[2] < 0 <= b[2]]
    texact, v1 = exact_impacts(e)
    want = len(texact) if e > 0 else 1
    if len(steps) < want:
        fails.append("%d impact(s), the exact ball has %d or more before t = %g" % (len(steps), want, rows[-1][0]))
    for k, (a, b) in enumerate(steps[:want], start=1):
        late = b[0] - texact[k - 1]
        lo, hi = (0.5 * h, 1.5 * h) if k == 1 else (-2 * k * h, 2 * k * h)
        print("    impact %d: step ends t = %.4f, exact %.6f, late by %5.2f h (allowed [%g, %g] h); v+/v- = %.15g"
              % (k, b[0], texact[k - 1], late / h, lo / h, hi / h, b[2] / a[2]))
        if not lo - 1e-12 <= late <= hi + 1e-12:
            fails.append("impact %d at %.6f, exact %.6f" % (k, b[0], texact[k - 1]))
        if abs(b[2] / a[2] + e) > 1e-12:
            fails.append("impact %d: v+/v- = %.17g, not -e" % (k, b[2] / a[2]))
    if e == 0:
        rest = [r for r in rows if r[0] > steps[0][1][0]] if steps else []
        if any(r[2] != 0 or abs(r[1]) > h * v1 for r in rest):
            fails.append("e = 0: the ball does not stay at rest within h V of the floor after its impact")
    return fails


def compare(peer_path, ndjson_path):
    """Max |dx|, |dv| over every common sample; the tolerance: rounding (1e-12 of the motion's scale)
    grown by the number of steps (each step's solve amplifies it by at most a few)."""
    peer = read_rows(peer_path)
    with open(ndjson_path) as f:
        samples = [s for s in map(json.loads, f) if s.get("type") == "sample"]
    n = (len(peer[0]) - 1) // 2
    if len(samples) != len(peer):
        return ["%d dashpot samples, %d peer rows" % (len(samples), len(peer))], 0, 0
    dx = dv = scale = 0.0
    for s, r in zip(samples, peer):
        if abs(s["t"] - r[0]) > 1e-9:
            return ["sample times differ: %r vs %r" % (s["t"], r[0])], 0, 0
        dx = max(dx, max(abs(a - b) for a, b in zip(s["x"], r[1:1 + n])))
        dv = max(dv, max(abs(a - b) for a, b in zip(s["v"], r[1 + n:])))
        scale = max(scale, max(abs(w) for w in r[1:]))
    tol = 1e-12 * len(peer) * max(scale, 1.0)
    fails = ["max |dx| %.3g, |dv| %.3g > %.3g" % (dx, dv, tol)] if max(dx, dv) > tol else []
    return fails, dx, dv


def main(argv):
    if len(argv) >= 3 and argv[0] == "write":
        write(argv[1], argv[2], argv[3:])
        return 0
    if len(argv) == 4 and argv[0] == "ball-check":
        fails = ball_check(argv[1], float(argv[2]), float(argv[3]))
    elif len(argv) == 3 and argv[0] == "compare":
        fails, dx, dv = compare(argv[1], argv[2])
        print("max_dx %.3g max_dv %.3g" % (dx, dv))
    else:
        print(__doc__, file=sys.stderr)
        return 2
    for f in fails:
        print("contact_cases.py: FAIL: " + f, file=sys.stderr)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
