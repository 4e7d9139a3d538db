#!/usr/bin/env bash
# tests/test_modes.sh - `dashpot modes|response` and POST /v1/modes, /v1/response end to end:
# Höschl's double pendulum (Höschl 1983 Ex. 28-29) and a chain of elements against closed forms computed here
# in Python (stdlib only), a free decay by the stick-slip network solver against the modal superposition,
# Rayleigh damping ratios, left-out set-valued elements, the three formats of the
# response curve by --format and by Accept, and bad input (422 with JSON Pointers, CLI exit 2).
# Env BUILD (default build). Prints "N passed, M failed"; exit 1 on any failure.
source "$(dirname "$0")/lib/daemon.bash"

BIN=$BUILD/dashpot
T=$SCRATCH

# pyjson FILE EXPR: EXPR holds for d = the JSON in FILE (math imported).
pyjson() {
    python3 -c 'import json,math,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if eval("(" + sys.argv[2] + ")") else 1)' "$1" "$2" ||
        { echo "    $2 fails for: $(head -c 600 "$1")"; return 1; }
}

# The double pendulum of Ex. 28 with m = 2, l = 0.5, g = 9.81: M = m l^2 [2 1; 1 1], K = m g l diag(2, 1).
cat >"$T/pendulum.json" <<'JSON'
{"model": {"mass_matrix": [[1, 0.5], [0.5, 0.5]], "stiffness_matrix": [[19.62, 0], [0, 9.81]]},
 "force_node": 0, "response_node": 0, "omega": {"from": 1, "to": 9, "points": 81}}
JSON

"$BIN" modes "$T/pendulum.json" >"$T/modes.json"
check "modes: exit 0" [ $? = 0 ]
# Omega = sqrt((2 -+ sqrt 2) g / l); shapes (0.38268, 0.54120), (0.92388, -1.30656) over l sqrt(m)
check "modes: Höschl's Ex. 28 frequencies and shapes" pyjson "$T/modes.json" "
len(d['modes']) == 2 and d['method'] == 'dense' and d['left_out'] == [] and
abs(d['modes'][0]['omega'] - math.sqrt((2 - math.sqrt(2)) * 19.62)) < 1e-12 and
abs(d['modes'][1]['omega'] - math.sqrt((2 + math.sqrt(2)) * 19.62)) < 1e-11 and
abs(d['modes'][0]['frequency'] - d['modes'][0]['omega'] / (2 * math.pi)) < 1e-15 and
abs(d['modes'][1]['period'] * d['modes'][1]['omega'] - 2 * math.pi) < 1e-12 and
all(abs(a * 0.5 * math.sqrt(2) - b) < 1e-5 for a, b in zip(d['modes'][0]['shape'] + d['modes'][1]['shape'],
    [0.38268, 0.54120, 0.92388, -1.30656])) and
abs(sum(m['effective_mass'] for m in d['modes']) - d['total_mass']) < 1e-12 and d['total_mass'] == 2.5 and
'damped' not in d and d['modes'][0]['damping_ratio'] is None"

# Ex. 29: H_00 = (1 - p) / (m g l (p - p1)(p - p2)), p = omega^2 l / g; antiresonance at p = 1.
"$BIN" response "$T/pendulum.json" >"$T/resp.json"
check "response: exit 0" [ $? = 0 ]
check "response: Ex. 29's dynamic compliance at 81 points, resonances, antiresonance at sqrt(g/l)" pyjson "$T/resp.json" "
len(d['rows']) == 81 and d['method'] == 'modal' and
all(r['magnitude'] is not None and abs(r['magnitude'] - abs(h)) <= 1e-9 * abs(h) and
    abs(r['phase'] - (0 if h >= 0 else math.pi)) < 1e-12
    for r in d['rows'] for p in [r['omega'] ** 2 * 0.5 / 9.81]
    for h in [(1 - p) / (9.81 * (p - 2 + math.sqrt(2)) * (p - 2 - math.sqrt(2)))]) and
