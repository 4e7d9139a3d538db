#!/usr/bin/env bash
# tests/test_layers.sh - the house stays in order: no include or call from a lower folder of src/ to a
# higher one and no circle between source files (scripts/layers.py, from cc -MM and the objects' symbols;
# the floors are drawn in docs/architecture.md). Then the check itself is shown to fail: a probe object
# in base/ that calls the run iterator at the top must be reported.
set -u
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
fail=0
python3 scripts/layers.py "$BUILD" || fail=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp -r "$BUILD/src" "$tmp/src"
printf '#include "dashpot/run.h"\nvoid dp_probe(void);\nvoid dp_probe(void) { dp_run_free(NULL); }\n' > "$tmp/probe.c"
cc -Iinclude -c "$tmp/probe.c" -o "$tmp/src/core/base/zz_probe.o"
out=$(python3 scripts/layers.py "$tmp" 2>&1)
if grep -q "call up: src/core/base/zz_probe.c (core/base) calls dp_run_free" <<<"$out"; then
    echo "ok: a call from base/ up to runs/ is reported"
else
    echo "FAIL: the planted call from base/ to runs/ went unreported:"; echo "$out"; fail=1
fi
[ $fail = 0 ] && echo "2 passed, 0 failed" || echo "1 passed, 1 failed"
exit $fail
