#!/usr/bin/env bash
# bench/lcs.sh - LCS circuits stepped by dashpot (`dashpot simulate`, docs/lcs.md) and by Siconos' kernel
# (bench/lcs_peer.cpp: FirstOrderLinearTIDS + FirstOrderLinearTIR + ComplementarityConditionNSL,
# EulerMoreauOSI, LCP/Lemke): the series RLC with an ideal diode and the four-diode bridge of Cibulka 2014
# (Examples 1.9, 1.10). EulerMoreauOSI is dashpot's θ-step, so the trajectories must agree to rounding at
# every step (x to 1e-12, u to 1e-9 relative: u comes out of an LCP whose matrix is O(h), which multiplies
# the rounding of x by 1/h); then the cost per step of each, 10^5 steps, printed with the ratio.
# Then random passive LCS (Cibulka 2014's passivity with P = I: A + Aᵀ negative definite, B = Cᵀ, D + Dᵀ
# positive semidefinite, so |x|²/2 decays), with constant offsets p and q, for a few seeds and sizes up to
# n = m = 10, compared to rounding the same way; the step's LCP matrix D + h C W⁻¹ B then has a positive
# definite symmetric part (checked in dashpot's meta line), so u is unique and comparing it means something.
# Exits non-zero when they disagree. Usage: BUILD=build bash bench/lcs.sh   (also run by `make bench`;
# AGREEMENT_ONLY=1 skips the timing, as tests/test_siconos.sh runs it in `make test`)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bash scripts/install-deps.sh --siconos || { echo "lcs.sh: FAIL: the peer is not installed" >&2; exit 1; }
make -s BUILD="$build" "$build/dashpot"
source bench/siconos_peer.bash
build_siconos_peer lcs_peer

python3 - "$build" "$tmp" <<'PY'
import json, os, random, subprocess, sys, time
build, tmp = sys.argv[1], sys.argv[2]
circuits = {
    "rlc (ideal diode)": {"A": [[0, 1], [-4, -0.5]], "B": [[0], [1]], "C": [[0, 1]], "D": [[0]], "x0": [0, 1]},
    "four-diode bridge": {"A": [[0, -2], [1, 0]], "B": [[0, 0, -2, 2], [0, 0, 0, 0]],
                          "C": [[0, 0], [0, 0], [-1, 0], [1, 0]],
                          "D": [[1, 1, -1, 0], [1, 1, 0, -1], [1, 0, 0, 0], [0, 1, 0, 0]], "x0": [0, 1]},
}
def passive(seed, n, m, d_zero=False):
    """A random passive LCS: A = -(G Gᵀ/n + I/10) + K (K skew), B random, C = Bᵀ, D = H Hᵀ/m + a skew part
    (or D = 0 with m <= n: B has full column rank, so the step's matrix h Bᵀ W⁻¹ B is still definite);
    p, q, x0 random; with D = 0, q keeps the initial w = C x0 + q >= 0 (else no initial u exists)."""
    rng = random.Random(seed)
    u = lambda: rng.uniform(-1, 1)
    G, K = [[u() for _ in range(n)] for _ in range(n)], [[u() for _ in range(n)] for _ in range(n)]
    A = [[-sum(G[i][k] * G[j][k] for k in range(n)) / n - (0.1 if i == j else 0) + 2 * (K[i][j] - K[j][i])
          for j in range(n)] for i in range(n)]
    B = [[u() for _ in range(m)] for _ in range(n)]
    C = [list(r) for r in zip(*B)]
    H, S = [[u() for _ in range(m)] for _ in range(m)], [[u() for _ in range(m)] for _ in range(m)]
    D = [[0.0 if d_zero else sum(H[i][k] * H[j][k] for k in range(m)) / m + 0.5 * (S[i][j] - S[j][i])
          for j in range(m)] for i in range(m)]
    x0, p = [u() for _ in range(n)], [u() for _ in range(n)]
    cx = [sum(C[i][j] * x0[j] for j in range(n)) for i in range(m)]
    q = [abs(c) - c + 0.2 * abs(u()) if d_zero else u() for c in cx]
    return {"A": A, "B": B, "C": C, "D": D, "x0": x0, "p": p, "q": q, "passive": True}