[round(x['omega'], 9) for x in d['resonances']] == [round(math.sqrt((2 - math.sqrt(2)) * 19.62), 9),
                                                    round(math.sqrt((2 + math.sqrt(2)) * 19.62), 9)] and
len(d['antiresonances']) == 1 and abs(d['antiresonances'][0]['omega'] - math.sqrt(19.62)) < 1e-9"

"$BIN" response "$T/pendulum.json" --format csv >"$T/resp.csv"
check "response --format csv: header and 81 rows equal to the JSON" python3 -c "
import csv, json
rows = list(csv.reader(open('$T/resp.csv')))
d = json.load(open('$T/resp.json'))['rows']
assert rows[0] == ['omega', 'magnitude', 'phase'] and len(rows) == 82
assert all(float(a[0]) == b['omega'] and float(a[1]) == b['magnitude'] and float(a[2]) == b['phase']
           for a, b in zip(rows[1:], d))
"
"$BIN" response "$T/pendulum.json" --format ndjson >"$T/resp.ndjson"
check "response --format ndjson: a meta line, then 81 points" python3 -c "
import json
rows = [json.loads(l) for l in open('$T/resp.ndjson')]
assert rows[0]['type'] == 'meta' and 'resonances' in rows[0] and len(rows) == 82
assert all(r['type'] == 'point' for r in rows[1:])
"

# A chain of three equal masses and springs fixed at one end, with a Coulomb damper (left out) and
# Rayleigh damping: omega^2 = 2 k/m (1 - cos((2j-1) pi / 7)), zeta_j = alpha / (2 w) + beta w / 2.
cat >"$T/chain.json" <<'JSON'
{"model": {"masses": [1, 1, 1],
           "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 4}},
                        {"between": [0, 1], "spring": {"law": "linear", "k": 4}},
                        {"between": [1, 2], "spring": {"law": "linear", "k": 4},
                         "damper": {"law": "coulomb", "phi0": 0.3}}]},
 "damping": {"rayleigh": {"alpha": 0.05, "beta": 0.01}}}
JSON
"$BIN" modes "$T/chain.json" >"$T/chain_modes.json"
check "modes of a chain: tridiagonal route, closed-form frequencies, Rayleigh ratios, element 2 left out" pyjson "$T/chain_modes.json" "
d['method'] == 'tridiagonal' and d['left_out'] == [2] and d['proportional_damping'] is True and
all(abs(m['omega'] - w) < 1e-12 * w and abs(m['damping_ratio'] - (0.05 / (2 * w) + 0.01 * w / 2)) < 1e-12 and
    abs(z['damping_ratio'] - m['damping_ratio']) < 1e-10 and abs(z['omega_n'] - w) < 1e-10 * w
    for j, m, z in zip(range(1, 4), d['modes'], d['damped'])
    for w in [math.sqrt(8 * (1 - math.cos((2 * j - 1) * math.pi / 7)))]) and
all(m['shape'][0] > 0 for m in d['modes'])"

# A free decay by the stick-slip network solver (theta = 1/2, dt = 1e-3) against the modal superposition of
# these modes: undamped x(t) = sum_k phi_k (phi_k^T M x0) cos(w_k t); with dampers c = 0.05 k on every
# spring (C = 0.05 K, proportional) each term decays as e^(-z w t)(cos w_d t + z w / w_d sin w_d t). The
# trapezoidal rule's phase error is ~ w^3 dt^2 t / 12 < 1e-5 here; 1e-4 catches a wrong sign or factor.
decay_spec() { # decay_spec C_FACTOR
    cat <<JSON
{"model": {"masses": [1, 2],
           "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 3}, "damper": {"law": "linear", "c": $(python3 -c "print(3 * $1)")}},
                        {"between": [0, 1], "spring": {"law": "linear", "k": 1}, "damper": {"law": "linear", "c": $1}}]},
 "initial": {"x": [1, -0.5], "v": [0, 0]},
 "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 10, "theta": 0.5},
 "output": {"every": 250}}
