#!/usr/bin/env bash
# bench/modes.sh - natural modes of chains of 10, 100 and 1000 masses: dashpot (its tridiagonal route, and
# its dense route for reference) against scipy.linalg.eigh(K, M) in the same run, goal being at
# least as fast at every size; scipy.linalg.eigh_tridiagonal is printed too, the like-for-like algorithm.
# The eigenvalues must agree (sum of omegas to 1e-9 relative). Usage: BUILD=build bash bench/modes.sh.
# One core: BLAS threads pinned to 1.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
py=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

mkdir -p "$build/bench"
cc -std=c17 -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes -O2 -g -Iinclude -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE \
  bench/modes_bench.c -o "$build/bench/modes_bench" "$build/libdashpot.a" -lgsl -lgslcblas -lm

export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1
taskset_cmd=""
command -v taskset >/dev/null && taskset_cmd="taskset -c 0"
$taskset_cmd "$build/bench/modes_bench" "$tmp" >"$tmp/c.txt"
if ! $py -c 'import numpy, scipy' 2>/dev/null; then
  echo "modes: numpy/scipy missing for $py (apt-get install python3-numpy python3-scipy); C only:"
  cat "$tmp/c.txt"
  exit 0
fi
$taskset_cmd $py bench/modes_peer.py "$tmp" >"$tmp/py.txt"

$py - "$tmp/c.txt" "$tmp/py.txt" <<'PY'
import sys
c = dict(l.split(None, 1) for l in open(sys.argv[1]).read().splitlines())
p = dict(l.split(None, 1) for l in open(sys.argv[2]).read().splitlines())
print("modes of a chain (fixed-free, varied masses and springs), seconds per solve (eigenvalues and shapes), one core")
print(f"  {'n':>5s} {'dashpot':>11s} {'route':>12s} {'dashpot dense':>14s} {'scipy eigh':>11s} {'eigh_tridiag':>13s} {'eigh/dashpot':>13s}")
ok = True
for n in (10, 100, 1000):
    d, e = float(c[f"n{n}_seconds"]), float(p[f"n{n}_eigh_seconds"])
    agree = abs(float(c[f"n{n}_sum_omega"]) - float(p[f"n{n}_eigh_sum_omega"])) <= 1e-9 * float(p[f"n{n}_eigh_sum_omega"])
    agree &= abs(float(c[f"n{n}_dense_sum_omega"]) - float(p[f"n{n}_eigh_sum_omega"])) <= 1e-9 * float(p[f"n{n}_eigh_sum_omega"])
    ok &= agree
    print(f"  {n:5d} {d:11.3e} {c[f'n{n}_route']:>12s} {float(c[f'n{n}_dense_seconds']):14.3e} {e:11.3e} "
          f"{float(p[f'n{n}_tri_seconds']):13.3e} {e / d:12.1f}x{'' if agree else '  EIGENVALUES DIFFER'}")
print(f"  ({p['scipy']})")
sys.exit(0 if ok else 1)
PY
