#!/usr/bin/env bash
# bench/contact.sh - unilateral contact and impacts: dashpot's "events": "none" contact step next
# to Siconos' Moreau-Jean (bench/contact_peer.cpp; the rules it follows are in bench/contact_peer.md) on the
# bouncing ball (e = 0.9, 0.5, 0), two stacked masses with two contacts, and a chain of 100 blocks on stops.
# 1. the peer's ball against the closed form (impact instants, the impact law), the pair against statics,
#    and the peer against bench/contact_mj.py (contact_peer.md's rules in plain Python) to rounding;
# 2. dashpot against the peer, every step, every node: max |dx|, |dv| (bench/contact_cases.py compare);
# 3. time per step side by side on the ball and the 100-block chain, and the ratio.
# The cases are defined once, in bench/contact_cases.py, which writes both programs' inputs.
#
# Usage: BUILD=build bash bench/contact.sh   (also run by `make bench`; DASHPOT=program replaces build/dashpot;
# AGREEMENT_ONLY=1 stops after the checks, as tests/test_siconos.sh runs it in `make test`)
# Exits non-zero if a check fails, or if this build of dashpot does not accept contacts yet (said plainly:
# "dashpot side: contact not supported by this build"); the peer's side runs and is checked either way.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

bash scripts/install-deps.sh --siconos || { echo "contact.sh: FAIL: the peer is not installed" >&2; exit 1; }
make -s BUILD="$build" "$build/dashpot"
mkdir -p "$build/bench"
cc -std=c17 -Wall -Wextra -Werror -O2 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE bench/contact_floor.c \
  -o "$build/bench/contact_floor" -lm
source bench/siconos_peer.bash
build_siconos_peer contact_peer
peer="$build/bench/contact_peer" dp=${DASHPOT:-$build/dashpot} cases=bench/contact_cases.py

peer_run() { OPENBLAS_NUM_THREADS=1 timeout 600 "$peer" "$@"; } # one thread, as dashpot
kv() { awk -v k="$2" '$1 == k { print $2; f = 1 } END { if (!f) print "-" }' "$1"; }
fail=0 dashpot_ok=1

echo "contact: dashpot vs Siconos $(dpkg-query -W -f='${Version}' libsiconos-kernel-dev) (MoreauJeanOSI + NewtonImpactNSL + LCP/Lemke), dt = 1e-3"
echo
echo "1. the peer against exact solutions (theta = 1/2)"
for e in 0.9 0.5 0; do
  python3 "$cases" write "ball_e$e" "$tmp"
  peer_run "$tmp/ball_e$e.txt" >"$tmp/ball_e$e.0.5.rows" 2>/dev/null
  echo "  ball, e = $e: impact instants against the closed form, v+/v- = -e at every impact"
  python3 "$cases" ball-check "$tmp/ball_e$e.0.5.rows" "$e" 1e-3 || fail=1
done
python3 "$cases" write pair "$tmp"
peer_run "$tmp/pair.txt" >"$tmp/pair.0.5.rows" 2>/dev/null
# At rest both contacts are closed: x0 = 0, x1 = x0 + 0.5, v = 0 (within the method's penetration, h |v|).
awk 'END { ok = ($2 < 0.01 && $2 > -0.01 && $3 - $2 > 0.49 && $3 - $2 < 0.51 && $4 * $4 + $5 * $5 < 1e-12)
           printf "  pair: final x = (%.3g, %.6g), v = (%.2g, %.2g); at rest on both contacts: %s\n", $2, $3, $4, $5,
                  ok ? "ok" : "FAIL"; exit !ok }' "$tmp/pair.0.5.rows" || fail=1