JSON
}
free_decay() { # free_decay C_FACTOR
    decay_spec "$1" >"$T/decay$1.json"
    "$BIN" simulate "$T/decay$1.json" --format ndjson >"$T/decay$1.ndjson" && "$BIN" modes "$T/decay$1.json" >"$T/decay$1.modes" &&
    python3 - "$T/decay$1.ndjson" "$T/decay$1.modes" <<'PY'
import json, math, sys
rows = [r for r in map(json.loads, open(sys.argv[1])) if r["type"] == "sample"]
modes = json.load(open(sys.argv[2]))["modes"]
M, x0 = [1, 2], [1, -0.5]
worst = 0
for r in rows:
    t, x = r["t"], [0.0, 0.0]
    for m in modes:
        w, z, phi = m["omega"], m["damping_ratio"] or 0, m["shape"]
        q0 = sum(phi[i] * M[i] * x0[i] for i in range(2))
        wd = w * math.sqrt(1 - z * z)
        g = math.exp(-z * w * t) * (math.cos(wd * t) + z * w / wd * math.sin(wd * t))
        for i in range(2):
            x[i] += phi[i] * q0 * g
    worst = max(worst, max(abs(a - b) for a, b in zip(x, r["x"])))
assert len(rows) == 41, len(rows)
assert worst < 1e-4, worst
print("    largest difference", worst)
PY
}
check "free decay of a linear network (stick-slip solver) = the modal superposition, undamped" free_decay 0
check "free decay with proportional element dampers = the damped modal superposition" free_decay 0.05

# ---- bad input on the CLI: exit 2, pointer on stderr ----
bad() { # bad NAME JSON POINTER [modes|response]
    printf '%s' "$2" >"$T/$1.json"
    "$BIN" "${4:-modes}" "$T/$1.json" >/dev/null 2>"$T/$1.err"
    local rc=$?
    [ $rc = 2 ] && grep -qF ": $3: " "$T/$1.err" || { echo "    exit $rc, stderr: $(cat "$T/$1.err")"; return 1; }
}
check "non-symmetric stiffness: exit 2 at /model/stiffness_matrix" bad nonsym \
    '{"model": {"masses": [1, 1], "stiffness_matrix": [[2, -1], [-0.5, 2]]}}' /model/stiffness_matrix
check "indefinite stiffness: exit 2 at /model/stiffness_matrix" bad indef \
    '{"model": {"masses": [1, 1], "stiffness_matrix": [[1, 2], [2, 1]]}}' /model/stiffness_matrix
check "singular mass matrix: exit 2 at /model/mass_matrix" bad sing \
    '{"model": {"mass_matrix": [[1, 1], [1, 1]]}}' /model/mass_matrix
check "a 2x3 matrix: exit 2 at /model/stiffness_matrix/1" bad size \
    '{"model": {"masses": [1, 1], "stiffness_matrix": [[1, 0], [0, 1, 2]]}}' /model/stiffness_matrix/1
check "a stiffness matrix of the wrong order: exit 2" bad order \
    '{"model": {"masses": [1, 1], "stiffness_matrix": [[1]]}}' /model/stiffness_matrix
check "an element to a missing node: exit 2 at /model/elements/0/between/1" bad node \
    '{"model": {"masses": [1], "elements": [{"between": ["ground", 3], "spring": {"law": "linear", "k": 1}}]}}' \
    /model/elements/0/between/1
check "reversed range: exit 2 at /omega/to" bad reversed \
    '{"model": {"masses": [1]}, "force_node": 0, "response_node": 0, "omega": {"from": 2, "to": 1, "points": 5}}' \
    /omega/to response
check "empty range: exit 2 at /omega/to" bad empty \
    '{"model": {"masses": [1]}, "force_node": 0, "response_node": 0, "omega": {"from": 1, "to": 1, "points": 5}}' \
    /omega/to response
