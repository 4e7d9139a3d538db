#!/usr/bin/env bash
# bench/quakes.sh - what the quake catalogue (docs/quakes.md) costs: a Carlson–Langer chain of 10^3 blocks
# (l = 3, sigma = 0.01, alpha = 2.5, nu = 0.01, dt = 0.05) run by the CLI with samples and events off, with
# and without output.quakes, for two run lengths: wall time and peak memory (GNU time's maximum resident set
# size). The catalogue adds a pass over the elements per step and a few numbers per element, so the time
# should grow by a few per cent and the memory not with the run's length. Measured and printed, not enforced.
#
# Usage: BUILD=build bash bench/quakes.sh   (not part of `make bench`)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
make -s BUILD="$build" "$build/dashpot"
[ -x /usr/bin/time ] || { echo "quakes.sh: needs GNU time (Debian: time)" >&2; exit 1; }

doc() { # doc T QUAKES: the chain's document
    python3 - "$1" "$2" <<'PY'
import json, random, sys
n, l, sigma, alpha, nu = 1000, 3.0, 0.01, 2.5, 0.01
c = 1 - sigma
friction = {"law": "generalized-coulomb", "phi0": c, "phi1": 1, "belt_velocity": -nu,
            "relaxation": {"kind": "rational", "a": c, "b": c / (2 * alpha)}}
els = [{"between": ["ground", j], "spring": {"law": "linear", "k": 1}, "damper": friction} for j in range(n)]
els += [{"between": [j, j + 1], "spring": {"law": "linear", "k": l * l}} for j in range(n - 1)]
rng = random.Random(1)
print(json.dumps({"model": {"masses": [1] * n, "elements": els}, "initial": {"x": [-rng.random() for _ in range(n)]},
                  "solver": {"kind": "stick-slip", "dt": 0.05, "t_end": float(sys.argv[1])},
                  "output": {"quakes": sys.argv[2] == "1", "samples": False, "events": False}}))
PY
}

printf '%-8s %-7s %10s %12s %8s\n' T quakes wall_s max_rss_kB quakes
for T in 500 2000; do
    for q in 0 1; do
        doc "$T" "$q" >"$tmp/doc.json"
        /usr/bin/time -f '%e %M' -o "$tmp/time" "$build/dashpot" simulate "$tmp/doc.json" --format ndjson >"$tmp/out"
        read -r wall rss <"$tmp/time"
        printf '%-8s %-7s %10s %12s %8s\n' "$T" "$q" "$wall" "$rss" "$(grep -c '"type":"quake"' "$tmp/out" || true)"
    done
done
