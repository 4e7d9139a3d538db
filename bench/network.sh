#!/usr/bin/env bash
# bench/network.sh - networks of masses: dashpot's exact network step next to Siconos on chains
# of 10, 100 and 1000 blocks with Coulomb friction on every block (bench/siconos_chain_peer.cpp:
# EulerMoreauOSI + one Relay row per Coulomb element), step by step at theta = 1/2 and 1, and a network with
# friction between two masses; Burridge-Knopoff chains of 10^2, 10^3, 10^4 blocks (cost per block-step, its
# growth, memory for two run lengths); a one-node network against the one-mass model. bench/network_bench.c
# is dashpot's side. docs/benchmarks.md ("Networks") explains the figures.
#
# Usage: BUILD=build bash bench/network.sh   (also run by `make bench` and `make bench-peers`)
#   SICONOS_CHAIN1000_STEPS (default 1): Siconos takes 25-35 s a step at 1000 blocks (its dense Lemke solve of
#   the 2n x 2n relay LCP and the n x 2n Delassus product grow like n^3), so it is stepped this many times.
# Exits non-zero, loudly, if dashpot and Siconos disagree beyond rounding (network_bench.c, rounding_ok) in
# any case. Speed goals are measured and reported, not enforced.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
sic1000=${SICONOS_CHAIN1000_STEPS:-1}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

bash scripts/install-deps.sh --siconos || { echo "network.sh: FAIL: the peer is not installed" >&2; exit 1; }
make -s BUILD="$build" "$build/libdashpot.a"
mkdir -p "$build/bench"
cflags=(-std=c17 -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes -O2 -g -Iinclude
        -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE)
cc "${cflags[@]}" bench/network_bench.c -o "$build/bench/network_bench" "$build/libdashpot.a" \
  -lcjson -lgsl -lgslcblas -lm
cc "${cflags[@]}" bench/floor.c -o "$build/bench/floor" -lm
source bench/siconos_peer.bash
build_siconos_peer siconos_chain_peer
dp="$build/bench/network_bench" sic="$build/bench/siconos_chain_peer"

# Single-threaded programs, best of several runs where affordable; every Siconos run is bounded.
sic_run() { OPENBLAS_NUM_THREADS=1 timeout 900 "$sic" "$@"; } # one thread, as dashpot
kv() { awk -v k="$2" '$1 == k { print $2; f = 1 } END { if (!f) print "-" }' "$1"; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0 && a != "-") printf "%.0f", a / b; else printf "-" }'; }
ratio2() { awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0 && a != "-") printf "%.2f", a / b; else printf "-" }'; }
goal() { awk -v n="$1" -v v="$2" -v g="$3" -v op="$4" -v note="${5:-}" 'BEGIN {
         ok = op == "<=" ? v + 0 <= g + 0 : v + 0 >= g + 0
         printf "  %-52s %10s  (goal %s %s)  %-7s %s\n", n, v, op, g, ok ? "met" : "NOT met", note }'; }
fail=0

# ---- the cases (the same key=value words go to both programs) -------------------------------------------
# chain: ground spring kg and Coulomb friction on a belt at vb on every block (bounds 0.5 (1 + 0.3 sin 2.3 i)),
# neighbour springs kc, x_i(0) = cos(1.3 i). pair2: two masses, friction between them and none on the
# ground (the belt is still). chain10p: friction on every neighbour pair too, and a constant load on the last
# block. Loads are constant or zero: Siconos weights a load theta F(t+h) + (1-theta) F(t), dashpot takes
# F(t + theta h), equal only for constant loads (bench/siconos.sh matches them for a harmonic load).
chain="kg=1 kc=1 phi0=0.5 het=0.3 vb=0.5 xamp=1"
declare -A agree=(
  [chain10]="n=10 $chain steps=2000"
  [chain100]="n=100 $chain steps=300"
  [chain1000]="n=1000 $chain steps=$sic1000"
  [pair2]="n=2 kg=1 kc=2 phi0=0 phic=0.4 vb=0 xamp=1 steps=2000"
  [chain10p]="n=10 $chain phic=0.2 F0=0.3 steps=2000"
)
order=(chain10 chain100 chain1000 pair2 chain10p)

echo "networks: dashpot vs Siconos $(dpkg-query -W -f='${Version}' libsiconos-kernel-dev) (EulerMoreauOSI + Relay/Lemke, one row per Coulomb element), dt = 1e-3"
echo
echo "agreement, \"events\":\"none\", every step, every node (tol: N n eps relative, network_bench.c rounding_ok)"
printf '  %-10s %-5s %6s %7s %9s %9s %9s %9s %9s %9s  %-6s %12s\n' case theta steps events 'max|dx|' 'max|dv|' \
  'max|dR|' 'split' 'over' 'tol_rel' verdict 'Siconos ns'