echo
echo "   the rules of bench/contact_peer.md, written out in bench/contact_mj.py, against the peer (every step, node)"
printf '  %-10s %-5s %10s %10s  %s\n' case theta 'max|dx|' 'max|dv|' verdict
for c in ball_e0.9 ball_e0.5 ball_e0 pair chain100; do
  for th in 0.5 1; do
    python3 "$cases" write "$c" "$tmp" theta=$th
    peer_run "$tmp/$c.txt" >"$tmp/$c.rows" 2>/dev/null
    python3 bench/contact_mj.py "$tmp/$c.txt" >"$tmp/$c.mj"
    verdict=ok
    python3 "$cases" compare "$tmp/$c.rows" "$tmp/$c.mj" >"$tmp/cmp" 2>"$tmp/cmp.err" || { verdict=FAIL; fail=1; }
    printf '  %-10s %-5s %10s %10s  %s\n' "$c" "$th" "$(awk '{ print $2 }' "$tmp/cmp")" \
      "$(awk '{ print $4 }' "$tmp/cmp")" "$verdict"
  done
done
echo

echo "2. dashpot against the peer, \"events\": \"none\", every step, every node (tol 1e-12 x steps x scale)"
python3 "$cases" write ball_e0.9 "$tmp"
if ! "$dp" simulate "$tmp/ball_e0.9.json" --format ndjson >"$tmp/probe" 2>"$tmp/probe.err"; then
  if grep -qi contact "$tmp/probe.err"; then
    echo "  dashpot side: contact not supported by this build ($(head -1 "$tmp/probe.err"))"
  else
    echo "  dashpot side: FAIL: dashpot refused the ball: $(head -1 "$tmp/probe.err")"
  fi
  dashpot_ok=0 fail=1
fi
if [ "$dashpot_ok" = 1 ]; then
  printf '  %-10s %-5s %6s %10s %10s  %s\n' case theta steps 'max|dx|' 'max|dv|' verdict
  for c in ball_e0.9 ball_e0.5 ball_e0 pair chain100; do
    for th in 0.5 1; do
      python3 "$cases" write "$c" "$tmp" theta=$th
      peer_run "$tmp/$c.txt" >"$tmp/$c.rows" 2>/dev/null
      verdict=ok
      if ! "$dp" simulate "$tmp/$c.json" --format ndjson >"$tmp/$c.ndjson" 2>"$tmp/$c.err"; then
        verdict="FAIL: $(head -1 "$tmp/$c.err")"
        echo "max_dx - max_dv -" >"$tmp/cmp"
      elif ! python3 "$cases" compare "$tmp/$c.rows" "$tmp/$c.ndjson" >"$tmp/cmp" 2>"$tmp/cmp.err"; then
        verdict="FAIL: $(sed 's/^contact_cases.py: FAIL: //' "$tmp/cmp.err" | head -1)"
      fi
      [ "$verdict" = ok ] || fail=1
      printf '  %-10s %-5s %6s %10s %10s  %s\n' "$c" "$th" "$(($(wc -l <"$tmp/$c.rows") - 1))" \
        "$(awk '{ print $2 }' "$tmp/cmp")" "$(awk '{ print $4 }' "$tmp/cmp")" "$verdict"
    done
  done
fi
echo

# The ball is one node with one contact: it runs the lean run type (solvers/network/network_contact_lean.c,
# the general step written out for one node, bit for bit); the chain runs the general network step.
# dashpot's cost per step from two run lengths (the difference cancels start-up and parsing), output off
# but for the summary; best of three. Siconos: its step calls only, best of three runs.
dp_best() { # document: the fastest of three runs, in ns
  local best=0 t0 t1
  for _ in 1 2 3; do
    t0=$(date +%s%N); "$dp" simulate "$1" --format ndjson >/dev/null 2>&1 || return 1; t1=$(date +%s%N)
    if [ "$best" = 0 ] || [ $((t1 - t0)) -lt "$best" ]; then best=$((t1 - t0)); fi
  done
  echo "$best"
}
dp_ns() { # case steps
  local short long
  python3 "$cases" write "$1" "$tmp" steps="$(($2 / 10))" every="$(($2 / 10))"
  short=$(dp_best "$tmp/$1.json") || return 1
  python3 "$cases" write "$1" "$tmp" steps="$2" every="$2"
  long=$(dp_best "$tmp/$1.json") || return 1
  awk -v a="$short" -v b="$long" -v n="$2" 'BEGIN { printf "%.4g", (b - a) / (0.9 * n) }'
}
if [ "${AGREEMENT_ONLY:-0}" = 1 ]; then   # tests/test_siconos.sh: the checks without the timing
  [ "$fail" = 0 ] && [ "$dashpot_ok" = 1 ] && exit 0
  echo "contact.sh: FAIL: a check above failed ('FAIL' lines)" >&2
  exit 1
