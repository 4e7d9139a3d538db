#!/usr/bin/env bash
# bench/run.sh - runs every benchmark script bench/*.sh (each prints its peer side by side and the ratios).
# Usage: bench/run.sh BUILD_DIR. Installs the peers' Debian packages first (wrk, numpy, scipy, ...).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
bash scripts/install-deps.sh --bench
fail=0
for b in bench/*.sh; do
  [ "$(basename "$b")" = run.sh ] && continue
  echo "== $b"
  BUILD=$build bash "$b" || fail=1
done
exit $fail