check "no points: exit 2 at /omega/points" bad nopoints \
    '{"model": {"masses": [1]}, "force_node": 0, "response_node": 0, "omega": {"from": 0, "to": 1, "points": 0}}' \
    /omega/points response
check "force node out of range: exit 2 at /force_node" bad force \
    '{"model": {"masses": [1]}, "force_node": 1, "response_node": 0, "omega": {"from": 0, "to": 1, "points": 5}}' \
    /force_node response
check "negative Rayleigh alpha: exit 2 at /damping/rayleigh/alpha" bad alpha \
    '{"model": {"masses": [1]}, "damping": {"rayleigh": {"alpha": -1}}}' /damping/rayleigh/alpha
same_as_simulate() { # same_as_simulate NAME JSON: modes and response refuse it with exactly simulate's errors
    printf '%s' "$2" >"$T/$1.json"
    "$BIN" simulate "$T/$1.json" >/dev/null 2>"$T/$1.sim"
    "$BIN" modes "$T/$1.json" >/dev/null 2>"$T/$1.modes"
    local rc=$?
    [ $rc = 2 ] && [ -s "$T/$1.sim" ] && cmp -s "$T/$1.sim" "$T/$1.modes" ||
        { echo "    exit $rc; simulate: $(cat "$T/$1.sim"); modes: $(cat "$T/$1.modes")"; return 1; }
}
check "a network's elements are read by simulate's parser: a misspelt law and a non-monotone graph in its words" \
    same_as_simulate laws '{"model": {"masses": [1, 1], "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 1}},
     {"between": [0, 1], "damper": {"law": "colomb", "phi0": 1}},
     {"between": [1, "ground"], "spring": {"law": "graph", "points": [[0, 1], [1, 0]]}}]}}'
check "...a Coulomb damper without phi0, a load on a missing node" same_as_simulate phi0 \
    '{"model": {"masses": [1], "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 1},
     "damper": {"law": "coulomb"}}], "forcing": [{"node": 3, "kind": "constant", "value": 1}]}}'
printf '%s' '{"model": {"masses": [1, 0.5], "elements": [{"between": ["ground", 0], "contact": {"distance": 0}},
  {"between": [0, 1], "spring": {"law": "linear", "k": 50}, "contact": {"distance": 0.1}}]}}' >"$T/contact.json"
"$BIN" modes "$T/contact.json" >"$T/contact.out"
check "a contact is left out, the linear spring beside it is not: omega^2 = k (1/m0 + 1/m1) = 150" pyjson \
    "$T/contact.out" "d['left_out'] == [0, 1] and d['modes'][0]['rigid'] and abs(d['modes'][1]['omega'] ** 2 - 150) < 1e-9"
check "an unknown member is named at its own pointer" bad unknown '{"model": {"masses": [1]}, "dampnig": {}}' /dampnig
check "a repeated key in an element's spring: exit 2 at its pointer" bad dupk \
    '{"model": {"masses": [1], "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 1, "k": 2}}]}}' \
    /model/elements/0/spring/k
check "a repeated key in a member modes ignores (solver): still refused" bad dupsolver \
    '{"model": {"masses": [1]}, "solver": {"dt": 1, "dt": 2}}' /solver/dt
check "response: a repeated omega: exit 2 at /omega" bad dupomega \
    '{"model": {"masses": [1]}, "force_node": 0, "response_node": 0, "omega": {"from": 0, "to": 1, "points": 5}, "omega": {}}' \
    /omega response