for c in "${order[@]}"; do
  for th in 0.5 1; do
    # shellcheck disable=SC2086 # the case is a list of words on purpose
    sic_run ${agree[$c]} dt=1e-3 theta=$th out="$tmp/sic.bin" >"$tmp/s.$c.$th"
    # shellcheck disable=SC2086
    "$dp" mode=compare ${agree[$c]} dt=1e-3 theta=$th sic="$tmp/sic.bin" >"$tmp/cmp" || echo "agree 0" >>"$tmp/cmp"
    verdict=ok
    if [ "$(kv "$tmp/cmp" agree)" != 1 ]; then verdict=FAIL; fail=1; fi
    printf '  %-10s %-5s %6s %7s %9s %9s %9s %9s %9s %9s  %-6s %12s\n' "$c" "$th" "$(kv "$tmp/cmp" steps)" \
      "$(kv "$tmp/cmp" events)" "$(kv "$tmp/cmp" max_dx)" "$(kv "$tmp/cmp" max_dv)" "$(kv "$tmp/cmp" max_dR)" \
      "$(kv "$tmp/cmp" max_split)" "$(kv "$tmp/cmp" max_over)" "$(kv "$tmp/cmp" tol_rel)" "$verdict" \
      "$(kv "$tmp/s.$c.$th" ns_per_step)"
  done
done
echo "  dR: the friction forces' resultant on each node (unique; rounding allowance dv's times m/dt, as it is"
echo "  recovered from one step's momentum balance); split: element forces, not unique where stuck elements close a"
echo "  cycle (ground-i-(i+1)-ground in chain10p), reported only; over: a force's excess over its bound, either code"
echo

echo "time per step, chains with Coulomb friction on every block (theta = 1/2; Siconos: the agreement runs above)"
printf '  %-6s %12s %12s %10s %14s %9s   %-24s\n' blocks 'dashpot ns' 'Siconos ns' ratio 'dp ns/block' 'dp ev/step' windows
for n in 10 100 1000; do
  steps=$(( n == 1000 ? 2000 : 20000 ))
  # shellcheck disable=SC2086
  "$dp" mode=time n=$n $chain steps=$steps reps=$(( n == 1000 ? 2 : 5 )) >"$tmp/d.txt"
  a=$(kv "$tmp/d.txt" ns_per_step) b=$(kv "$tmp/s.chain$n.0.5" ns_per_step)
  [ "$n" = 100 ] && speed100=$(ratio "$b" "$a") blk100=$(kv "$tmp/d.txt" ns_per_block_step)
  printf '  %-6s %12s %12s %9sx %14s %9s   dashpot %s steps, Siconos %s\n' "$n" "$a" "$b" "$(ratio "$b" "$a")" \
    "$(kv "$tmp/d.txt" ns_per_block_step)" "$(kv "$tmp/d.txt" events_per_step)" "$steps" \
    "$(kv "$tmp/s.chain$n.0.5" steps)"
done
echo "  Siconos at 1000 blocks: $sic1000 step(s) (SICONOS_CHAIN1000_STEPS), 25-35 s each"
# The floor of a block-step: bench/floor.c, the bare theta-step of one block (m = 1, kg = 1, phi0 = 0.5 on the
# belt at 0.5) in a C loop with its constants hoisted; a block of the chain does that and its share of the band
# products and solves, so the floor is a lower bound, not a target.
"$build/bench/floor" m=1 k=1 phi0=0.5 vb=0.5 x0=1 steps=10000000 reps=3 >"$tmp/floor.txt"
floor_blk=$(kv "$tmp/floor.txt" ns_per_step)
echo "  floor: the bare theta-step of one block (bench/floor.c), $floor_blk ns per block-step"
echo

# Burridge-Knopoff in the plate's frame: leaf springs kg = 1, neighbour springs kc = 10, friction bounds
# 1 + 0.5 sin(2.3 i) on a belt at -V = -0.1, x_i(0) = 0.5 cos(1.3 i). The same simulated window (t = 0.5,
# 500 steps) at every size, so that the phase changes per block-step are comparable.
bk="kg=1 kc=10 phi0=1 het=0.5 vb=-0.1 xamp=0.5"
echo "Burridge-Knopoff scaling, \"events\":\"none\", theta = 1/2, 500 steps (t = 0.5), output off"
printf '  %-6s %12s %12s %10s %12s %10s %10s %12s %12s\n' blocks 'ns/step' 'ns/block' 'ev/step' 'ev/blk-step' \
  'stick' 'iter/step' 'RSS kB 500' 'RSS kB 2000'
