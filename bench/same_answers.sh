#!/usr/bin/env bash
# bench/same_answers.sh - whether two dashpot builds give the same answers, byte for byte, on the network
# cases the benchmarks time: a change that only trims work (docs/benchmarks.md, "Networks") must leave every
# sample, event and summary as it was. Complements tests/test_corpus.sh, whose documents are short: these
# run long enough (thousands of steps, up to 10^3 blocks) for the step's reused factors, kept forests and
# held solves to matter.
#
# Usage: bash bench/same_answers.sh OLD_DASHPOT NEW_DASHPOT [NETWORK_BENCH]
#   OLD_DASHPOT, NEW_DASHPOT: two `dashpot` binaries (e.g. a worktree of the old commit's build/dashpot).
#   NETWORK_BENCH: the document writer (bench/network_bench.c), built here into a temporary folder if not given.
# Every case runs `dashpot simulate DOC --format ndjson` (every step's sample, every event; then every 7th
# step's sample) with both and compares the outputs with cmp. Cases: the contact chain of 100 blocks on stops and the balls and the pair of
# bench/contact_cases.py ("events" "none" as written, and "locate"); the friction chains of 10 and 100 blocks
# (Moreau-Jean's chain of bench/network.sh), chain10p (friction between neighbours too, a load on the last),
# Burridge-Knopoff chains of 10^2 and 10^3 blocks, the friction chain of 10^3 blocks; each at theta 1/2 and 1,
# with "events" "none" and "locate"; Burridge-Knopoff's of 10^4 blocks with "none". Exit status 1 when any
# case differs or fails to run in one build and not the other. ~2-3 minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  echo "usage: $0 OLD_DASHPOT NEW_DASHPOT [NETWORK_BENCH]" >&2
  exit 2
fi
old=$(realpath "$1") new=$(realpath "$2")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
nb=${3:-}
if [ -z "$nb" ]; then
  nb="$tmp/network_bench"
  cc -std=c17 -O2 -Iinclude -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE bench/network_bench.c -o "$nb" \
    "$(dirname "$new")/libdashpot.a" -lcjson -lgsl -lgslcblas -lm
fi

fail=0 count=0
# compare NAME DOC: both builds on DOC, outputs and exit statuses compared; then DOC again with every 7th step
# written (a step that writes no row forms no forces: network_run_element_phases, the stop chain)
compare() {
  compare_one "$1" "$2"
  python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); d["output"]["every"] = 7; json.dump(d, open(sys.argv[2], "w"))' \
    "$2" "$tmp/every7.json"
  compare_one "$1 every=7" "$tmp/every7.json"
}
compare_one() {
  local name=$1 doc=$2 so sn
  so=0 sn=0
  "$old" simulate "$doc" --format ndjson >"$tmp/old.out" 2>"$tmp/old.err" || so=$?
  "$new" simulate "$doc" --format ndjson >"$tmp/new.out" 2>"$tmp/new.err" || sn=$?
  count=$((count + 1))
  if [ "$so" != "$sn" ] || ! cmp -s "$tmp/old.out" "$tmp/new.out"; then
    echo "DIFFERS  $name (exit $so / $sn; $(wc -l <"$tmp/old.out") / $(wc -l <"$tmp/new.out") lines)"
    cmp "$tmp/old.out" "$tmp/new.out" | head -1 || true
    fail=1
  else
    printf 'same     %-44s %8s lines\n' "$name" "$(wc -l <"$tmp/new.out")"
  fi
}

# contact cases ("events" "none" as bench/contact.sh writes them; "locate" by rewriting the one member)
for c in chain100 ball_e0.9 ball_e0.5 ball_e0 pair; do
  for th in 0.5 1; do
    steps=$([ "$c" = chain100 ] && echo 2000 || echo 3000)
    python3 bench/contact_cases.py write "$c" "$tmp" steps=$steps theta=$th
    compare "contact $c theta=$th none" "$tmp/$c.json"
    sed 's/"events": "none"/"events": "locate"/' "$tmp/$c.json" >"$tmp/$c.loc.json"
    compare "contact $c theta=$th locate" "$tmp/$c.loc.json"
  done
done

# friction chains (bench/network.sh's words)
chain="kg=1 kc=1 phi0=0.5 het=0.3 vb=0.5 xamp=1"
bk="kg=1 kc=10 phi0=1 het=0.5 vb=-0.1 xamp=0.5"
declare -A cases=(
  [chain10]="n=10 $chain steps=2000"
  [chain100]="n=100 $chain steps=2000"
  [chain10p]="n=10 $chain phic=0.2 F0=0.3 steps=2000"
  [bk100]="n=100 $bk steps=500"
  [bk1000]="n=1000 $bk steps=200"
  [chain1000]="n=1000 $chain steps=200"
  [bk10000]="n=10000 $bk steps=30"
)
# the grounded chain's lean step ("none") at 10^3 and 10^4 blocks too: a step there changes many blocks at
# once, so its active-set pass runs more than one update (the located 10^4 chain is left out: minutes)
for c in chain10 chain100 chain10p bk100 bk1000 chain1000 bk10000; do
  for th in 0.5 1; do
    for loc in 0 1; do
      [ "$c" = bk10000 ] && [ "$loc" = 1 ] && continue
      # shellcheck disable=SC2086 # the case is a list of words on purpose
      "$nb" mode=doc ${cases[$c]} dt=1e-3 theta=$th locate=$loc >"$tmp/doc.json"
      compare "network $c theta=$th $([ $loc = 1 ] && echo locate || echo none)" "$tmp/doc.json"
    done
  done
done

if [ "$fail" = 0 ]; then
  echo "same_answers: all $count cases byte for byte the same"
else
  echo "same_answers: FAIL: some cases differ" >&2
fi
exit "$fail"