# ---- scale: no spin, finite through, honest rigid modes ----
# The review's hostile requests: their first-order matrices held infinities and GSL's balancing spun for ever.
# Each is refused at the member to blame, and `timeout` turns a hang into a failure.
scale_bad() { # scale_bad NAME JSON POINTER: modes and response both exit 2 at POINTER, saying the scale overflows
    printf '%s' "$2" >"$T/$1.json"
    local cmd rc
    for cmd in modes response; do
        timeout 60 "$BIN" $cmd "$T/$1.json" >/dev/null 2>"$T/$1.$cmd.err"
        rc=$?
        [ $rc = 2 ] && grep -qF ": $3: " "$T/$1.$cmd.err" && grep -q "overflows" "$T/$1.$cmd.err" ||
            { echo "    $cmd: exit $rc, stderr: $(cat "$T/$1.$cmd.err")"; return 1; }
    done
}
RESP='"force_node": 0, "response_node": 2, "omega": {"from": 0.1, "to": 10, "points": 50}'
check "the docs' chain with a spring of 1e308 and Rayleigh damping: exit 2 at that spring's k, no hang" scale_bad k308 \
    '{"model": {"masses": [1, 1, 1], "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 4}},
     {"between": [0, 1], "spring": {"law": "linear", "k": 1e308}}, {"between": [1, 2], "spring": {"law": "linear", "k": 4}}]},
     "damping": {"rayleigh": {"alpha": 0.05, "beta": 0.01}}, '"$RESP"'}' /model/elements/1/spring/k
check "masses 1e-10 and 1 on k = 1e300 with a damper: exit 2 at the spring's k" scale_bad k300 \
    '{"model": {"masses": [1e-10, 1, 1], "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 1}},
     {"between": [0, 1], "spring": {"law": "linear", "k": 1e300}, "damper": {"law": "linear", "c": 1}},
     {"between": [1, 2], "spring": {"law": "linear", "k": 1}}]}, '"$RESP"'}' /model/elements/1/spring/k
check "a mass of 5e-324 with damping: exit 2 at /model/masses/0" scale_bad m324 \
    '{"model": {"masses": [5e-324, 1, 1], "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 4}},
     {"between": [0, 1], "spring": {"law": "linear", "k": 4}}, {"between": [1, 2], "spring": {"law": "linear", "k": 4},
     "damper": {"law": "linear", "c": 0.3}}]}, '"$RESP"'}' /model/masses/0
check "two springs of 1e308 on one node sum past DBL_MAX: exit 2 at the stiffer one" scale_bad ksum \
    '{"model": {"masses": [1, 1, 1], "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 1e308}},
     {"between": [0, 1], "spring": {"law": "linear", "k": 1.5e308}}, {"between": [1, 2], "spring": {"law": "linear", "k": 4}}]},
     '"$RESP"'}' /model/elements/1/spring/k
check "Rayleigh beta K past DBL_MAX: exit 2 at /damping/rayleigh/beta" scale_bad beta \
    '{"model": {"masses": [1, 1, 1], "stiffness_matrix": [[1e300, 0, 0], [0, 1, 0], [0, 0, 1]]},
     "damping": {"rayleigh": {"beta": 1e12}}, '"$RESP"'}' /damping/rayleigh/beta

# Two uncoupled masses on k = 1e12 and k = 1: the soft one keeps omega = 1 (the old rigid test, relative to
# K's largest entry, gave it omega = 0), and its receptance is 1 / (1 - omega^2 + i 0.01 omega).
printf '%s' '{"model": {"masses": [1, 1], "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 1e12}},
  {"between": ["ground", 1], "spring": {"law": "linear", "k": 1}}]}, "damping": {"rayleigh": {"alpha": 0.01}},
  "force_node": 1, "response_node": 1, "omega": {"from": 0.5, "to": 2, "points": 31}}' >"$T/pair.json"
"$BIN" modes "$T/pair.json" >"$T/pair.modes"
check "stiff/soft pair: omega 1 and 1e6 to 1e-9, neither rigid" pyjson "$T/pair.modes" "
[m['rigid'] for m in d['modes']] == [False, False] and abs(d['modes'][0]['omega'] - 1) < 1e-9 and
abs(d['modes'][1]['omega'] / 1e6 - 1) < 1e-9"
"$BIN" response "$T/pair.json" >"$T/pair.resp"
check "stiff/soft pair: the receptance is the closed form at 31 frequencies, magnitude and phase" pyjson "$T/pair.resp" "
len(d['rows']) == 31 and all(abs(r['magnitude'] - abs(h)) <= 1e-9 * abs(h) and abs(r['phase'] - math.atan2(h.imag, h.real)) < 1e-9
    for r in d['rows'] for h in [1 / complex(1 - r['omega'] ** 2, 0.01 * r['omega'])]) and