for n in 100 1000 10000; do
  reps=$(( n == 10000 ? 1 : n == 1000 ? 3 : 10 ))
  # shellcheck disable=SC2086
  "$dp" mode=time n=$n $bk steps=500 reps=$reps >"$tmp/b.$n"
  # shellcheck disable=SC2086
  "$dp" mode=time n=$n $bk steps=2000 reps=1 >"$tmp/b4.$n"
  printf '  %-6s %12s %12s %10s %12s %10s %10s %12s %12s\n' "$n" "$(kv "$tmp/b.$n" ns_per_step)" \
    "$(kv "$tmp/b.$n" ns_per_block_step)" "$(kv "$tmp/b.$n" events_per_step)" \
    "$(awk -v e="$(kv "$tmp/b.$n" events_per_step)" -v n="$n" 'BEGIN { printf "%.2g", e / n }')" \
    "$(kv "$tmp/b.$n" stick_fraction)" "$(kv "$tmp/b.$n" iterations_per_step)" "$(kv "$tmp/b.$n" maxrss_kb)" \
    "$(kv "$tmp/b4.$n" maxrss_kb)"
done
growth=$(ratio2 "$(kv "$tmp/b.10000" ns_per_block_step)" "$(kv "$tmp/b.100" ns_per_block_step)")
rss_growth=$(ratio2 "$(kv "$tmp/b4.10000" maxrss_kb)" "$(kv "$tmp/b.10000" maxrss_kb)")
echo "  stick: fraction of block-time stuck; iter/step: active-set iterations (each a pass over the whole band;"
echo "  a refactorization where the assignment's structure changed)"
echo

# The same chains with located events: every phase change splits its step at the instant it happens, found
# by a bracketed root of the held assignment's margins (the root search's held solves over the stretches
# between stuck blocks that its candidates need; the end margins, the state at the event and the rest of the
# step over the whole band), so the cost per step is about (1 + assignment changes per step x a few whole
# solves) x O(n): it grows with the number of changes per step, which grows with n in this window
# (docs/benchmarks.md, "Networks").
echo "the same chains with located events (\"events\":\"locate\"), 500 steps"
printf '  %-6s %12s %12s %10s\n' blocks 'ns/step' 'ns/block' 'ev/step'
for n in 100 1000 10000; do
  reps=$(( n == 10000 ? 1 : n == 1000 ? 2 : 5 ))
  # shellcheck disable=SC2086
  "$dp" mode=time n=$n $bk steps=500 reps=$reps locate=1 >"$tmp/l.$n"
  printf '  %-6s %12s %12s %10s\n' "$n" "$(kv "$tmp/l.$n" ns_per_step)" "$(kv "$tmp/l.$n" ns_per_block_step)" \
    "$(kv "$tmp/l.$n" events_per_step)"
done
lgrowth=$(ratio2 "$(kv "$tmp/l.10000" ns_per_block_step)" "$(kv "$tmp/l.100" ns_per_block_step)")
located10k=$(ratio2 "$(kv "$tmp/l.10000" ns_per_step)" "$(kv "$tmp/b.10000" ns_per_step)")
echo "  growth of the cost per block-step, 10^4 / 10^2 blocks: ${lgrowth}x (bounded by the phase changes per step)"
echo

echo "one node against the one-mass model (m = 1, k = 1, phi0 = 1, belt 0.5, x0 = -2; \"events\":\"none\"), 1e5 steps"
"$dp" mode=single kg=1 phi0=1 vb=0.5 xamp=-2 steps=100000 reps=5 >"$tmp/one.txt"
printf '  %-22s %12s %12s %8s  %s\n' '' 'one-mass ns' 'network ns' ratio 'final x: one-mass / network'
printf '  %-22s %12s %12s %7sx  %s / %s\n' '1 node, 1 element' "$(kv "$tmp/one.txt" one_mass_ns_per_step)" \
  "$(kv "$tmp/one.txt" network_ns_per_step)" "$(kv "$tmp/one.txt" ratio)" \
  "$(kv "$tmp/one.txt" final_x_one_mass)" "$(kv "$tmp/one.txt" final_x_network)"
echo

echo "goals (measured, not enforced)"
goal "Siconos / dashpot time per step, 100 blocks" "${speed100}x" 4000 ">="
goal "dashpot ns per block-step, 100 blocks" "$blk100" 50 "<=" "(floor $floor_blk ns)"
goal "BK cost per block-step, 10^4 / 10^2 blocks" "${growth}x" 1.5 "<="
goal "BK peak RSS, 2000 / 500 steps at 10^4 blocks" "${rss_growth}x" 1.05 "<="
goal "BK located / \"none\" time per step at 10^4 blocks" "${located10k}x" 5 "<="
goal "one-node network / one-mass time per step" "$(kv "$tmp/one.txt" ratio)x" 1.5 "<="

if [ "$fail" -ne 0 ]; then
  echo "network.sh: FAIL: dashpot and Siconos disagree beyond rounding on a network (table above, 'FAIL' rows)" >&2
  exit 1
fi
