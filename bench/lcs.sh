#!/usr/bin/env bash
# bench/lcs.sh - LCS circuits stepped by dashpot (`dashpot simulate`, docs/lcs.md) and by Siconos' kernel
# (bench/lcs_peer.cpp: FirstOrderLinearTIDS + FirstOrderLinearTIR + ComplementarityConditionNSL,
# EulerMoreauOSI, LCP/Lemke): the series RLC with an ideal diode and the four-diode bridge of seed 002
# (Examples 1.9, 1.10). EulerMoreauOSI is dashpot's θ-step, so the trajectories must agree to rounding at
# every step (x to 1e-12, u to 1e-9 relative: u comes out of an LCP whose matrix is O(h), which multiplies
# the rounding of x by 1/h); then the cost per step of each, 10^5 steps, printed with the ratio.
# Exits non-zero when they disagree. Usage: BUILD=build bash bench/lcs.sh   (also run by `make bench`)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bash scripts/install-deps.sh --siconos || { echo "lcs.sh: FAIL: the peer is not installed" >&2; exit 1; }
make -s BUILD="$build" "$build/dashpot"
mkdir -p "$build/bench"
c++ -O2 -std=c++17 -Wall -Wextra -Werror -isystem /usr/include/siconos -isystem /usr/include/siconos/kernel \
  -isystem /usr/include/siconos/numerics bench/lcs_peer.cpp -o "$build/bench/lcs_peer" \
  -lsiconos_kernel -lsiconos_numerics

python3 - "$build" "$tmp" <<'PY'
import json, subprocess, sys, time
build, tmp = sys.argv[1], sys.argv[2]
circuits = {
    "rlc (ideal diode)": {"A": [[0, 1], [-4, -0.5]], "B": [[0], [1]], "C": [[0, 1]], "D": [[0]], "x0": [0, 1]},
    "four-diode bridge": {"A": [[0, -2], [1, 0]], "B": [[0, 0, -2, 2], [0, 0, 0, 0]],
                          "C": [[0, 0], [0, 0], [-1, 0], [1, 0]],
                          "D": [[1, 1, -1, 0], [1, 1, 0, -1], [1, 0, 0, 0], [0, 1, 0, 0]], "x0": [0, 1]},
}
h, theta, ok = 1e-3, 0.5, True
print("LCS circuits: dashpot simulate vs Siconos kernel (EulerMoreauOSI + LCP Lemke), dt = %g, theta = %g" % (h, theta))
print("%-20s %7s %12s %12s %14s %14s %8s" % ("circuit", "steps", "max|dx|", "max|du|rel", "dashpot ns/st", "siconos ns/st", "ratio"))
def peer(c, steps):
    n, m = len(c["A"]), len(c["D"])
    flat = [n, m] + sum(c["A"], []) + sum(c["B"], []) + sum(c["C"], []) + sum(c["D"], []) + c["x0"] + [h, steps, theta]
    open(tmp + "/in.txt", "w").write(" ".join(map(repr, flat)))
    r = subprocess.run([build + "/bench/lcs_peer", tmp + "/in.txt"], capture_output=True, text=True, check=True)
    ns = float(r.stderr.split()[-1])
    return [list(map(float, l.split())) for l in r.stdout.splitlines()], ns
def dashpot(c, steps, samples):
    doc = {"model": {"lcs": {k: c[k] for k in "ABCD"}, "laws": [{"law": "complementarity"}] * len(c["D"])},
           "initial": {"x": c["x0"]}, "solver": {"kind": "stick-slip", "dt": h, "t_end": steps * h, "theta": theta},
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
    dx = max(abs(a["x"][i] - b[1 + i]) for a, b in zip(s, p) for i in range(n))
    umax = max(1.0, max(abs(v) for b in p for v in b[1 + n:]))
    du = max(abs(a["u"][j] - b[1 + n + j]) for a, b in zip(s, p) for j in range(len(c["D"]))) / umax
    agree = len(s) == len(p) == 3000 and dx <= 1e-12 and du <= 1e-9
    ok &= agree
    steps = 100000
    _, t_dp = dashpot(c, steps, False)
    _, t_base = dashpot(c, 1, False)   # start-up and parse, subtracted
    _, ns_sic = peer(c, steps)
    ns_dp = 1e9 * (t_dp - t_base) / steps
    print("%-20s %7d %12.3g %12.3g %14.4g %14.4g %8.1f  %s" % (name, 3000, dx, du, ns_dp, ns_sic, ns_sic / ns_dp,
                                                            "ok" if agree else "FAIL"))
sys.exit(0 if ok else 1)
PY