[round(x['omega'], 9) for x in d['resonances']] == [1.0]"

# Hostile magnitudes in every numeric member of a document that has them all: each answer is 200 with finite
# numbers or 422 with a pointer, never a hang, a crash or a NaN.
cat >"$T/every.json" <<'JSON'
{"model": {"masses": [1, 2, 1],
           "stiffness_matrix": [[1, 0, 0], [0, 2, -1], [0, -1, 2]], "damping_matrix": [[0.1, 0, 0], [0, 0, 0], [0, 0, 0.2]],
           "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 4}},
                        {"between": [0, 1], "spring": {"law": "linear", "k": 4}, "damper": {"law": "linear", "c": 0.3}},
                        {"between": [1, 2], "spring": {"law": "linear", "k": 4}, "damper": {"law": "bingham", "c": 0.2, "tau": 1}}]},
 "damping": {"rayleigh": {"alpha": 0.05, "beta": 0.01}},
 "force_node": 0, "response_node": 2, "omega": {"from": 0.1, "to": 10, "points": 40, "spacing": "log"}}
JSON
hostile_sweep() { # every numeric leaf of every.json (and of its mass_matrix form) at 1e308, 5e-324, -1e308
    python3 - "$BIN" "$T" <<'PY'
import json, math, subprocess, sys
bin_, tmp = sys.argv[1], sys.argv[2]
base = json.load(open(tmp + "/every.json"))
dense = json.loads(json.dumps(base))
dense["model"].pop("masses")
dense["model"]["mass_matrix"] = [[1, 0.1, 0], [0.1, 2, 0], [0, 0, 1]]
def leaves(d, path=()):
    if isinstance(d, dict):
        for k, v in d.items():
            yield from leaves(v, path + (k,))
    elif isinstance(d, list):
        for i, v in enumerate(d):
            yield from leaves(v, path + (i,))
    elif isinstance(d, (int, float)) and not isinstance(d, bool) and path[-1] not in ("between", "force_node", "response_node", "points"):
        yield path
def finite(x):
    if isinstance(x, dict): return all(finite(v) for v in x.values())
    if isinstance(x, list): return all(finite(v) for v in x)
    return not isinstance(x, float) or math.isfinite(x)
bad, runs = [], 0
for doc in (base, dense):
    for path in list(leaves(doc)):
        for value in ("1e308", "5e-324", "-1e308"):
            d = json.loads(json.dumps(doc))
            node = d
            for p in path[:-1]: node = node[p]
            node[path[-1]] = "@@"
            text = json.dumps(d).replace('"@@"', value)
            open(tmp + "/hostile.json", "w").write(text)
            for cmd in ("modes", "response"):
                runs += 1
                try:
                    p = subprocess.run([bin_, cmd, tmp + "/hostile.json"], capture_output=True, text=True, timeout=60)
                except subprocess.TimeoutExpired:
                    bad.append((cmd, path, value, "hang")); continue
                if p.returncode == 0:
                    if not finite(json.loads(p.stdout, parse_constant=lambda c: float("nan"))):
                        bad.append((cmd, path, value, "non-finite output"))
                elif p.returncode != 2 or ": /" not in p.stderr:
                    bad.append((cmd, path, value, "exit %d: %s" % (p.returncode, p.stderr[:300])))
for b in bad[:10]:
    print("    %s %s = %s: %s" % b)
print("    %d runs, %d bad" % (runs, len(bad)))
sys.exit(1 if bad else 0)
PY
}
check "1e308, 5e-324 and -1e308 in every member of modes and response: 200 finite or 422 located, no hang" hostile_sweep

