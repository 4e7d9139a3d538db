#!/usr/bin/env bash
# scripts/thesis-figures.sh - the data behind the thesis' (Babováková 2012) Figs. 4.2-4.5: m = k = phi0 = 1, T = 10, dt = 1e-3,
# x0 in {0..5}, x1 = 0, F = 0, algorithm 4.1 (Z = 100, eps = 1e-4), without and with gamma = 0.5 v/(1+|v|).
# Usage: thesis-figures.sh DASHPOT_BINARY OUT_DIR. Writes OUT_DIR/x0_<x0>_<plain|relaxed>.csv (t,x,v,Fs,Fd,Fc,
# phase: Fig. 4.2 is v against x, 4.3 F_d against v, 4.4 x and v against t, 4.5 F_d and F_s against t) and
# OUT_DIR/summary.csv (rest position and stick time of each run, next to the closed form for the plain runs).
set -euo pipefail
bin=${1:?usage: thesis-figures.sh DASHPOT_BINARY OUT_DIR}
out=${2:?usage: thesis-figures.sh DASHPOT_BINARY OUT_DIR}
mkdir -p "$out"
echo "x0,relaxation,rest_x,stick_time,closed_form_rest_x,closed_form_stick_time" > "$out/summary.csv"
for x0 in 0 1 2 3 4 5; do
  for kind in plain relaxed; do
    relax=""
    [ "$kind" = relaxed ] && relax=',"relaxation":{"kind":"rational","a":0.5,"b":1}'
    spec='{"model":{"mass":1,"spring":{"law":"linear","k":1},"damper":{"law":"coulomb","phi0":1'"$relax"'}},
           "initial":{"x":'"$x0"',"v":0},
           "solver":{"kind":"stick-slip","variant":"thesis","dt":1e-3,"t_end":10,"Z":100,"eps":1e-4}}'
    echo "$spec" | "$bin" simulate - --format csv --quiet > "$out/x0_${x0}_${kind}.csv"
    summary=$(echo "$spec" | "$bin" simulate - --format ndjson --quiet | tail -n 1)
    rest=$(echo "$summary" | python3 -c 'import json,sys; s=json.load(sys.stdin); print(s["final"]["x"], s["stick_time"])')
    # closed form (4.14): turning points shrink by 2 phi0/k until |x| <= phi0/k, each half swing takes pi
    cf=$(python3 -c "
import math
x=float($x0); t=0.0
while abs(x) > 1: x = -(abs(x) - 2) * (1 if x > 0 else -1); t += math.pi
print(x, 10 - t)")
    [ "$kind" = relaxed ] && cf=", "
    echo "$x0,$kind,${rest// /,},${cf// /,}" >> "$out/summary.csv"
  done
done
column -s, -t < "$out/summary.csv"