for seed, n, m, d_zero in [(1, 2, 2, False), (2, 4, 3, False), (3, 6, 6, False), (4, 10, 10, False),
                           (5, 10, 4, True), (6, 8, 8, False)]:
    circuits["passive s%d n%d m%d%s" % (seed, n, m, " D=0" if d_zero else "")] = passive(seed, n, m, d_zero)
h, theta, ok = 1e-3, 0.5, True
print("LCS circuits and random passive LCS: dashpot simulate vs Siconos kernel (EulerMoreauOSI + LCP Lemke), "
      "dt = %g, theta = %g" % (h, theta))
print("%-26s %7s %7s %12s %12s %14s %14s %8s" % ("system", "steps", "u>0 %", "max|dx|rel", "max|du|rel",
                                                 "dashpot ns/st", "siconos ns/st", "ratio"))
def peer(c, steps):
    n, m = len(c["A"]), len(c["D"])
    flat = [n, m] + sum(c["A"], []) + sum(c["B"], []) + sum(c["C"], []) + sum(c["D"], []) + c["x0"] + [h, steps, theta]
    flat += c.get("p", [0] * n) + c.get("q", [0] * m)
    open(tmp + "/in.txt", "w").write(" ".join(map(repr, flat)))
    r = subprocess.run([build + "/bench/lcs_peer", tmp + "/in.txt"], capture_output=True, text=True, check=True)
    ns = float(r.stderr.split()[-1])
    return [list(map(float, l.split())) for l in r.stdout.splitlines()], ns
def dashpot(c, steps, samples):
    lcs = {k: c[k] for k in "ABCDpq" if k in c}
    doc = {"model": {"lcs": lcs, "laws": [{"law": "complementarity"}] * len(c["D"])},
           "initial": {"x": c["x0"]}, "solver": {"kind": "stick-slip", "dt": h, "t_end": steps * h, "theta": theta, "events": "none"},
           "output": {"samples": samples}}
    t0 = time.perf_counter()
    r = subprocess.run([build + "/dashpot", "simulate", "-", "--format", "ndjson", "--quiet"], input=json.dumps(doc),
                       capture_output=True, text=True, check=True)
    return [json.loads(l) for l in r.stdout.splitlines()], time.perf_counter() - t0
for name, c in circuits.items():
    n = len(c["A"])
    rows, _ = dashpot(c, 3000, True)
    s = [r for r in rows if r["type"] == "sample"][1:]
    p, _ = peer(c, 3000)
    xmax = max(1.0, max(abs(v) for b in p for v in b[1:1 + n]))
    dx = max(abs(a["x"][i] - b[1 + i]) for a, b in zip(s, p) for i in range(n)) / xmax
    umax = max(1.0, max(abs(v) for b in p for v in b[1 + n:]))
    du = max(abs(a["u"][j] - b[1 + n + j]) for a, b in zip(s, p) for j in range(len(c["D"]))) / umax
    agree = len(s) == len(p) == 3000 and dx <= 1e-12 and du <= 1e-9
    active = sum(1 for b in p if max(b[1 + n:]) > 0) / len(p)   # the steps with some u > 0
    if c.get("passive") and (not rows[0]["step"]["theory"]["positive_definite_symmetric_part"] or active == 0):
        print("FAIL: %s: the step's matrix is not definite, or no u is ever positive" % name, file=sys.stderr)
        agree = False
    ok &= agree
    if os.environ.get("AGREEMENT_ONLY") == "1":   # tests/test_siconos.sh: the check without the timing
        print("%-26s %7d %7.1f %12.3g %12.3g  %s" % (name, 3000, 100 * active, dx, du, "ok" if agree else "FAIL"))
        continue
    steps = 100000
    # best of three (a wall-clock time, exposed to other load), start-up and parse (best of three) subtracted
    t_dp = min(dashpot(c, steps, False)[1] for _ in range(3))
    t_base = min(dashpot(c, 1, False)[1] for _ in range(3))
    _, ns_sic = peer(c, steps)
    ns_dp = 1e9 * (t_dp - t_base) / steps
    print("%-26s %7d %7.1f %12.3g %12.3g %14.4g %14.4g %8.1f  %s" % (name, 3000, 100 * active, dx, du, ns_dp,
                                                                  ns_sic, ns_sic / ns_dp, "ok" if agree else "FAIL"))
sys.exit(0 if ok else 1)
PY
