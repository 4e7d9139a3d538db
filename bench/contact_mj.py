#!/usr/bin/env python3
"""bench/contact_mj.py - Moreau-Jean with contacts written from bench/contact_peer.md's rules (a)-(e) and
nothing else, in plain Python: if its rows agree with Siconos' (bench/contact_peer.cpp) to rounding, the
rules dashpot is asked to follow are the ones Siconos runs. It reads the peer's text case and writes
dashpot's NDJSON samples ({"type":"sample","t","x","v"}), so bench/contact_cases.py compare judges it as
it judges dashpot (and exercises that path before dashpot accepts contacts).

  contact_mj.py CASE.txt > rows.ndjson
"""
import json
import sys


def read_case(path):
    c = {"h": 1e-3, "steps": 1000, "theta": 0.5, "springs": [], "dampers": [], "forces": [], "contacts": []}
    end = lambda w: -1 if w == "ground" else int(w)
    with open(path) as f:
        for line in f:
            w = line.split("#")[0].split()
            if not w:
                continue
            if w[0] in ("masses", "x0", "v0"):
                c[w[0]] = [float(x) for x in w[1:]]
            elif w[0] in ("spring", "damper"):
                c[w[0] + "s"].append((end(w[1]), end(w[2]), float(w[3])))
            elif w[0] == "contact":
                c["contacts"].append((end(w[1]), end(w[2]), float(w[3]), float(w[4])))
            elif w[0] == "force":
                c["forces"].append((int(w[1]), float(w[2])))
            else:
                c[w[0]] = int(w[1]) if w[0] == "steps" else float(w[1])
    n = len(c["masses"])
    c.setdefault("x0", [0.0] * n)
    c.setdefault("v0", [0.0] * n)
    return c


def outer_terms(pairs):
    """k b b^T as sparse (i, j, value) terms, b = e_b - e_a without the ground."""
    terms = []
    for a, b, k in pairs:
        ends = [(i, s) for i, s in ((a, -1.0), (b, 1.0)) if i >= 0]
        terms += [(i, j, k * si * sj) for i, si in ends for j, sj in ends]
    return terms


def solve(A, b):
    """Gaussian elimination with partial pivoting (A small and dense)."""
    n = len(b)
    M = [row[:] + [b[i]] for i, row in enumerate(A)]
    for k in range(n):
        p = max(range(k, n), key=lambda i: abs(M[i][k]))
        M[k], M[p] = M[p], M[k]
        for i in range(k + 1, n):
            f = M[i][k] / M[k][k]
            if f:
                M[i] = [x - f * y for x, y in zip(M[i], M[k])]
    x = [0.0] * n
    for i in reversed(range(n)):
        x[i] = (M[i][n] - sum(M[i][j] * x[j] for j in range(i + 1, n))) / M[i][i]
    return x


def lcp(M, q):
    """0 <= M z + q _|_ z >= 0 for a P-matrix M: Murty's least-index principal pivoting (finite)."""
    n, S = len(q), {i for i in range(len(q)) if q[i] < 0}
    scale = 1e-13 * (1.0 + max(abs(x) for x in q))
    for _ in range(50 * n + 50):
        idx = sorted(S)
        zS = solve([[M[i][j] for j in idx] for i in idx], [-q[i] for i in idx]) if idx else []
        z = [0.0] * n
        for i, zi in zip(idx, zS):
            z[i] = zi
        w = [q[i] + sum(M[i][j] * z[j] for j in idx) for i in range(n)]
        bad = [i for i in range(n) if (z[i] < -scale if i in S else w[i] < -scale)]
        if not bad:
            return [max(zi, 0.0) for zi in z]
        S ^= {bad[0]}
    raise RuntimeError("LCP: no solution found")


def run(c):
    n, h, th = len(c["masses"]), c["h"], c["theta"]
    K, C = outer_terms(c["springs"]), outer_terms(c["dampers"])
    f = [0.0] * n
    for i, fi in c["forces"]:
        f[i] += fi
    # (e) W = M + h theta C + h^2 theta^2 K, inverted once.
    W = [[c["masses"][i] if i == j else 0.0 for j in range(n)] for i in range(n)]
    for terms, s in ((C, h * th), (K, h * h * th * th)):
        for i, j, x in terms:
            W[i][j] += s * x
    Winv_cols = [solve(W, [1.0 if i == j else 0.0 for i in range(n)]) for j in range(n)]
    Winv = [[Winv_cols[j][i] for j in range(n)] for i in range(n)]
    # each contact's row b (u = b^T q) as {node: +-1}
    B = [{i: s for i, s in ((a, -1.0), (b, 1.0)) if i >= 0} for a, b, _, _ in c["contacts"]]
    q, v = list(c["x0"]), list(c["v0"])
    yield 0.0, q, v
    for step in range(c["steps"]):
        q, v = step_once(q, v, c, K, C, f, Winv, B)
        yield (step + 1) * h, q, v


def step_once(q, v, c, K, C, f, Winv, B):
    n, h, th = len(q), c["h"], c["theta"]
    dot = lambda b, x: sum(s * x[i] for i, s in b.items())
    # (a) index set from the step's start: g + h u'/2 <= 0.
    active = [k for k, (_, _, d, _) in enumerate(c["contacts"]) if dot(B[k], q) - d + 0.5 * h * dot(B[k], v) <= 0]
    # (c) free velocity, loads weighted theta f(t+h) + (1-theta) f(t) (constant here: f).
    rhs = [h * fi for fi in f]
    for i, j, x in C:
        rhs[i] -= h * x * v[j]
    for i, j, x in K:
        rhs[i] -= x * (h * h * th * v[j] + h * q[j])
    vn = [v[i] + sum(Winv[i][j] * rhs[j] for j in range(n)) for i in range(n)]
    if active:
        # (b) 0 <= b^T v+ + e b^T v_k _|_ P >= 0, v+ = v_free + W^-1 B P.
        WB = [[sum(Winv[i][j] * s for j, s in B[k].items()) for i in range(n)] for k in active]
        M = [[dot(B[k], WB[m]) for m in range(len(active))] for k in active]
        qq = [dot(B[k], vn) + c["contacts"][k][3] * dot(B[k], v) for k in active]
        P = lcp(M, qq)
        vn = [vn[i] + sum(WB[m][i] * P[m] for m in range(len(active))) for i in range(n)]
    # (d) q+ = q + h (theta v+ + (1 - theta) v).
    return [q[i] + h * (th * vn[i] + (1 - th) * v[i]) for i in range(n)], vn


def main(argv):
    if len(argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    out = sys.stdout
    for t, q, v in run(read_case(argv[0])):
        out.write(json.dumps({"type": "sample", "t": t, "x": q, "v": v}) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
