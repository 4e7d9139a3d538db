#!/usr/bin/env bash
# tests/test_lcs.sh - `dashpot lcp` and POST /v1/lcp end to end: Cibulka 2014's Examples 1.6 and 2.4
# with their own numbers (closed forms in the comments, checked here in Python), a 3-solution problem whose
# solutions are computed by hand, the CLI and the daemon answering byte for byte alike, and bad input (422
# with JSON Pointers, CLI exit 2, 400 for malformed JSON), the problem's units (scaled by 1e±10 .. 1e±200: one
# solution, not the 2, 4 or 6 an absolute tolerance listed; a solution beyond the doubles a 422 at /q), Lemke's
# pivot limit on Murty 1978's matrix (answered by the enumeration at m = 12, a 422 at /M above, at /solver in
# an LCS), then the LCS circuits of docs/lcs.md and their derived matrices leaving the doubles (422 at the member).
# Env BUILD (default build). Prints "N passed, M failed"; exit 1 on any failure.
source "$(dirname "$0")/lib/daemon.bash"

BIN=$BUILD/dashpot
T=$SCRATCH

pyjson() {
    python3 -c 'import json,math,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if eval("(" + sys.argv[2] + ")") else 1)' "$1" "$2" ||
        { echo "    $2 fails for: $(head -c 600 "$1")"; return 1; }
}

# Example 1.6: 0 <= u ⊥ v + u >= 0 -> u = max(-v, 0), w = v + u = max(v, 0); v = (-1.5, 2, 0, -3).
echo '{"M": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]], "q": [-1.5, 2, 0, -3]}' >"$T/ex16.json"
"$BIN" lcp "$T/ex16.json" >"$T/ex16.out"
check "lcp Example 1.6: u = v^-, w = v^+, one solution, P-matrix, mu = 1" pyjson "$T/ex16.out" "
d['lemke']['z'] == [1.5, 0, 0, 3] and d['lemke']['w'] == [0, 2, 0, 0] and d['count'] == 1 and
d['solutions'][0]['z'] == [1.5, 0, 0, 3] and d['theory']['p_matrix'] is True and d['theory']['mu'] == 1 and
d['theory']['lipschitz'] == 1 and d['verdict'].startswith('exactly one solution')"

# Example 2.4: p in a u + N_R+(u) is M = [a], q = [-p]. a = -2, p = -3: u = 0 and u = p/a = 1.5 (Fig. 7, a < 0).
echo '{"M": [[-2]], "q": [3]}' >"$T/ex24.json"
"$BIN" lcp "$T/ex24.json" >"$T/ex24.out"
check "lcp Example 2.4, a < 0: two solutions 0 and p/a, not a P-matrix (minor -2)" pyjson "$T/ex24.out" "
sorted(s['z'][0] for s in d['solutions']) == [0, 1.5] and d['count'] == 2 and
d['theory']['p_matrix'] is False and d['theory']['minor_witness'] == {'rows': [0], 'minor': -2} and
d['theory']['mu'] == -2 and d['theory']['lipschitz'] is None and d['verdict'].startswith('2 solutions')"
# a = 0.5, p = 2: u = p/a = 4, mu = a, Lipschitz constant L/mu = 2 (Theorem 2.3).
echo '{"M": [[0.5]], "q": [-2]}' | "$BIN" lcp - >"$T/ex24b.out"
check "lcp Example 2.4, a > 0: u = p/a = 4, mu = 0.5, Lipschitz 2" pyjson "$T/ex24b.out" "
d['lemke']['z'] == [4] and d['count'] == 1 and d['theory']['mu'] == 0.5 and d['theory']['lipschitz'] == 2"
# a = 0, p = 1: no solution (Lemke's ray); a = 0, p = 0: u = 0 and the singular basis (every u >= 0 solves).
echo '{"M": [[0]], "q": [-1]}' | "$BIN" lcp - >"$T/ex24c.out"
check "lcp Example 2.4, a = 0, p > 0: no solution, Lemke's ray" pyjson "$T/ex24c.out" "
d['lemke']['outcome'] == 'ray' and d['lemke']['z'] is None and d['count'] == 0 and d['verdict'].startswith('no solution: Lemke')"
echo '{"M": [[0]], "q": [0]}' | "$BIN" lcp - >"$T/ex24d.out"
check "lcp Example 2.4, a = 0, p = 0: u = 0 and a singular basis (a continuum)" pyjson "$T/ex24d.out" "
d['count'] == 1 and d['singular_bases'] == 1 and 'continuum' in d['verdict']"

# M = [[1, 2], [3, 1]], q = (-1, -1): z = (1, 0), (0, 1), and both w = 0: z = M^-1 (1, 1) = (1/5, 2/5).
echo '{"M": [[1, 2], [3, 1]], "q": [-1, -1]}' >"$T/three.json"
"$BIN" lcp "$T/three.json" >"$T/three.out"
check "lcp: three solutions of a non-P matrix, Lemke's is one of them" pyjson "$T/three.out" "
d['count'] == 3 and
sorted([round(x, 15) for x in s['z']] for s in d['solutions']) == [[0, 1], [0.2, 0.4], [1, 0]] and
d['lemke']['z'] in [s['z'] for s in d['solutions']] and d['theory']['minor_witness']['minor'] == -5"