fi
echo "3. time per step, theta = 1/2, output off"
declare -A ratio
dp_ball=-
printf '  %-10s %7s %12s %12s %10s\n' case steps 'dashpot ns' 'Siconos ns' ratio
for spec in ball_e0.9:100000 chain100:2000; do
  c=${spec%%:*} n=${spec##*:}
  python3 "$cases" write "$c" "$tmp" steps="$n"
  peer_run "$tmp/$c.txt" quiet reps=3 2>"$tmp/t.$c" >/dev/null
  s=$(kv "$tmp/t.$c" ns_per_step) d=- r=-
  if [ "$dashpot_ok" = 1 ]; then
    d=$(dp_ns "$c" "$((n * 10))") || d=-
    r=$(awk -v a="$s" -v b="$d" 'BEGIN { if (b + 0 <= 0) printf "-"; else printf (a / b < 10 ? "%.2g" : "%.0f"), a / b }')
  fi
  ratio[$c]=$r
  [ "$c" = ball_e0.9 ] && dp_ball=$d
  printf '  %-10s %7s %12s %12s %9sx\n' "$c" "$n" "$d" "$s" "$r"
done
echo

# The floor beside the ball: its Moreau-Jean step as a bare C loop (bench/contact_floor.c), checked to follow
# dashpot's trajectory (3000 steps, four impacts) before its time is printed.
floor_ns=-
if [ "$dashpot_ok" = 1 ]; then
  python3 "$cases" write ball_e0.9 "$tmp" steps=3000 every=3000
  "$dp" simulate "$tmp/ball_e0.9.json" --format ndjson | tail -1 >"$tmp/ball.sum"
  "$build/bench/contact_floor" g=-9.81 e=0.9 x0=1 steps=3000 >"$tmp/cf.txt"
  if python3 -c 'import json, sys
s = json.load(open(sys.argv[1]))["final"]; f = {l.split()[0]: float(l.split()[1]) for l in open(sys.argv[2])}
sys.exit(not (abs(s["x"][0] - f["final_x"]) < 1e-9 and abs(s["v"][0] - f["final_v"]) < 1e-9))' "$tmp/ball.sum" "$tmp/cf.txt"
  then
    "$build/bench/contact_floor" g=-9.81 e=0.9 x0=1 steps=1000000 reps=3 >"$tmp/cf.txt"
    floor_ns=$(kv "$tmp/cf.txt" ns_per_step)
  else
    echo "  contact_floor.c does not follow dashpot's ball: its time is not printed" >&2
  fi
fi
echo "  floor: the ball's bare Moreau-Jean step (bench/contact_floor.c), $floor_ns ns a step"
echo

goal() { awk -v n="$1" -v v="$2" -v g="$3" -v note="${4:-}" 'BEGIN { ok = v != "-" && v + 0 >= g + 0
         printf "  %-48s %8sx  (goal >= %sx)  %-12s %s\n", n, v, g, ok ? "met" : (v == "-" ? "not measured" : "NOT met"),
                note }'; }
echo "goals (measured, not enforced)"
goal "Siconos / dashpot time per step, ball" "${ratio[ball_e0.9]}" 100 "(dashpot $dp_ball ns, floor $floor_ns ns)"
goal "Siconos / dashpot time per step, 100 blocks" "${ratio[chain100]}" 100

if [ "$dashpot_ok" = 0 ]; then
  echo "contact.sh: FAIL: dashpot side: contact not supported by this build (the peer's side above ran)" >&2
  exit 1
fi
if [ "$fail" -ne 0 ]; then
  echo "contact.sh: FAIL: a check above failed ('FAIL' lines)" >&2
  exit 1
fi
