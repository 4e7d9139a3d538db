#!/usr/bin/env bash
# bench/stability.sh - stability verdicts per second (degree-4 laws) and a 1000x1000 stability map, libdashpot
# against numpy/scipy doing the same work on the same laws; prints both side by side and the ratios.
# Usage: BUILD=build bash bench/stability.sh [N_LAWS] [MAP_STEPS]. One core: BLAS threads pinned to 1.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
n=${1:-2000000}
steps=${2:-1000}
py=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The same flags as the Makefile's library objects.
mkdir -p "$build/bench"
cc -std=c17 -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes -O2 -g -Iinclude -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE \
  bench/stability_bench.c -o "$build/bench/stability_bench" "$build/libdashpot.a" -lgsl -lgslcblas -lm -lcjson

export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1
taskset_cmd=""
command -v taskset >/dev/null && taskset_cmd="taskset -c 0"
$taskset_cmd "$build/bench/stability_bench" "$n" "$tmp/laws.bin" "$steps" >"$tmp/c.txt"
if ! $py -c 'import numpy, scipy' 2>/dev/null; then
  echo "stability: numpy/scipy missing for $py (apt-get install python3-numpy python3-scipy); C only:"
  cat "$tmp/c.txt"
  exit 0
fi
$taskset_cmd $py bench/stability_peer.py "$tmp/laws.bin" "$steps" >"$tmp/py.txt"

$py - "$tmp/c.txt" "$tmp/py.txt" <<'EOF'
import sys
c = dict(l.split(None, 1) for l in open(sys.argv[1]).read().splitlines())
p = dict(l.split(None, 1) for l in open(sys.argv[2]).read().splitlines())
n = int(c["laws"]); pts = int(c["map_points"])
f = lambda k, d: float(d[k])
rows = [
    ("dashpot verdict (Hurwitz, roots near boundary)", n / f("verdict_seconds", c), c["verdict_stable"]),
    ("dashpot verdict + spectral abscissa (roots)", n / f("roots_seconds", c), c["roots_stable"]),
    ("numpy batched eigvals of companions", n / f("eigvals_seconds", p), p["eigvals_stable"]),
    ("numpy vectorised degree-4 Hurwitz formulas", n / f("hurwitz_seconds", p), p["hurwitz_stable"]),
    ("scipy.linalg.eigvals, one call per law", 1 / f("scipy_per_call_seconds", p), "-"),
]
print(f"stability verdicts, {n} random degree-4 laws (same laws for both), one core")
print(f"  {'':50s} {'verdicts/s':>12s} {'stable':>9s}")
for name, rate, st in rows:
    print(f"  {name:50s} {rate:12.3e} {st:>9s}")
base = n / f("verdict_seconds", c)
print(f"  ratio dashpot/numpy-eigvals {base / rows[2][1]:.2f}x, dashpot/numpy-hurwitz {base / rows[3][1]:.2f}x, "
      f"dashpot-with-roots/numpy-eigvals {rows[1][1] / rows[2][1]:.2f}x, dashpot/scipy-per-call {base / rows[4][1]:.1f}x")
print(f"stability map {c['map_points']} points (mu[0] x mu[2], model 1.4), verdict + spectral abscissa per point")
print(f"  dashpot      {f('map_seconds', c):8.3f} s   stable points {c['map_stable']}")
print(f"  numpy eigvals {f('map_seconds', p):7.3f} s   stable points {p['map_stable']}")
print(f"  ratio numpy/dashpot time {f('map_seconds', p) / f('map_seconds', c):.2f}x   ({p['numpy']} numpy, scipy {p['scipy']})")
EOF
