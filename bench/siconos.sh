#!/usr/bin/env bash
# bench/siconos.sh - dashpot's stick-slip solver side by side with Siconos: the same 1-DOF Coulomb
# oscillator (free decay, harmonic forcing, belt-driven stick-slip) stepped by dashpot ("events":"none") and
# by Siconos' kernel (EulerMoreauOSI + Relay, bench/siconos_peer.cpp), theta = 1/2 and 1. Prints per case:
# max |dx|, |dv|, |dF| between the two, the error of each against the closed form, ns per step and peak RSS
# of each and their ratios; how the cost grows from 1e4 to 1e7 steps; dashpot against a bare C loop of the
# step (bench/floor.c); the cost of NDJSON samples. docs/benchmarks.md explains the figures.
#
# Usage: BUILD=build bash bench/siconos.sh   (also run by `make bench` through bench/run.sh)
#   SICONOS_MAX_STEPS (default 1000000): Siconos takes ~7 us a step, so its 1e7-step run (over a minute a
#   case) is skipped unless this is raised to 10000000.
# Installs the peer (libsiconos-kernel-dev) from Debian if missing (as root; otherwise prints the command).
# Exits non-zero, loudly, if the two solvers disagree beyond rounding (definition in stick_slip_bench.c,
# rounding_ok) for any case at theta = 1/2 or 1. Speed goals are measured and reported, not enforced.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
max_sic=${SICONOS_MAX_STEPS:-1000000}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# ---- the peer, from Debian --------------------------------------------------------------------------------
# scripts/install-deps.sh installs what is missing as root, or prints the apt-get line and fails otherwise.
bash scripts/install-deps.sh --siconos || { echo "siconos.sh: FAIL: the peer is not installed" >&2; exit 1; }

# ---- build ------------------------------------------------------------------------------------------------
# The library as the Makefile builds it (a no-op after `make`), then the three programs: C with the
# Makefile's warnings, the peer against Siconos' headers (-isystem: their warnings are not ours).
make -s BUILD="$build" "$build/libdashpot.a"
mkdir -p "$build/bench"
cflags=(-std=c17 -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes -O2 -g -Iinclude
        -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE)
cc "${cflags[@]}" bench/stick_slip_bench.c -o "$build/bench/stick_slip_bench" "$build/libdashpot.a" \
  -lcjson -lgsl -lgslcblas -lm
cc "${cflags[@]}" bench/floor.c -o "$build/bench/floor" -lm
source bench/siconos_peer.bash
build_siconos_peer siconos_peer
dp="$build/bench/stick_slip_bench" sic="$build/bench/siconos_peer" flo="$build/bench/floor"

# Every program is single-threaded. Not pinned to a core: on a shared machine the scheduler finds the idle
# one, and every figure is the best of several runs. Every Siconos run is bounded: a hang fails the script
# instead of stalling it.
sic_run() { timeout 300 "$sic" "$@"; }

