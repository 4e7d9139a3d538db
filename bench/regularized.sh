#!/usr/bin/env bash
# bench/regularized.sh - the regularized solver (PCn) as n grows from 10 to 1e5: steps and wall time per GSL
# stepper (implicit msbdf, rk4imp, bsimp with the analytic Jacobian; explicit rkf45, rk8pd), side by side with
# SciPy's solve_ivp (Radau, LSODA) on the same ODE, tolerances and output times; prints the ratios and the
# goals (implicit step count flat in n; dashpot >= 10x faster than SciPy at every n).
# Usage: BUILD=build bash bench/regularized.sh [N_MAX]. One core.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
nmax=${1:-1e5}
py=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The same flags as the Makefile's library objects.
mkdir -p "$build/bench"
cc -std=c17 -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes -O2 -g -Iinclude \
  -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE bench/regularized_bench.c -o "$build/bench/regularized_bench" \
  "$build/libdashpot.a" -lgsl -lgslcblas -lm -lcjson

taskset_cmd=""
command -v taskset >/dev/null && taskset_cmd="taskset -c 0"
$taskset_cmd "$build/bench/regularized_bench" "$nmax" >"$tmp/c.txt"
if ! $py -c 'import numpy, scipy' 2>/dev/null; then
  echo "regularized: numpy/scipy missing for $py (apt-get install python3-numpy python3-scipy); C only:"
  cat "$tmp/c.txt"
  exit 0
fi
$taskset_cmd $py bench/regularized_peer.py "$nmax" >"$tmp/py.txt"

$py - "$tmp/c.txt" "$tmp/py.txt" <<'PY'
import sys
rows = {}
for path in sys.argv[1:]:
    for line in open(path):
        m, n, steps, rej, fev, jev, sec, x = line.split()
        rows[(m, float(n))] = dict(steps=int(steps), rej=int(rej), fev=int(fev), jev=int(jev), sec=float(sec), x=float(x))
methods = [m for m in dict.fromkeys(k[0] for k in rows)]
ns = sorted(dict.fromkeys(k[1] for k in rows))
print("regularized (PCn): Coulomb free decay, m = k = phi0 = 1, x0 = 4.5, t in [0, 30], 301 samples, "
      "rtol = atol = 1e-10, one core")
print(f"  {'method':8s} {'n':>7s} {'steps':>8s} {'rejected':>8s} {'fevals':>8s} {'jevals':>6s} {'time':>11s} {'x(30)':>15s}")
for m in methods:
    for n in ns:
        r = rows.get((m, n))
        if r:
            rej = r['rej'] if r['rej'] >= 0 else '-'
            print(f"  {m:8s} {n:7.0e} {r['steps']:8d} {rej:>8} {r['fev']:8d} {r['jev']:6d} {r['sec']*1e3:8.3f} ms {r['x']:15.10f}")
print("ratios (SciPy time / dashpot msbdf time):")
ok = True
for n in ns:
    d = rows[("msbdf", n)]["sec"]
    rad, lso = rows[("Radau", n)]["sec"] / d, rows[("LSODA", n)]["sec"] / d
    dx = max(abs(rows[(m, n)]["x"] - rows[("Radau", n)]["x"]) for m in ("msbdf", "LSODA"))
    ok &= min(rad, lso) >= 10
    print(f"  n = {n:7.0e}: Radau/msbdf {rad:7.1f}x   LSODA/msbdf {lso:6.1f}x   |x(30) msbdf, LSODA - Radau| <= {dx:.1e}")
steps = [rows[("msbdf", n)]["steps"] for n in ns]
flat = max(steps) <= 1.5 * min(steps)
expl = rows[("rkf45", ns[-1])]["steps"] / rows[("rkf45", ns[0])]["steps"]
print(f"goal: msbdf steps flat in n ({min(steps)}..{max(steps)}): {'met' if flat else 'MISSED'}; "
      f"rkf45 steps grow {expl:.0f}x over the same n")
print(f"goal: dashpot >= 10x faster than Radau and LSODA at every n: {'met' if ok else 'MISSED'}")
PY