bad() { # bad NAME DOC POINTER: exit 2 and the pointer on stderr
    echo "$2" | "$BIN" lcp - >/dev/null 2>"$T/err"
    local rc=$?
    [ $rc = 2 ] && grep -q -- "-: $3: " "$T/err" || { echo "    exit $rc: $(cat "$T/err")"; return 1; }
}
check "lcp: a short row named" bad row '{"M": [[1, 2], [3]], "q": [1, 1]}' /M/1
check "lcp: q of another length named" bad q '{"M": [[1]], "q": [1, 2]}' /q
check "lcp: a string entry named" bad entry '{"M": [[1, "x"], [0, 1]], "q": [1, 1]}' /M/0/1
check "lcp: a missing M named" bad missing '{"q": [1]}' /M
check "lcp: an unknown key named at its pointer" bad key '{"M": [[1]], "q": [1], "r": 1}' /r
check "lcp: a repeated key named, as on every route" bad dup '{"M": [[1]], "q": [1], "q": [2]}' /q
check "lcp: a repeated key inside M's rows is no key, but one in a nested object is" bad dupdeep \
    '{"M": [[1]], "q": [1], "r": {"a": 1, "a": 2}}' /r/a
check "lcp: a NUL in a key (cJSON would read \"q\") named at its object" bad nulkey '{"M": [[1]], "q\u0000": [1]}' \
    '(document)'

# ---- the problem's units, Lemke's pivot limit (docs/lcs.md, "Scaling, tolerances and limits") ----
lcpcount() { # lcpcount DOC COUNT: the CLI lists COUNT solutions, each z >= 0, w >= 0, zᵀw = 0, the verdict agreeing
    echo "$1" | "$BIN" lcp - >"$T/sc.out" && pyjson "$T/sc.out" "
d['count'] == $2 == len(d['solutions']) and all(min(s['z']) >= 0 and min(s['w']) >= 0 and
all(a * b == 0 for a, b in zip(s['z'], s['w'])) for s in d['solutions']) and
(d['verdict'].startswith('exactly one') == (d['count'] == 1))"
}
check "lcp: w = Mz + q at 1e9 has one solution listed, not two (the tolerance was absolute)" \
    lcpcount '{"M": [[1.42, 0], [2.84, 2]], "q": [8.9e9, -1.9e8]}' 1
spd_scaled() { # spd_scaled C: [[2, 1], [1, 2]] z = (1, 1) times C answers one solution z = (1/3, 1/3), P-matrix
    python3 -c "import json; c=float('$1'); print(json.dumps({'M': [[2*c, c], [c, 2*c]], 'q': [-c, -c]}))" >"$T/spd.json"
    "$BIN" lcp "$T/spd.json" >"$T/spd.out" && pyjson "$T/spd.out" "
d['count'] == 1 and all(abs(x - 1/3) < 1e-15 for x in d['solutions'][0]['z']) and d['theory']['p_matrix'] is True"
}
for c in 1e10 1e-10 1e60 1e-60 1e200 1e-200; do
    check "lcp: the SPD problem times $c: one solution z = (1/3, 1/3), P-matrix true" spd_scaled $c
done
echo '{"M": [[1e200, 0], [0, 1e200]], "q": [-1, -1]}' | "$BIN" lcp - >"$T/big.out"
check "lcp: 1e200 I solved with z = 1e-200, w = 0 (not w = -1)" pyjson "$T/big.out" "
d['lemke']['z'] == [1e-200, 1e-200] and d['lemke']['w'] == [0, 0] and d['theory']['p_matrix'] is True"
check "lcp: a solution beyond the doubles (z = 1e400) is a 422 at /q, never z = null" bad huge \
    '{"M": [[1e-200, 0], [0, 1e-200]], "q": [-1e200, -1]}' /q
murty() { # murty M: Murty 1978's matrix (1 on the diagonal, 3/2 below), q = -e, as a document
    python3 -c "import json; m=$1; print(json.dumps({'M': [[1 if i == j else 1.5 if j < i else 0 for j in range(m)]
        for i in range(m)], 'q': [-1] * m}))"
}
murty 12 >"$T/murty12.json"
"$BIN" lcp "$T/murty12.json" >"$T/murty12.out"
check "lcp: Murty's matrix, m = 12: Lemke's pivot limit, the enumeration answers: one solution, e_1" pyjson "$T/murty12.out" "
d['lemke']['outcome'] == 'pivot-limit' and d['lemke']['z'] is None and d['count'] == 1 and
d['solutions'][0]['z'] == [1] + [0] * 11 and d['theory']['p_matrix'] is True and d['verdict'].startswith('exactly one')"
murty 13 >"$T/murty13.json"
"$BIN" lcp "$T/murty13.json" >/dev/null 2>"$T/err"
check "lcp: Murty's matrix, m = 13: the pivot limit named at /M with its number" \
    grep -q -- "/M: Lemke's method took its limit of 3600 pivots" "$T/err"
python3 -c "import json; m=13; print(json.dumps({'model': {'lcs': {'A': [[0]], 'B': [[0] * m], 'C': [[0]] * m,
    'D': [[1 if i == j else 1.5 if j < i else 0 for j in range(m)] for i in range(m)], 'q': [-1] * m},
    'laws': [{'law': 'complementarity'}] * m}, 'initial': {'x': [0]},
    'solver': {'kind': 'stick-slip', 'dt': 0.1, 't_end': 1, 'theta': 0.5}}))" >"$T/lcsmurty.json"
