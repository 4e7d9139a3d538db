#!/usr/bin/env bash
# tests/test_siconos.sh - dashpot against Siconos, its independent reference, to rounding, in `make test`
# (the benchmarks add the timing): the contact step (bench/contact.sh: the bouncing ball for e = 0.9, 0.5, 0,
# two stacked masses, 100 blocks on stops, theta 1/2 and 1, every step and node against Siconos'
# MoreauJeanOSI + NewtonImpactNSL) and the LCS step (bench/lcs.sh: the seed's diode circuits and random
# passive LCS against EulerMoreauOSI + LCP), both with AGREEMENT_ONLY=1. The peer (libsiconos-kernel-dev, g++) is a test
# dependency (scripts/install-deps.sh). Env BUILD (default build).
set -uo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
passed=0 failed=0
run() { # DESC SCRIPT
  local out
  if out=$(AGREEMENT_ONLY=1 BUILD="$BUILD" bash "$2" 2>&1); then
    echo "ok - $1"; passed=$((passed + 1))
  else
    echo "not ok - $1"; echo "$out" | grep -E 'FAIL|fail' | head -20 | sed 's/^/    /'; failed=$((failed + 1))
  fi
}
run "contacts: dashpot's Moreau-Jean equals Siconos' on the ball, the pair and 100 blocks on stops (bench/contact.sh)" \
  bench/contact.sh
run "LCS: the diode circuits and six random passive LCS equal Siconos' EulerMoreauOSI at every step (bench/lcs.sh)" \
  bench/lcs.sh
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