# ---- the daemon ----
start_daemon modes || finish
U=$URL_modes
post() { # post PATH ACCEPT FILE -> status, content type in $T/ct, body in $T/body
    hcurl -X POST -H "Accept: $2" --data-binary @"$3" -o "$T/body" -w '%{http_code} %{content_type}' "$U$1" >"$T/ct"
}
post /v1/modes application/json "$T/pendulum.json"
check "POST /v1/modes: 200 application/json" [ "$(cat "$T/ct")" = "200 application/json" ]
check "POST /v1/modes: the CLI's answer, byte for byte" cmp -s "$T/body" "$T/modes.json"
post /v1/response text/csv "$T/pendulum.json"
check "POST /v1/response as text/csv: the CLI's CSV" cmp -s "$T/body" "$T/resp.csv"
check "POST /v1/response as text/csv: 200 text/csv" [ "$(cat "$T/ct")" = "200 text/csv; charset=utf-8" ]
post /v1/response application/x-ndjson "$T/pendulum.json"
check "POST /v1/response as NDJSON: the CLI's NDJSON" cmp -s "$T/body" "$T/resp.ndjson"
post /v1/response application/json "$T/pendulum.json"
check "POST /v1/response as JSON: the CLI's JSON" cmp -s "$T/body" "$T/resp.json"
post /v1/response image/png "$T/pendulum.json"
check "POST /v1/response as image/png: 406" [ "$(cut -d' ' -f1 "$T/ct")" = 406 ]
post /v1/modes application/json "$T/indef.json"
check "POST /v1/modes, indefinite K: 422 problem naming /model/stiffness_matrix" pyjson "$T/body" "
d['status'] == 422 and [e['pointer'] for e in d['errors']] == ['/model/stiffness_matrix']"
post /v1/response application/json "$T/reversed.json"
check "POST /v1/response, reversed range: 422 at /omega/to" pyjson "$T/body" "
d['status'] == 422 and [e['pointer'] for e in d['errors']] == ['/omega/to']"
post /v1/modes application/json "$T/k308.json"
check "POST /v1/modes, a spring of 1e308: 422 at /model/elements/1/spring/k, promptly" pyjson "$T/body" "
d['status'] == 422 and [e['pointer'] for e in d['errors']] == ['/model/elements/1/spring/k']"
post /v1/response application/json "$T/m324.json"
check "POST /v1/response, a mass of 5e-324: 422 at /model/masses/0" pyjson "$T/body" "
d['status'] == 422 and [e['pointer'] for e in d['errors']] == ['/model/masses/0']"
printf '{"model": ' >"$T/trunc.json"
post /v1/modes application/json "$T/trunc.json"
check "POST /v1/modes, malformed JSON: 400" [ "$(cut -d' ' -f1 "$T/ct")" = 400 ]
printf '{"model": {"masses": [1],\n  "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 1},}]}}' \
    >"$T/comma.json"
post /v1/response application/json "$T/comma.json"
check "POST /v1/response, a trailing comma: 400 at line 2, column 78, the words of every route" pyjson "$T/body" "
d['status'] == 400 and [(e['pointer'], e['detail']) for e in d['errors']] == [
('', 'malformed JSON near byte 103 (line 2, column 78): a trailing comma before }; remove it')]"
printf '{"model": {"masses": [1], "elements": [{"between": ["ground", 0], "damper": {"law": "linear", "c": 1}, "damper": {}}]}}' \
    >"$T/dupel.json"
post /v1/modes application/json "$T/dupel.json"
check "POST /v1/modes, a repeated key in a network element: 422 at its pointer" pyjson "$T/body" "
d['status'] == 422 and ('/model/elements/0/damper', 'duplicate key \"damper\"') in [(e['pointer'], e['detail']) for e in d['errors']]"
check "/metrics counts /v1/modes and /v1/response" bash -c \
    "curl -s '$U/metrics' | grep -q 'route=\"/v1/modes\"' && curl -s '$U/metrics' | grep -q 'route=\"/v1/response\"'"
stop_daemon modes
check "SIGTERM: exit 0" [ "$RC_modes" = 0 ]
finish