"$BIN" simulate "$T/lcsmurty.json" >/dev/null 2>"$T/err"
check "simulate lcs: Lemke's pivot limit on the algebraic part is the solver's, at /solver, not /initial/x" \
    bash -c "grep -q -- ': /solver: Lemke.s method took its limit of 3600 pivots' '$T/err' && ! grep -q /initial/x '$T/err'"

# ---- LCS models in `dashpot simulate` (docs/lcs.md) ----
# Series RLC with an ideal diode (Cibulka 2014 Ex. 1.9), R = 0.5, L = 1, C = 0.25, x = (charge, current), no source.
cat >"$T/rlc.json" <<'JSON'
{"model": {"lcs": {"A": [[0, 1], [-4, -0.5]], "B": [[0], [1]], "C": [[0, 1]], "D": [[0]]},
           "laws": [{"law": "complementarity"}]},
 "initial": {"x": [0, 1]},
 "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 3, "theta": 0.5}}
JSON
"$BIN" simulate "$T/rlc.json" --format ndjson >"$T/rlc.ndjson"
check "simulate rlc.json: exit 0, 3001 rows" [ $? = 0 -a "$(grep -c '"sample"' "$T/rlc.ndjson")" = 3001 ]
# Closed form: q = e^{-at} sin(wd t)/wd, i = e^{-at}(cos wd t - (a/wd) sin wd t), a = R/2L, until
# t* = atan2(wd, a)/wd; then i = 0 for good, q = q*, u = -v_D = q*/C. O(h^2) before t* (u = 0) and after it
# (the switch lands up to h late, but i is linear there, so q* is missed by O(h^2)); measured 3.8e-7, 2.6e-7.
cat >"$T/rlc_check.py" <<'PY'
import json, math, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
meta, samples = rows[0], [r for r in rows if r['type'] == 'sample']
R, L, C = 0.5, 1.0, 0.25
a = R / (2 * L); wd = math.sqrt(1 / (L * C) - a * a); ts = math.atan2(wd, a) / wd
q = lambda t: math.exp(-a * t) * math.sin(wd * t) / wd
i = lambda t: math.exp(-a * t) * (math.cos(wd * t) - a / wd * math.sin(wd * t))
before = [s for s in samples if s['t'] < ts - 0.002]
after = [s for s in samples if s['t'] > ts + 0.002]
e1 = max(max(abs(s['x'][0] - q(s['t'])), abs(s['x'][1] - i(s['t']))) for s in before)
assert e1 < 2e-6, ('before t*', e1)
assert all(abs(s['x'][1]) < 1e-12 and abs(s['x'][0] - q(ts)) < 2e-6 and abs(s['u'][0] - q(ts) / C) < 1e-5 for s in after)
assert all(s['u'][0] >= 0 and s['w'][0] >= 0 and s['u'][0] * s['w'][0] == 0 for s in samples)
assert meta['model'] == 'lcs' and meta['step']['theory']['p_matrix'] is True and meta['step']['uniqueness'].startswith('one u')
ev = [r for r in rows if r['type'] == 'event']
assert meta['events_mode'] == 'locate' and len(ev) == 1, ev  # the diode blocks (u = -v_D leaves 0: "on") at t*
assert ev[0]['kind'] == 'on' and ev[0]['component'] == 0 and ev[0]['mode'] == 1 and abs(ev[0]['t'] - ts) < 1e-6, ev
PY
check "rlc: the closed form before t*, blocked for good after it, 0 <= u ⊥ w >= 0 at every row, one event at t*" python3 "$T/rlc_check.py" "$T/rlc.ndjson"

# "events": "none": the plain θ-steps, no event lines, and the meta line says so.
python3 -c "import json; d=json.load(open('$T/rlc.json')); d['solver']['events']='none'; print(json.dumps(d))" >"$T/rlc_none.json"
"$BIN" simulate "$T/rlc_none.json" --format ndjson >"$T/rlc_none.ndjson"
check "rlc with events none: no event line, events_mode none, the same rows before t*" python3 -c "
import json
a = [json.loads(l) for l in open('$T/rlc_none.ndjson')]; b = [json.loads(l) for l in open('$T/rlc.ndjson')]
assert a[0]['events_mode'] == 'none' and not [r for r in a if r['type'] == 'event']
assert [r for r in a if r['type'] == 'sample' and r['t'] < 0.72] == [r for r in b if r['type'] == 'sample' and r['t'] < 0.72]"

# The same with a breakdown diode, V_b = 0.5 < q*/C: u = v_D in [-0.5, 0], B = -b, C = -c. At t* the
# current reverses: y = q - C V_b, y(s) = y* e^{-as}(cos wd s + (a/wd) sin wd s), i = -y* (w0^2/wd) e^{-as} sin wd s.
cat >"$T/breakdown.json" <<'JSON'
{"model": {"lcs": {"A": [[0, 1], [-4, -0.5]], "B": [[0], [-1]], "C": [[0, -1]]},
           "laws": [{"law": "interval", "min": -0.5, "max": 0}]},
 "initial": {"x": [0, 1]},
 "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 2.2, "theta": 0.5}}
JSON
"$BIN" simulate "$T/breakdown.json" --format ndjson >"$T/bd.ndjson"
cat >"$T/bd_check.py" <<'PY'
import json, math, sys
samples = [r for r in map(json.loads, open(sys.argv[1])) if r['type'] == 'sample']
R, L, C, Vb = 0.5, 1.0, 0.25, 0.5
a = R / (2 * L); w02 = 1 / (L * C); wd = math.sqrt(w02 - a * a); ts = math.atan2(wd, a) / wd
qs = math.exp(-a * ts) * math.sin(wd * ts) / wd; ys = qs - C * Vb
rev = [s for s in samples if ts + 0.005 < s['t'] < ts + math.pi / wd - 0.005]
assert len(rev) > 1000
err = max(max(abs(s['x'][1] + ys * w02 / wd * math.exp(-a * (s['t'] - ts)) * math.sin(wd * (s['t'] - ts))),
              abs(s['x'][0] - C * Vb - ys * math.exp(-a * (s['t'] - ts)) * (math.cos(wd * (s['t'] - ts)) +
                  a / wd * math.sin(wd * (s['t'] - ts))))) for s in rev)
assert err < 2e-6, err  # O(h^2): the switch located inside its step (measured 6.0e-7; 2.2e-4 unlocated)
assert all(s['u'][0] == -Vb for s in rev), 'in breakdown v_D = -V_b'
assert all(-Vb <= s['u'][0] <= 0 for s in samples)
rows = [json.loads(l) for l in open(sys.argv[1])]
ev = [r for r in rows if r['type'] == 'event']
assert rows[0]['events_mode'] == 'locate' and len(ev) == 1, ev
assert ev[0]['kind'] == 'off' and ev[0]['component'] == 0 and ev[0]['mode'] == 0 and abs(ev[0]['t'] - ts) < 1e-6, ev
PY
check "breakdown diode: reverse current about q = C V_b after t*, v_D = -V_b throughout it, one event at t*" \
    python3 "$T/bd_check.py" "$T/bd.ndjson"

# The four-diode bridge (Ex. 1.10) with the seed's matrices, R = 1, L = 1, C = 0.5, x = (v_C, i_L): a parallel
# RLC, v_C = -(i0/(C wd)) e^{-at} sin wd t, a = 1/(2RC), and the load current i_DF1 + i_DR1 = |v_C|/R.
cat >"$T/bridge.json" <<'JSON'
{"model": {"lcs": {"A": [[0, -2], [1, 0]],
                   "B": [[0, 0, -2, 2], [0, 0, 0, 0]],
                   "C": [[0, 0], [0, 0], [-1, 0], [1, 0]],
                   "D": [[1, 1, -1, 0], [1, 1, 0, -1], [1, 0, 0, 0], [0, 1, 0, 0]]},
           "laws": [{"law": "complementarity"}, {"law": "complementarity"},
                    {"law": "complementarity"}, {"law": "complementarity"}]},
 "initial": {"x": [0, 1]},
 "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 8, "theta": 0.5}}
JSON
"$BIN" simulate "$T/bridge.json" --format ndjson >"$T/bridge.ndjson"
cat >"$T/bridge_check.py" <<'PY'
import json, math, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
samples = [r for r in rows if r['type'] == 'sample']
a, wd = 1.0, 1.0
vc = lambda t: -(1 / (0.5 * wd)) * math.exp(-a * t) * math.sin(wd * t)
err = max(abs(s['x'][0] - vc(s['t'])) for s in samples)
assert err < 5e-4, err  # O(h): u is taken at the step's end (measured 3.1e-4)
assert max(abs(s['u'][2] + s['w'][0] - abs(s['x'][0])) for s in samples) < 1e-9
assert any(s['x'][0] > 1e-3 for s in samples) and any(s['x'][0] < -1e-3 for s in samples)
assert rows[0]['step']['theory']['p_matrix'] is False and rows[0]['step']['theory']['positive_semidefinite'] is True
PY
check "bridge: a parallel RLC, the load current |v_C|/R both ways (rectified), the step matrix PSD not P" \
    python3 "$T/bridge_check.py" "$T/bridge.ndjson"

# The one-mass Coulomb oscillator written as an LCS: x = (x, v), u = F_d ∈ φ0 Sgn(v) is u ∈ [-φ0, φ0] with
# v ∈ N(u), i.e. w = -v ∈ -N(u): B = (0, -1/m), C = (0, -1). Its θ-step is the stick-slip solver's own
# (u at the step's end, "events": "none" for both: plain θ-steps), so the two trajectories agree to rounding
# at every step.
for th in 0.5 1; do
    cat >"$T/coulomb.json" <<JSON
{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 1}},
 "initial": {"x": 4.5, "v": 0}, "solver": {"kind": "stick-slip", "dt": 0.01, "t_end": 10, "theta": $th, "events": "none"}}
JSON
    cat >"$T/coulomb_lcs.json" <<JSON
{"model": {"lcs": {"A": [[0, 1], [-1, 0]], "B": [[0], [-1]], "C": [[0, -1]]},
           "laws": [{"law": "interval", "min": -1, "max": 1}]},
 "initial": {"x": [4.5, 0]}, "solver": {"kind": "stick-slip", "dt": 0.01, "t_end": 10, "theta": $th, "events": "none"}}
JSON
    "$BIN" simulate "$T/coulomb.json" --format csv >"$T/c1.csv"
    "$BIN" simulate "$T/coulomb_lcs.json" --format csv >"$T/c2.csv"
    check "the Coulomb oscillator as an LCS equals the stick-slip solver to rounding (theta $th, 1001 rows)" python3 -c "
import csv
a = list(csv.reader(open('$T/c1.csv')))[1:]; b = list(csv.reader(open('$T/c2.csv')))[1:]
assert len(a) == len(b) == 1001
d = max(abs(float(p[i]) - float(q[i])) for p, q in zip(a, b) for i in (0, 1, 2))
assert d < 1e-12, d
# the damper force: Fd (one mass) is u0 (LCS) wherever the mass moves
assert max(abs(float(p[4]) - float(q[3])) for p, q in zip(a, b) if p[6] == 'slip') < 1e-12
"
done

# A source in time: x' = -x + sin t + u, 0 <= u ⊥ x >= 0 (p a harmonic forcing, phase -pi/2). From x(0) = 0:
# x = (sin t - cos t + e^{-t})/2 until it returns to 0 at t1 (in (pi, 2 pi)), then x = 0 with u = -sin t
# until 2 pi, then the same again. The θ-point of each step takes p at t_n + h/2, so u lags by h/2.
cat >"$T/proj.json" <<'JSON'
{"model": {"lcs": {"A": [[-1]], "B": [[1]], "C": [[1]],
                   "p": [{"kind": "harmonic", "amplitude": 1, "omega": 1, "phase": -1.5707963267948966}]},
           "laws": [{"law": "complementarity"}]},
 "initial": {"x": [0]},
 "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 12.566370614359172, "theta": 0.5},
 "output": {"every": 1}}
JSON
"$BIN" simulate "$T/proj.json" --format ndjson >"$T/proj.ndjson"
check "a harmonic source in p: the projected ODE's closed form over two periods" python3 -c "
import json, math
s = [r for r in map(json.loads, open('$T/proj.ndjson')) if r['type'] == 'sample']
f = lambda t: (math.sin(t) - math.cos(t) + math.exp(-t)) / 2
lo, hi = math.pi, 2 * math.pi - 1e-9
for _ in range(200):
    mid = (lo + hi) / 2
    lo, hi = (mid, hi) if f(mid) > 0 else (lo, mid)
t1 = lo
x = lambda t: f(t % (2 * math.pi)) if t % (2 * math.pi) <= t1 else 0.0
assert len(s) == 12568
e = max(abs(r['x'][0] - x(r['t'])) for r in s)
assert e < 5e-7, e  # measured 6.3e-8
blocked = [r for r in s if t1 + 0.01 < r['t'] < 2 * math.pi - 0.01]
assert len(blocked) > 2000 and max(abs(r['u'][0] + math.sin(r['t'] - 0.0005)) for r in blocked) < 1e-6
"

# /v1/wellposedness for LCS models: Cibulka 2014 Theorem 2.3 needs D's symmetric part positive definite.
"$BIN" wellposedness "$T/rlc.json" >"$T/wp_rlc.json"
check "wellposedness, ideal-diode RLC (D = 0): not guaranteed by Theorem 2.3, each θ-step well defined" pyjson "$T/wp_rlc.json" "
d['framework'] == 'LCS' and d['existence']['guaranteed'] is False and d['uniqueness']['theorem'] is None and
[c['holds'] for c in d['checks']] == [True, False, True] and 'mu = lambda_min((D + D^T)/2) = 0,' in d['checks'][1]['detail']"
echo '{"model": {"lcs": {"A": [[-1]], "B": [[1]], "C": [[1]], "D": [[2]]}, "laws": [{"law": "complementarity"}]}}' >"$T/pd.json"
"$BIN" wellposedness "$T/pd.json" >"$T/wp_pd.json"
# D = [2]: mu = 2; with the default θ = 1 the step's matrix is D + h C (1 - hθA)^-1 B = 2 + h/(1 + h)
check "wellposedness, D = [2]: existence and uniqueness by Theorem 2.3, the step's mu = 2 + h/(1 + h)" pyjson "$T/wp_pd.json" "
d['existence']['guaranteed'] and d['uniqueness']['guaranteed'] and 'Theorem 2.3' in d['existence']['theorem'] and
all(c['holds'] for c in d['checks']) and 'mu = lambda_min((D + D^T)/2) = 2 > 0' in d['checks'][1]['detail'] and
'its mu = ' + format(2 + 0.001 / 1.001, '.6g') + ';' in d['checks'][2]['detail']"
"$BIN" wellposedness "$T/bridge.json" >"$T/wp_bridge.json"
check "wellposedness, the bridge: the step's matrix has a zero principal minor (not a P-matrix)" pyjson "$T/wp_bridge.json" "
[c['holds'] for c in d['checks']] == [True, False, False] and 'a principal minor is 0 <= 0' in d['checks'][2]['detail']"

simbad() { # simbad NAME DOC POINTER: dashpot simulate exits 2 naming the pointer
    echo "$2" | "$BIN" simulate - >/dev/null 2>"$T/err"
    local rc=$?
    [ $rc = 2 ] && grep -q -- "-: $3: " "$T/err" || { echo "    exit $rc: $(cat "$T/err")"; return 1; }
}
LCSM='"A": [[0, 1], [-4, -0.5]], "B": [[0], [1]], "C": [[0, 1]]'
check "simulate lcs: B of another size named" simbad B '{"model": {"lcs": {"A": [[0, 1], [-4, -0.5]], "B": [[0, 1]], "C": [[0, 1]]}, "laws": [{"law": "complementarity"}]}}' /model/lcs/B
check "simulate lcs: a law list of the wrong length shows at C" simbad laws "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"complementarity\"}, {\"law\": \"complementarity\"}]}}" /model/lcs/C
check "simulate lcs: an unknown law named" simbad law "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"graf\"}]}}" /model/laws/0/law
check "simulate lcs: a graph law without points named" simbad nopoints "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"graph\"}]}}" /model/laws/0/points
check "simulate lcs: an interval with min > max named" simbad interval "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"interval\", \"min\": 1, \"max\": 0}]}}" /model/laws/0/max
check "simulate lcs: a backward current through an ideal diode is outside the laws" simbad domain "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"complementarity\"}]}, \"initial\": {\"x\": [0, -1]}}" /initial/x
check "simulate lcs: initial x of another length named" simbad x0 "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"complementarity\"}]}, \"initial\": {\"x\": [0]}}" /initial/x
check "simulate lcs: another solver named" simbad kind "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"complementarity\"}]}, \"solver\": {\"kind\": \"analytic\"}}" /solver/kind
# A step without solution: D = -1, q = -1 at x = (0, 0.5)... w = x2 - 1 - u: the initial state already fails.
check "simulate lcs: no u at the initial state (w = x2 - 1 - u < 0 for all u >= 0)" simbad nosol "{\"model\": {\"lcs\": {$LCSM, \"D\": [[-1]], \"q\": [-1]}, \"laws\": [{\"law\": \"complementarity\"}]}, \"initial\": {\"x\": [0, 0.5]}}" /initial/x

# ---- graph laws for LCS components: -w ∈ G(u), the interval's convention (docs/lcs.md) ----
# The ideal diode's cone N_R+ through (0, -1), (0, 0), (1, 0) and the breakdown diode's N_[-0.5, 0] as graphs:
# the same rows as the named laws (u, w and x at every sample).
sed 's|{"law": "complementarity"}|{"law": "graph", "points": [[0, -1], [0, 0], [1, 0]]}|' "$T/rlc.json" >"$T/rlc_graph.json"
sed 's|{"law": "interval", "min": -0.5, "max": 0}|{"law": "graph", "points": [[-0.5, -1], [-0.5, 0], [0, 0], [0, 1]]}|' \
    "$T/breakdown.json" >"$T/breakdown_graph.json"
same_rows() { # same_rows A.json B.json: the CSV rows agree to 1e-12 and there are more than 2
    "$BIN" simulate "$1" --format csv >"$T/a.csv" && "$BIN" simulate "$2" --format csv >"$T/b.csv" || return 1
    python3 -c "
import csv, sys
a = list(csv.reader(open('$T/a.csv'))); b = list(csv.reader(open('$T/b.csv')))
assert a[0] == b[0] and len(a) == len(b) > 3, (len(a), len(b))
d = max(abs(float(p) - float(q)) for r, s in zip(a[1:], b[1:]) for p, q in zip(r, s))
assert d <= 1e-12, d
"
}
check "graph law = complementarity: the ideal-diode RLC's rows to 1e-12" same_rows "$T/rlc.json" "$T/rlc_graph.json"
check "graph law = interval: the breakdown diode's rows to 1e-12" same_rows "$T/breakdown.json" "$T/breakdown_graph.json"
# docs/lcs.md's diode with a forward voltage V_f = 0.2 and on-resistance r = 0.4 in the ideal diode's RLC:
# -i ∈ G(-v_D), G through (-1, -2), (-0.2, 0), (1, 0) (slope 1/r, then blocked). While it conducts,
# y = q + C V_f obeys y'' + ((R + r)/L) y' + y/(LC) = 0, y(0) = C V_f, y'(0) = 1, until i = y' = 0 at t*;
# then blocked for good with u = -v_D = q*/C. O(h) while u != 0 (measured 1.2e-4, q* 4.5e-5).
cat >"$T/diode.json" <<'JSON'
{"model": {"lcs": {"A": [[0, 1], [-4, -0.5]], "B": [[0], [1]], "C": [[0, 1]], "D": [[0]]},
           "laws": [{"law": "graph", "points": [[-1, -2], [-0.2, 0], [1, 0]]}]},
 "initial": {"x": [0, 1]},
 "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 3, "theta": 0.5}}
JSON
"$BIN" simulate "$T/diode.json" --format ndjson >"$T/diode.ndjson"
cat >"$T/diode_check.py" <<'PY'
import json, math, sys
s = [r for r in map(json.loads, open(sys.argv[1])) if r['type'] == 'sample']
R, L, C, Vf, r = 0.5, 1.0, 0.25, 0.2, 0.4
a = (R + r) / (2 * L); wd = math.sqrt(1 / (L * C) - a * a); y0 = C * Vf; B = (1 + a * y0) / wd
y = lambda t: math.exp(-a * t) * (y0 * math.cos(wd * t) + B * math.sin(wd * t))
yp = lambda t: math.exp(-a * t) * ((B * wd - a * y0) * math.cos(wd * t) - (y0 * wd + a * B) * math.sin(wd * t))
ts = math.atan2(B * wd - a * y0, y0 * wd + a * B) / wd; qs = y(ts) - y0
before = [x for x in s if x['t'] < ts - 0.002]; after = [x for x in s if x['t'] > ts + 0.002]
assert len(s) == 3001 and len(before) > 600 and len(after) > 2300
e1 = max(max(abs(x['x'][0] - (y(x['t']) - y0)), abs(x['x'][1] - yp(x['t']))) for x in before)
assert e1 < 5e-4, e1
assert max(abs(x['u'][0] + Vf + r * x['x'][1]) for x in before) < 1e-12  # on the conducting piece
assert all(x['x'][1] == 0 and abs(x['x'][0] - qs) < 2e-4 and abs(x['u'][0] - qs / C) < 1e-3 for x in after)
PY
check "a graph law: the diode with forward voltage and on-resistance, the RLC's closed form, then blocked" \
    python3 "$T/diode_check.py" "$T/diode.ndjson"
# The Jenkins element x = (s, e), s' = u, e' = cos t, -w = 2 (e - s) ∈ 0.5 Sgn(u): "coulomb" is the graph
# through (-1, -0.5), (0, -0.5), (0, 0.5), (1, 0.5); a rope (k = 2, length 0.2) is the graph through
# (0, 0), (0.2, 0.4), (0.2, 1.4). The driven force stays within [-0.5, 0.5] (checked on the rows).
jenkins() { # jenkins LAW: the Jenkins element's document with that law
    echo "{\"model\": {\"lcs\": {\"A\": [[0, 0], [0, 0]], \"B\": [[1], [0]], \"C\": [[2, -2]],
      \"p\": [0, {\"kind\": \"harmonic\", \"amplitude\": 1, \"omega\": 1}]}, \"laws\": [$1]},
      \"initial\": {\"x\": [0, 0]}, \"solver\": {\"kind\": \"stick-slip\", \"dt\": 0.01, \"t_end\": 10, \"theta\": 0.5},
      \"output\": {\"every\": 10}}"
}
jenkins '{"law": "coulomb", "phi0": 0.5}' >"$T/jc.json"
jenkins '{"law": "graph", "points": [[-1, -0.5], [0, -0.5], [0, 0.5], [1, 0.5]]}' >"$T/jg.json"
jenkins '{"law": "rope", "k": 2, "length": 0.2}' >"$T/jr.json"
jenkins '{"law": "graph", "points": [[0, 0], [0.2, 0.4], [0.2, 1.4]]}' >"$T/jrg.json"
check "graph law = coulomb (the damper's builder): the Jenkins element's rows to 1e-12" same_rows "$T/jc.json" "$T/jg.json"
check "coulomb: the force -w stays in [-0.5, 0.5] and reaches both ends (slips both ways)" python3 -c "
import csv
r = list(csv.DictReader(open('$T/a.csv'))); F = [-float(x['w0']) for x in r]
assert max(abs(f) for f in F) <= 0.5 + 1e-12 and max(F) > 0.5 - 1e-12 and min(F) < -0.5 + 1e-12, (min(F), max(F))"
check "graph law = rope (the spring's builder): the Jenkins element's rows to 1e-12" same_rows "$T/jr.json" "$T/jrg.json"
"$BIN" simulate "$T/jg.json" --format ndjson | head -1 >"$T/jg_meta.json"
check "the meta line names a graph law with its points and the LCP rows it adds (coulomb: 2)" pyjson "$T/jg_meta.json" "
d['laws'] == [{'law': 'graph', 'points': [[-1, -0.5], [0, -0.5], [0, 0.5], [1, 0.5]], 'lcp_rows': 2}]"
"$BIN" simulate "$T/jr.json" --format ndjson | head -1 >"$T/jr_meta.json"
check "the meta line names a rope law with its parameters (1 row: the slack ray)" pyjson "$T/jr_meta.json" "
d['laws'] == [{'law': 'rope', 'k': 2, 'length': 0.2, 'lcp_rows': 1}]"
check "simulate lcs: a non-monotone graph point named" simbad nonmono "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"graph\", \"points\": [[0, -1], [0, 0], [1, -0.5]]}]}}" /model/laws/0/points/2
check "simulate lcs: a negative Coulomb threshold named" simbad phi "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"coulomb\", \"phi0\": -1}]}}" /model/laws/0/phi0
check "simulate lcs: a rope without length named" simbad rope "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"rope\", \"k\": 1}]}}" /model/laws/0/length
ZIG=$(python3 -c "print(','.join('[%d, %g]' % (i, (i * i if i % 2 else i * i + 0.5))  for i in range(300)))")
check "simulate lcs: a graph whose step LCP exceeds 500 rows named at the law list" simbad rows "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"graph\", \"points\": [$ZIG]}]}}" /model/laws

check "simulate lcs: h W B beyond the doubles named at B" simbad hwb '{"model": {"lcs": {"A": [[0]], "B": [[1e308]], "C": [[1]]}, "laws": [{"law": "complementarity"}]}, "initial": {"x": [1]}, "solver": {"kind": "stick-slip", "dt": 10, "t_end": 100, "theta": 0.5}}' /model/lcs/B
check "simulate lcs: h θ A beyond the doubles named at A" simbad hta '{"model": {"lcs": {"A": [[1e308]], "B": [[1]], "C": [[1]]}, "laws": [{"law": "complementarity"}]}, "initial": {"x": [1]}, "solver": {"kind": "stick-slip", "dt": 10, "t_end": 100, "theta": 0.5}}' /model/lcs/A
check "simulate lcs: D + h C W B beyond the doubles named at C" simbad cwb '{"model": {"lcs": {"A": [[0]], "B": [[1e300]], "C": [[1e308]]}, "laws": [{"law": "complementarity"}]}, "initial": {"x": [1]}, "solver": {"kind": "stick-slip", "dt": 1, "t_end": 10, "theta": 0.5}}' /model/lcs/C

start_daemon lcp || finish
U=$URL_lcp
post() { # post PATH FILE -> status and content type in $T/ct, body in $T/body
    hcurl -X POST --data-binary @"$2" -o "$T/body" -w '%{http_code} %{content_type}' "$U$1" >"$T/ct"
}
post /v1/lcp "$T/three.json"
check "POST /v1/lcp: 200 application/json, the CLI's answer byte for byte" \
    bash -c "[ \"\$(cat '$T/ct')\" = '200 application/json' ] && cmp -s '$T/body' '$T/three.out'"
echo '{"M": [[1, 2], [3, 4]], "q": [1]}' >"$T/badq.json"
post /v1/lcp "$T/badq.json"
check "POST /v1/lcp, q too short: 422 problem at /q" pyjson "$T/body" "
d['status'] == 422 and [e['pointer'] for e in d['errors']] == ['/q']"
printf '{"M": ' >"$T/trunc.json"
post /v1/lcp "$T/trunc.json"
check "POST /v1/lcp, malformed JSON: 400" [ "$(cut -d' ' -f1 "$T/ct")" = 400 ]
printf '{"M": [[1]],\n "q": [NaN]}' >"$T/nan.json"
post /v1/lcp "$T/nan.json"
check "POST /v1/lcp, NaN: 400 at line 2, column 8, the words of every route" pyjson "$T/body" "
d['status'] == 400 and d['type'] == '/problems/malformed-json' and [(e['pointer'], e['detail']) for e in d['errors']] == [
('', 'malformed JSON near byte 20 (line 2, column 8): JSON has no NaN or Infinity; send a number or null')]"
printf '{"M": [[1]], "q": [1], "M": [[2]]}' >"$T/dup.json"
post /v1/lcp "$T/dup.json"
check "POST /v1/lcp, a repeated key: 422 problem at /M" pyjson "$T/body" "
d['status'] == 422 and [(e['pointer'], e['detail']) for e in d['errors']] == [('/M', 'duplicate key \"M\"')]"
post /v1/lcp "$T/murty13.json"
check "POST /v1/lcp, Murty's matrix m = 13: 422 over-limit at /M" pyjson "$T/body" "
d['status'] == 422 and d['type'] == '/problems/over-limit' and [e['pointer'] for e in d['errors']] == ['/M']"
post /v1/lcp "$T/murty12.json"
check "POST /v1/lcp, Murty's matrix m = 12: the CLI's answer byte for byte" cmp -s "$T/body" "$T/murty12.out"
post /v1/simulate "$T/lcsmurty.json"
check "POST /v1/simulate, an LCS whose algebraic part takes Lemke's limit: 422 over-limit at /solver" pyjson "$T/body" "
d['status'] == 422 and d['type'] == '/problems/over-limit' and [e['pointer'] for e in d['errors']] == ['/solver']"
check "/metrics counts /v1/lcp" bash -c "curl -s '$U/metrics' | grep -q 'route=\"/v1/lcp\"'"
hcurl -X POST --data-binary @"$T/pd.json" -o "$T/body" "$U/v1/wellposedness"
check "POST /v1/wellposedness with an LCS model: the CLI's answer" python3 -c "
import json; assert json.load(open('$T/body')) == json.load(open('$T/wp_pd.json'))"
hcurl -X POST -H 'Accept: application/x-ndjson' --data-binary @"$T/rlc.json" -o "$T/body" "$U/v1/simulate"
check "POST /v1/simulate with an LCS model: the CLI's NDJSON byte for byte" cmp -s "$T/body" "$T/rlc.ndjson"
echo "{\"model\": {\"lcs\": {$LCSM}, \"laws\": [{\"law\": \"graph\", \"points\": [[0, -1], [0, 0], [1, -0.5]]}]}}" >"$T/nonmono.json"
post /v1/simulate "$T/nonmono.json"
check "POST /v1/simulate, a non-monotone graph law: 422 problem+json at /model/laws/0/points/2" pyjson "$T/body" "
d['status'] == 422 and [e['pointer'] for e in d['errors']] == ['/model/laws/0/points/2'] and
'non-decreasing' in d['errors'][0]['detail']" && grep -q '^422 application/problem+json' "$T/ct"
hcurl -X POST -H 'Accept: application/x-ndjson' --data-binary @"$T/jg.json" -o "$T/body" "$U/v1/simulate"
check "POST /v1/simulate with a graph law: the CLI's NDJSON byte for byte" bash -c "'$BIN' simulate '$T/jg.json' --format ndjson | cmp -s - '$T/body'"
stop_daemon lcp
check "SIGTERM: exit 0" [ "$RC_lcp" = 0 ]
finish