kv() { awk -v k="$2" '$1 == k { print $2; f = 1 } END { if (!f) print "-" }' "$1"; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.0f", a / b; else printf "-" }'; }
ratio1() { awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.1f", a / b; else printf "-" }'; }
# Running extremes for the goals line: keep the smaller (min) or larger (max) of two numbers.
minof() { awk -v a="$1" -v b="$2" 'BEGIN { print (a == "" || b + 0 < a + 0) ? b : a }'; }
maxof() { awk -v a="$1" -v b="$2" 'BEGIN { print (a == "" || b + 0 > a + 0) ? b : a }'; }

# ---- the cases (the same key=value words go to all three programs) ------------------------------------------
names=(free-decay harmonic belt)
declare -A spec=(
  [free-decay]="m=1 k=1 phi0=1 x0=4.5 v0=0"                      # README's example: sticks at t = 2 pi
  [harmonic]="m=1 k=1 phi0=0.8 amp=1 omega=1.3 x0=0 v0=0"        # 9 stick phases in 20 s
  [belt]="m=1 k=1 phi0=1 vb=0.5 x0=-2 v0=0"                      # crosses the belt speed, sticks, breaks away
)
dt=1e-3
acc_steps=20000   # t_end = 20
fail=0

echo "stick-slip: dashpot vs Siconos $(dpkg-query -W -f='${Version}' libsiconos-kernel-dev) (EulerMoreauOSI + Relay/Lemke), dt = $dt; times: best of runs, one thread each"
echo
echo "accuracy over $acc_steps steps (dashpot \"events\":\"none\" vs Siconos, step by step; err = max error against the closed form)"
printf '  %-10s %-5s %9s %9s %9s  %-8s %10s %10s %10s %10s %10s\n' case theta 'max|dx|' 'max|dv|' 'max|dF|' rounding \
  'err_x dp' 'err_x sic' 'err_v dp' 'err_v sic' 'err_x loc'
for c in "${names[@]}"; do
  for th in 0.5 1; do
    # shellcheck disable=SC2086 # the spec is a list of words on purpose
    sic_run ${spec[$c]} dt=$dt steps=$acc_steps theta=$th out="$tmp/sic.bin" >"$tmp/sic.txt"
    out="$tmp/cmp.$c.$th"
    # shellcheck disable=SC2086
    "$dp" mode=compare ${spec[$c]} dt=$dt steps=$acc_steps theta=$th sic="$tmp/sic.bin" >"$out"
    verdict=ok
    [ "$(kv "$out" rounding)" = 1 ] || verdict=quadr
    if [ "$(kv "$out" agree)" != 1 ]; then verdict=FAIL; fail=1; fi
    printf '  %-10s %-5s %9s %9s %9s  %-8s %10s %10s %10s %10s %10s\n' "$c" "$th" "$(kv "$out" max_dx)" \
      "$(kv "$out" max_dv)" "$(kv "$out" max_dF)" "$verdict" "$(kv "$out" err_x_dashpot)" \
      "$(kv "$out" err_x_siconos)" "$(kv "$out" err_v_dashpot)" "$(kv "$out" err_v_siconos)" \
      "$(kv "$out" err_x_located)"
    if [ "$(kv "$out" matched_load_max_dx)" != - ] && [ "$(kv "$out" rounding)" != 1 ]; then
      printf '  %-16s load quadrature matched (Siconos weights theta F(t+h) + (1-theta) F(t)): max|dx| %s max|dv| %s max|dF| %s\n' \
        '' "$(kv "$out" matched_load_max_dx)" "$(kv "$out" matched_load_max_dv)" "$(kv "$out" matched_load_max_dF)"
    fi
  done
done
echo "  rounding: |dx| <= N eps (1 + max|x|), |dv| likewise, |dF| <= N eps (1 + max|F|) + N eps (1 + max|v|) m/dt;"
echo "  quadr: differ by the load's quadrature only (matched-load line below it); err_x loc: dashpot's default"
echo "  \"events\":\"locate\" at the same dt; '-': no closed form (harmonic load)"
echo

echo "cost per step over 1e5 steps, output off (dashpot \"samples\":false; Siconos: the loop, no output)"
printf '  %-10s %-5s %12s %12s %8s   %10s %10s\n' case theta 'dashpot ns' 'Siconos ns' ratio 'dp RSS kB' 'sic RSS kB'
for c in "${names[@]}"; do
  for th in 0.5 1; do
    # shellcheck disable=SC2086
    "$dp" mode=time ${spec[$c]} dt=$dt steps=100000 reps=20 theta=$th >"$tmp/d.txt"
    # shellcheck disable=SC2086
    sic_run ${spec[$c]} dt=$dt steps=100000 reps=2 theta=$th >"$tmp/s.txt"
    a=$(kv "$tmp/d.txt" ns_per_step) b=$(kv "$tmp/s.txt" ns_per_step)
    min_speedup=$(minof "${min_speedup:-}" "$(ratio "$b" "$a")")
    printf '  %-10s %-5s %12s %12s %7sx   %10s %10s\n' "$c" "$th" "$a" "$b" "$(ratio "$b" "$a")" \
      "$(kv "$tmp/d.txt" maxrss_kb)" "$(kv "$tmp/s.txt" maxrss_kb)"
  done
done
echo

echo "growth with the number of steps (theta = 1/2, dt = $dt: t_end grows with N); Siconos capped at $max_sic steps"
printf '  %-10s %9s %12s %10s %12s %10s %8s\n' case N 'dashpot ns' 'dp RSS kB' 'Siconos ns' 'sic RSS kB' ratio
for c in "${names[@]}"; do
  for n in 10000 100000 1000000 10000000; do
    reps=$(( n >= 10000000 ? 5 : 10000000 / n > 100 ? 100 : 10000000 / n ))
    # shellcheck disable=SC2086
    "$dp" mode=time ${spec[$c]} dt=$dt steps=$n reps=$reps >"$tmp/d.$c.$n"
    a=$(kv "$tmp/d.$c.$n" ns_per_step) b=- rs=-
    if [ "$n" -le "$max_sic" ]; then
      # shellcheck disable=SC2086
      sic_run ${spec[$c]} dt=$dt steps=$n reps=$(( n <= 10000 ? 3 : 1 )) >"$tmp/s.txt"
      b=$(kv "$tmp/s.txt" ns_per_step) rs=$(kv "$tmp/s.txt" maxrss_kb)
    fi
    r=-
    [ "$b" != - ] && r="$(ratio "$b" "$a")x"
    printf '  %-10s %9s %12s %10s %12s %10s %8s\n' "$c" "$n" "$a" "$(kv "$tmp/d.$c.$n" maxrss_kb)" "$b" "$rs" "$r"
  done
done
[ "$max_sic" -lt 10000000 ] && echo "  '-': Siconos not run (~70 s per case at 1e7 steps); SICONOS_MAX_STEPS=10000000 runs it"
echo

echo "dashpot against the physical floor (bench/floor.c: the bare theta-step loop), 1e7 steps, theta = 1/2"
printf '  %-10s %12s %10s %8s\n' case 'dashpot ns' 'floor ns' ratio
for c in "${names[@]}"; do
  cp "$tmp/d.$c.10000000" "$tmp/d.txt" # dashpot's run of the growth table
  # shellcheck disable=SC2086
  "$flo" ${spec[$c]} dt=$dt steps=10000000 reps=5 >"$tmp/f.txt"
  # The floor must compute the same trajectory, or its time means nothing.
  if ! awk -v a="$(kv "$tmp/d.txt" final_x)" -v b="$(kv "$tmp/f.txt" final_x)" \
         'BEGIN { d = a - b; if (d < 0) d = -d; m = a < 0 ? -a : a; exit !(d <= 1e-6 * (1 + m)) }'; then
    echo "siconos.sh: FAIL: floor.c ends at x = $(kv "$tmp/f.txt" final_x), dashpot at $(kv "$tmp/d.txt" final_x) ($c)" >&2
    fail=1
  fi
  a=$(kv "$tmp/d.txt" ns_per_step) b=$(kv "$tmp/f.txt" ns_per_step)
  max_floor=$(maxof "${max_floor:-}" "$(ratio1 "$a" "$b")")
  printf '  %-10s %12s %10s %7sx\n' "$c" "$a" "$b" "$(ratio1 "$a" "$b")"
done
echo

echo "every sample encoded as NDJSON (dp_encoder_record into a dp_buf reset per 4096-record block), 1e6 steps, theta = 1/2"
printf '  %-10s %12s %14s %14s %10s\n' case 'samples/s' 'encode ns/smp' 'solve ns/smp' 'bytes/smp'
for c in "${names[@]}"; do
  # shellcheck disable=SC2086
  "$dp" mode=ndjson ${spec[$c]} dt=$dt steps=1000000 reps=3 >"$tmp/n.txt"
  min_ndjson=$(minof "${min_ndjson:-}" "$(kv "$tmp/n.txt" samples_per_second)")
  printf '  %-10s %12s %14s %14s %10s\n' "$c" "$(kv "$tmp/n.txt" samples_per_second)" \
    "$(kv "$tmp/n.txt" encode_ns_per_sample)" "$(kv "$tmp/n.txt" solve_ns_per_sample)" \
    "$(kv "$tmp/n.txt" bytes_per_sample)"
done
echo
# The speed goals: measured and reported, not enforced (they depend on the machine and its load).
goal() { awk -v n="$1" -v v="$2" -v g="$3" -v op="$4" 'BEGIN { ok = op == "<=" ? v + 0 <= g + 0 : v + 0 >= g + 0
         printf "  %-44s %10s  (goal %s %s)  %s\n", n, v, op, g, ok ? "met" : "NOT met" }'; }
echo "goals (measured, not enforced)"
goal "dashpot output off / floor, worst case" "${max_floor}x" 5 "<="
goal "Siconos / dashpot time per step, worst case" "${min_speedup}x" 500 ">="
goal "NDJSON samples/s, worst case" "$min_ndjson" 5e6 ">="

if [ "$fail" -ne 0 ]; then
  echo "siconos.sh: FAIL: dashpot and Siconos disagree beyond rounding (table above, 'FAIL' rows)" >&2
  exit 1
fi
