#!/usr/bin/env bash
# bench/lcp.sh - LCP solves per second, dashpot's Lemke (src/core/lcp/lemke.c) against Siconos numerics'
# lcp_lexicolemke on the same random problems of sizes 2, 10 and 100, printed side by side with the ratio
# (bench/lcp_bench.c). The issue's goal is >= 10x Siconos at every size; it is measured and reported, not
# enforced. Exits non-zero if the two disagree beyond 1e-9 relative on any problem.
# Usage: BUILD=build bash bench/lcp.sh   (also run by `make bench` through bench/run.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
# The peer's library and headers come with libsiconos-kernel-dev (its numerics part).
bash scripts/install-deps.sh --siconos || { echo "lcp.sh: FAIL: the peer is not installed" >&2; exit 1; }
make -s BUILD="$build" "$build/libdashpot.a"
mkdir -p "$build/bench"
cc -std=c17 -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes -Wno-missing-field-initializers \
  -O2 -g -Iinclude -isystem /usr/include/siconos -isystem /usr/include/siconos/numerics \
  -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE bench/lcp_bench.c -o "$build/bench/lcp_bench" \
  "$build/libdashpot.a" -lsiconos_numerics -lcjson -lgsl -lgslcblas -lm
"$build/bench/lcp_bench"
