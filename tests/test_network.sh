#!/usr/bin/env bash
# tests/test_network.sh - network documents (docs/systems.md §1, docs/networks.md) end to end, over HTTP and the
# CLI: the 3-mass chain in every format (column names, array lengths, no NaN, located events that name an
# element), every kind of bad network input refused with 422 and the exact JSON Pointer (the n-mass step
# bound with relaxation on both sides of it), relaxation and static thresholds on elements against their
# laws, the regularized scheme against the exact stepping, /v1/wellposedness for a network, two unconnected
# networks in one document equal to the two separate runs (bit for bit without event location, to the
# method's error with it), and the examples of docs/networks.md print what it shows. The JSON checks are python3 so that nothing here trusts the
# program's own parser. Env BUILD (default build).
source "$(dirname "$0")/lib/daemon.bash"
source "$(dirname "$0")/lib/post.bash"
CLI=$BUILD/dashpot


# The chain of docs/networks.md: 3 masses, a Coulomb element to the ground, a spring and a viscous damper
# between masses, a harmonic load on node 2; nodes 0 and 2 and element 0 written, every 2000 steps.
CHAIN='{"model": {"masses": [1, 2, 1.5],
 "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.3, "belt_velocity": 0}},
              {"between": [0, 1], "spring": {"law": "linear", "k": 2}},
              {"between": [1, 2], "damper": {"law": "linear", "c": 0.1}}],
 "forcing": [{"node": 2, "kind": "harmonic", "amplitude": 1, "omega": 2, "phase": 0}]},
 "initial": {"x": [1, -0.5, 2], "v": [0, 0.3, 0]},
 "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 20, "theta": 0.5},
 "output": {"every": 2000, "nodes": [0, 2], "elements": [0]}}'

# What every network record must satisfy: arrays of the listed columns' lengths, finite numbers, phases
# from the documented set, events naming an element of the document. `rows` are the parsed records.
ROW_RULES='
NODES, ELEMS = 2, 1
def finite(v):
    return all(isinstance(a, (int, float)) and math.isfinite(a) for a in v)
def row_ok(r):
    assert len(r["x"]) == NODES and len(r["v"]) == NODES, r
    assert len(r["Fs"]) == ELEMS and len(r["Fd"]) == ELEMS and len(r["phase"]) == ELEMS, r
    assert finite(r["x"] + r["v"] + r["Fs"] + r["Fd"] + [r["t"]]), r
    assert all(p in ("stick", "slip", None) for p in r["phase"]), r
def event_ok(e):
    assert e["kind"] in ("stick", "slip") and e["element"] == 0 and 0 < e["t"] <= 20, e
    assert math.isfinite(e["u"]) and math.isfinite(e["du"]), e
'
CHECK_ROWS='
samples = [r for r in rows if r.get("type", "sample") == "sample"]
events = [r for r in rows if r.get("type") == "event"]
assert [r["t"] for r in samples] == [2.0 * i for i in range(11)], [r["t"] for r in samples]
for r in samples: row_ok(r)
assert len(events) >= 2 and {e["kind"] for e in events} == {"stick", "slip"}, events
for e in events: event_ok(e)
assert samples[0]["x"] == [1, 2] and samples[0]["v"] == [0, 0], samples[0]
# The spring force 1 is over the threshold 0.3 at t = 0: node 0 slips from the start (Fd = -0.3, no event),
# as the one-mass model says; a located stick lies strictly inside a step, where the velocity crosses zero.
assert samples[0]["phase"] == ["slip"] and samples[0]["Fd"] == [-0.3], samples[0]
sticks = [e for e in events if e["kind"] == "stick"]
assert sticks and all(abs(e["du"]) < 1e-12 for e in sticks), sticks
assert any(abs(e["t"] / 0.001 - round(e["t"] / 0.001)) > 1e-3 for e in sticks), [e["t"] for e in sticks]
'
CHECK_META='
assert meta["model"] == "network" and meta["nodes"] == 3 and meta["elements"] == 3, meta
assert meta["columns"] == {"nodes": [0, 2], "elements": [0]}, meta["columns"]
assert meta["events_mode"] == "locate" and meta["wellposedness"]["framework"] == "network", meta
'
CHECK_SUMMARY='
last = {k: v for k, v in samples[-1].items() if k != "type"}
assert summary["final"] == last, (summary["final"], last)
assert summary["samples"] == 11 and summary["events"] == len(events) and summary["steps"] == 20000, summary
'

start_daemon net || finish
U=$URL_net/v1/simulate

# ---- the chain in every format ----
ndjson_ok() {
    py "$1" "$ROW_RULES"'rows = [loads(l) for l in text.splitlines()]
assert rows[0]["type"] == "meta" and rows[-1]["type"] == "summary", [r["type"] for r in rows]
meta, summary, rows = rows[0], rows[-1], rows[1:-1]
'"$CHECK_ROWS$CHECK_META$CHECK_SUMMARY"
}
json_ok() {
    py "$1" "$ROW_RULES"'d = loads(text)
assert sorted(d) == ["events", "meta", "samples", "summary"], sorted(d)
meta, summary = d["meta"], d["summary"]
rows = d["samples"] + [dict(e, type="event") for e in d["events"]]
'"$CHECK_ROWS$CHECK_META$CHECK_SUMMARY"
}
csv_ok() {
    py "$1" "$ROW_RULES"'lines = text.splitlines()
assert lines[0] == "t,x0,x2,v0,v2,Fs0,Fd0,phase0", lines[0]
assert len(lines) == 12, len(lines)
rows = []
for l in lines[1:]:
    f = l.split(",")
    assert len(f) == 8, l
    rows.append({"t": float(f[0]), "x": [float(f[1]), float(f[2])], "v": [float(f[3]), float(f[4])],
                 "Fs": [float(f[5])], "Fd": [float(f[6])], "phase": [f[7] or None]})
samples = rows
for r in rows: row_ok(r)
assert [r["t"] for r in rows] == [2.0 * i for i in range(11)]
'
}
sse_ok() {
    py "$1" "$ROW_RULES"'blocks = [b for b in text.split("\n\n") if b.strip()]
kinds, rows = [], []
for b in blocks:
    ev = [l[len("event: "):] for l in b.splitlines() if l.startswith("event: ")]
    data = "".join(l[len("data: "):] for l in b.splitlines() if l.startswith("data: "))
    o = loads(data)
    assert o.get("type", ev[0]) == ev[0], (ev, o)
    kinds.append(ev[0]); rows.append(dict(o, type=ev[0]))
assert kinds[0] == "meta" and kinds[-1] == "summary", kinds
meta, summary, rows = rows[0], rows[-1], rows[1:-1]
'"$CHECK_ROWS$CHECK_META$CHECK_SUMMARY"
}

for fmt in "application/json json_ok" "application/x-ndjson ndjson_ok" "text/event-stream sse_ok" "text/csv csv_ok"; do
    set -- $fmt
    req "$U" "$1" "$CHAIN"
    check "HTTP $1: the 3-mass chain is 200 $1" is "$STATUS $(header Content-Type | cut -d';' -f1)" "200 $1"
    check "HTTP $1: columns of nodes [0, 2] and element [0], 11 samples, no NaN, events name element 0" "$2" "$BODY"
    cp "$BODY" "$SCRATCH/http.${1#*/}"
done
for fmt in "json json_ok" "ndjson ndjson_ok" "csv csv_ok"; do
    set -- $fmt
    echo "$CHAIN" | "$CLI" simulate - --format "$1" >"$SCRATCH/cli.$1" 2>"$SCRATCH/cli.err"
    rc=$?
    check "CLI --format $1: exit 0" is "$rc" 0
    check "CLI --format $1: the same checks as over HTTP" "$2" "$SCRATCH/cli.$1"
    check "CLI --format $1: nothing on stderr" test ! -s "$SCRATCH/cli.err"
done
check "CLI and HTTP give the same NDJSON bytes" cmp -s "$SCRATCH/cli.ndjson" "$SCRATCH/http.x-ndjson"
check "CLI and HTTP give the same CSV bytes" cmp -s "$SCRATCH/cli.csv" "$SCRATCH/http.csv"

# Without output.nodes / output.elements every node and element is written, in order.
ALL=$(python3 -c 'import json,sys; d=json.loads(sys.argv[1]); del d["output"]["nodes"], d["output"]["elements"]; print(json.dumps(d))' "$CHAIN")
req "$U" text/csv "$ALL"
check "without output.nodes/elements: CSV t,x0..x2,v0..v2,Fs0..Fs2,Fd0..Fd2,phase0..phase2" is "$(head -1 "$BODY")" \
    "t,x0,x1,x2,v0,v1,v2,Fs0,Fs1,Fs2,Fd0,Fd1,Fd2,phase0,phase1,phase2"
req "$U" application/x-ndjson "$ALL"
check "without output.nodes/elements: meta columns are all nodes and elements, samples of 3 and 3" py "$BODY" '
rows = [loads(l) for l in text.splitlines()]
assert rows[0]["columns"] == {"nodes": [0, 1, 2], "elements": [0, 1, 2]}, rows[0]["columns"]
s = [r for r in rows if r["type"] == "sample"]
assert all(len(r["x"]) == 3 and len(r["phase"]) == 3 for r in s)
# Elements 1 and 2 cannot stick (a spring; a viscous damper): their phase is null.
assert all(r["phase"][1] is None and r["phase"][2] is None for r in s), s[0]
# A linear spring k = 2 between nodes 0 and 1 carries 2 (x1 - x0); the ground element k = 1 carries x0.
for r in s:
    assert abs(r["Fs"][1] - 2 * (r["x"][1] - r["x"][0])) < 1e-12 and abs(r["Fs"][0] - r["x"][0]) < 1e-12, r
'

# ---- bad input: 422 problem+json naming the member ----
# bad DESCRIPTION POINTER JSON-PATCH: the chain with the python statement applied to d is refused at POINTER.
bad() {
    local doc
    doc=$(python3 -c 'import json,sys; d=json.loads(sys.argv[1]); exec(sys.argv[2]); print(json.dumps(d))' "$CHAIN" "$3") || return 1
    req "$U" '*/*' "$doc"
    check "$1: 422 at $2" py "$BODY" '
d = loads(text)
assert d["status"] == '"$STATUS"' == 422 and d["type"] == "/problems/invalid-spec", (d["status"], d.get("type"))
ptrs = [e["pointer"] for e in d["errors"]]
assert ptrs == ["'"$2"'"], ptrs
assert d["errors"][0]["detail"], d
'
    check "$1: application/problem+json" is "$(header Content-Type)" application/problem+json
    "$CLI" simulate "$SCRATCH/request" >/dev/null 2>"$SCRATCH/cli.err"
    local rc=$?
    check "$1: CLI exit 2 naming $2" bash -c '[ "$1" = 2 ] && grep -q "^dashpot: [^:]*: $2: " "$3"' _ "$rc" "$2" "$SCRATCH/cli.err"
}
bad "element end out of range" /model/elements/0/between/1 'd["model"]["elements"][0]["between"] = ["ground", 3]'
bad "element end neither ground nor an index" /model/elements/1/between/0 'd["model"]["elements"][1]["between"][0] = "sky"'
bad "element joining a node to itself" /model/elements/0/between 'd["model"]["elements"][0]["between"] = [1, 1]'
bad "element joining the ground to itself" /model/elements/2/between 'd["model"]["elements"][2]["between"] = ["ground", "ground"]'
bad "element with neither spring nor damper" /model/elements/1 'd["model"]["elements"][1] = {"between": [0, 1]}'
bad "element with an unknown member" /model/elements/1/mass 'd["model"]["elements"][1]["mass"] = 1'
bad "a zero mass" /model/masses/1 'd["model"]["masses"][1] = 0'
bad "a negative mass" /model/masses/2 'd["model"]["masses"][2] = -1.5'
# With no node count to check them against, output.nodes/elements add no errors of their own.
bad "masses not an array, with output.nodes and output.elements" /model/masses 'd["model"]["masses"] = "three"'
bad "an empty masses array" /model/masses 'd["model"]["masses"] = []; d["model"]["elements"] = []; d["model"]["forcing"] = []; d["initial"] = {}; del d["output"]["nodes"], d["output"]["elements"]'
bad "initial.x of 2 numbers for 3 nodes" /initial/x 'd["initial"]["x"] = [1, 2]'
bad "initial.v of 4 numbers for 3 nodes" /initial/v 'd["initial"]["v"] = [0, 0, 0, 0]'
bad "initial.x a number for a network" /initial/x 'd["initial"]["x"] = 1'
bad "a load on a node out of range" /model/forcing/0/node 'd["model"]["forcing"][0]["node"] = 3'
MM='d["model"]["mass_matrix"] = M; del d["model"]["masses"]'
bad "a non-symmetric mass_matrix" /model/mass_matrix "M = [[2, 1, 0], [0, 2, 0], [0, 0, 1]]; $MM"
bad "an indefinite mass_matrix" /model/mass_matrix "M = [[1, 2, 0], [2, 1, 0], [0, 0, 1]]; $MM"
bad "a singular mass_matrix" /model/mass_matrix "M = [[1, 1, 0], [1, 1, 0], [0, 0, 1]]; $MM"
bad "a mass_matrix row of the wrong length" /model/mass_matrix/1 "M = [[1, 0, 0], [0, 1], [0, 0, 1]]; $MM"
bad "masses and mass_matrix together" /model/mass_matrix \
    'd["model"]["mass_matrix"] = [[1, 0, 0], [0, 2, 0], [0, 0, 1.5]]; del d["output"]["nodes"], d["output"]["elements"]'
bad "an indefinite stiffness_matrix" /model/stiffness_matrix 'd["model"]["stiffness_matrix"] = [[0, 0, 0], [0, -1, 0], [0, 0, 0]]'
bad "output.nodes out of range" /output/nodes/1 'd["output"]["nodes"] = [0, 3]'
bad "output.elements out of range" /output/elements/0 'd["output"]["elements"] = [3]'
bad "a power relaxation on an element (not Lipschitz at rest)" /model/elements/0/damper/relaxation \
    'd["model"]["elements"][0]["damper"]["relaxation"] = {"kind": "power", "N": 2}'
# The n-mass step bound: W - h theta sum_e L_e b_e b_e^T > 0. Element 0 joins node 0 (m = 1) to the ground and
# only it relaxes, so the bound is hθL < 1 + h²θ²(k0 + k1) = 1 + 0.25e-6 * 3: L < 2000.0015 at dt = 1e-3,
# θ = 1/2 (one without θ would put it at 1000, one without h²θ²K the same to 1e-6). Rational γ: L = a/b.
RELAX='d["model"]["elements"][0]["damper"]["relaxation"] = {"kind": "rational", "a": 0.3, "b": 0.3 / L}'
bad "a dt past the n-mass step bound (L = 2010)" /solver/dt "L = 2010; $RELAX"
bad "the analytic solver on a network" /solver/kind 'd["solver"] = {"kind": "analytic", "t_end": 1, "dt": 0.1}'
REG='d["solver"] = {"kind": "regularized", "scheme": "PC", "n": 1e4, "t_end": 1, "dt": 0.01}'
bad "the regularized solver on a network with scheme PI" /solver/scheme \
    "$REG"'; d["solver"].update(scheme="PI", k=10); del d["solver"]["n"]'
bad "the regularized solver on a network with a list of n" /solver/n "$REG"'; d["solver"]["n"] = [10, 100]'
bad "the regularized solver on a network of 201 masses" /model/masses \
    "$REG"'; d["model"]["masses"] = [1] * 201; d["initial"] = {}'
bad "more than 200 nodes with a mass_matrix" /model/mass_matrix \
    'n = 201; d = {"model": {"mass_matrix": [[float(i == j) for j in range(n)] for i in range(n)]}, "solver": {"dt": 0.01, "t_end": 1}}'
bad "more than 20000 masses" /model/masses \
    'd = {"model": {"masses": [1] * 20001}, "solver": {"dt": 0.01, "t_end": 1}}'
bad "output.nodes on a one-mass document" /output/nodes \
    'd = {"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "none"}}, "output": {"nodes": [0]}, "solver": {"dt": 0.01, "t_end": 1}}'
bad "output.elements on a one-mass document" /output/elements \
    'd = {"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "none"}}, "output": {"elements": [0]}, "solver": {"dt": 0.01, "t_end": 1}}'

# ---- laws the network stepping took on after the first release: relaxation, static thresholds ----
# patch JSON-PYTHON: the chain with the python statement applied to d, on stdout.
patch() { python3 -c 'import json,sys; d=json.loads(sys.argv[1]); exec(sys.argv[2]); print(json.dumps(d))' "$CHAIN" "$1"; }
# Rational relaxation γ(z) = a z/(b + |z|) on the Coulomb element (thesis (3.2)): a slipping element carries
# F_d = φ0 sign z − γ(z) (z = v0, the ground does not move), checked on every slipping sample.
req "$U" application/x-ndjson "$(patch 'd["model"]["elements"][0]["damper"]["relaxation"] = {"kind": "rational", "a": 0.2, "b": 0.5}; d["output"] = {"every": 100}')"
check "rational relaxation on an element: 200, meta events_mode locate, F_d = 0.3 sign v − 0.2 v/(0.5 + |v|) when slipping" py "$BODY" '
rows = [loads(l) for l in text.splitlines()]
meta, s = rows[0], [r for r in rows if r["type"] == "sample"]
assert meta["events_mode"] == "locate" and rows[-1]["type"] == "summary", (meta["events_mode"], rows[-1])
assert [c["holds"] for c in meta["wellposedness"]["checks"]] == [True] * 4, meta["wellposedness"]
assert s[0]["phase"][0] == "slip" and s[0]["Fd"][0] == -0.3, s[0]     # at rest, pushed by Fs = 1 > 0.3
slip = [r for r in s[1:] if r["phase"][0] == "slip"]
# located, node 0 reverses through v = 0 without sticking (as a run at dt = 2e-5 shows); stepped, each
# reversal showed a stick of one step
assert len(slip) == 200 and rows[-1]["events"] == 0, (len(slip), rows[-1])
for r in slip:
    z = r["v"][0]
    want = 0.3 * (1 if z > 0 else -1) - 0.2 * z / (0.5 + abs(z))
    assert abs(r["Fd"][0] - want) < 1e-12 and abs(want) <= 0.3, (r, want)
'
# The accepted side of the step bound above: L = 1990 < 2000.0015 runs to its end.
req "$U" text/csv "$(patch 'L = 1990; d["model"]["elements"][0]["damper"]["relaxation"] = {"kind": "rational", "a": 0.3, "b": 0.3 / L}')"
check "a dt inside the n-mass step bound (L = 1990): 200, 11 finite rows to t = 20" py "$BODY" '
lines = text.splitlines()
assert len(lines) == 12 and lines[-1].startswith("20,"), lines[-2:]
assert all(math.isfinite(float(f)) for l in lines[1:] for f in l.split(",")[:-1]), lines
'
# Generalized Coulomb φ0 = 0.3, φ1 = 0.5 (the rest branch): slipping it carries ±φ0, stuck anything in
# [−φ1, φ1], and it does hold a force over φ0 at rest (else the static threshold would not matter here).
req "$U" application/x-ndjson "$(patch 'd["model"]["elements"][0]["damper"] = {"law": "generalized-coulomb", "phi0": 0.3, "phi1": 0.5}; d["output"] = {"every": 10}')"
check "a static threshold phi1 > phi0 on an element, events located: slipping |Fd| = 0.3, stuck |Fd| <= 0.5 and over 0.3 somewhere" py "$BODY" '
rows = [loads(l) for l in text.splitlines()]
assert rows[0]["events_mode"] == "locate" and rows[-1]["type"] == "summary", rows[0]
s = [r for r in rows if r["type"] == "sample"]
stuck = [abs(r["Fd"][0]) for r in s if r["phase"][0] == "stick"]
assert all(abs(abs(r["Fd"][0]) - 0.3) < 1e-12 for r in s if r["phase"][0] == "slip")
assert stuck and max(stuck) <= 0.5 + 1e-12 and max(stuck) > 0.3 + 1e-3, max(stuck or [0])
'

# ---- the regularized scheme (PCn, Yosida dampers) on the chain ----
# Against the exact stepping of the same chain at dt = 1e-4 (CLI): it converges at rate 1/n, so n = 1e4 is
# within a few 1e-4 (the core's study: 8.4e-5 at t = 20); 1e-3 would catch a wrong sign or half the friction.
REGDOC=$(patch 'd["solver"] = {"kind": "regularized", "scheme": "PC", "n": 1e4, "dt": 0.01, "t_end": 4}; d["output"]["every"] = 100')
EXACT=$(patch 'd["solver"] = {"kind": "stick-slip", "dt": 1e-4, "t_end": 4, "theta": 0.5}; d["output"]["every"] = 10000')
echo "$EXACT" | "$CLI" simulate - --format ndjson >"$SCRATCH/exact.ndjson"
req "$U" application/json "$REGDOC"
check "regularized on a network, JSON: 5 samples, phase null, within 1e-3 of the exact stepping at dt = 1e-4" py "$BODY" '
d = loads(text)
s = d["samples"]
exact = [json.loads(l) for l in open(sys.argv[1].replace("body", "exact.ndjson"))]
exact = [r for r in exact if r["type"] == "sample"]
assert d["events"] == [] and [r["t"] for r in s] == [0, 1, 2, 3, 4] == [r["t"] for r in exact], (s, exact)
assert all(r["phase"] == [None] and len(r["x"]) == 2 and len(r["Fd"]) == 1 for r in s), s[0]
err = max(abs(p - q) for r, e in zip(s, exact) for k in ("x", "v") for p, q in zip(r[k], e[k]))
assert err < 1e-3, err
assert d["summary"]["steps"] == 400 and d["summary"]["fevals"] > 0, d["summary"]
'
req "$U" text/csv "$REGDOC"
check "regularized on a network, CSV: the chain's header, 5 rows, phase empty" py "$BODY" '
lines = text.splitlines()
assert lines[0] == "t,x0,x2,v0,v2,Fs0,Fd0,phase0" and len(lines) == 6, lines
assert all(l.endswith(",") and len(l.split(",")) == 8 for l in lines[1:]), lines
'

# ---- /v1/wellposedness and dashpot wellposedness answer for networks ----
req "$URL_net/v1/wellposedness" application/json "$CHAIN"
check "/v1/wellposedness on the 3-mass chain: 200, framework network, existence and uniqueness guaranteed" py "$BODY" '
d = loads(text)
assert d["framework"] == "network" and d["existence"]["guaranteed"] and d["uniqueness"]["guaranteed"], d
assert all(c["holds"] for c in d["checks"]) and d["checks"][0]["detail"].startswith("3 nodes"), d["checks"]
'
cp "$BODY" "$SCRATCH/wp.http"
echo "$CHAIN" | "$CLI" wellposedness - >"$SCRATCH/wp.cli"
check "dashpot wellposedness on the chain: the same report as over HTTP" py "$SCRATCH/wp.cli" '
assert loads(text) == loads(open(sys.argv[1].replace("wp.cli", "wp.http")).read())
'

# ---- two unconnected networks in one document are the two separate runs ----
# A: the chain above with every node written; B: two masses on a belt, a Coulomb element between them.
A=$(python3 -c 'import json,sys; d=json.loads(sys.argv[1]); d["output"] = {"every": 50}; print(json.dumps(d))' "$CHAIN")
B='{"model": {"masses": [0.5, 1],
 "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 3}, "damper": {"law": "coulomb", "phi0": 0.4, "belt_velocity": 0.2}},
              {"between": [0, 1], "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.2}}],
 "forcing": [{"node": 1, "kind": "constant", "value": 0.1}]},
 "initial": {"x": [0.3, -0.2], "v": [0.2, 0]},
 "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 20, "theta": 0.5}, "output": {"every": 50}}'
AB=$(python3 - "$A" "$B" <<'PY'
import json, sys
a, b = json.loads(sys.argv[1]), json.loads(sys.argv[2])
na, ea = len(a["model"]["masses"]), len(a["model"]["elements"])
shift = lambda e: e if e == "ground" else e + na
m = {"masses": a["model"]["masses"] + b["model"]["masses"],
     "elements": a["model"]["elements"] + [dict(e, between=[shift(x) for x in e["between"]]) for e in b["model"]["elements"]],
     "forcing": a["model"]["forcing"] + [dict(f, node=f["node"] + na) for f in b["model"]["forcing"]]}
print(json.dumps({"model": m, "initial": {k: a["initial"][k] + b["initial"][k] for k in ("x", "v")},
                  "solver": a["solver"], "output": a["output"]}))
PY
)
# events "none" (Moreau-Jean: every step whole) gives the separate runs bit for bit. Located events split a
# step for the whole document at the first event of either half, so the other half takes two shorter θ-steps
# instead of one: the same trajectory to the method's error (θ = 1/2, dt = 1e-3: ~dt² = 1e-6), not bit for bit.
for mode in none locate; do
    for name in A B AB; do
        doc=$(python3 -c 'import json,sys; d=json.loads(sys.argv[1]); d["solver"]["events"] = sys.argv[2]; print(json.dumps(d))' "${!name}" "$mode")
        req "$U" application/x-ndjson "$doc"
        cp "$BODY" "$SCRATCH/sep.$mode.$name"
    done
done
SEPARATE='
def load(f):
    rows = [json.loads(l) for l in open(f).read().splitlines()]
    assert rows[-1]["type"] == "summary", rows[-1]
    return [r for r in rows if r["type"] == "sample"], [r for r in rows if r["type"] == "event"]
base = sys.argv[1][:-len("AB")]
sa, ea = load(base + "A")
sb, eb = load(base + "B")
s, e = load(sys.argv[1])
assert len(s) == len(sa) == len(sb) == 401, (len(s), len(sa), len(sb))
# Both halves stick and slip; the events of B are renumbered by the 3 elements of A.
assert len(ea) >= 2 and len(eb) >= 2, (len(ea), len(eb))
key = lambda x: (x["t"], x["element"], x["kind"])
want = sorted([x for x in ea] + [dict(x, element=x["element"] + 3) for x in eb], key=key)
got = sorted(e, key=key)
'
check "two unconnected networks, events none: every sample and event equals the separate runs, bit for bit" \
    py "$SCRATCH/sep.none.AB" "$SEPARATE"'
for r, a, b in zip(s, sa, sb):
    assert r["t"] == a["t"] == b["t"]
    for k in ("x", "v", "Fs", "Fd", "phase"):
        assert r[k] == a[k] + b[k], (r["t"], k, r[k], a[k] + b[k])
assert got == want, (len(got), len(want))
'
check "two unconnected networks, events located: the separate runs to 1e-6, the same events at times within 1e-6" \
    py "$SCRATCH/sep.locate.AB" "$SEPARATE"'
worst = 0
for r, a, b in zip(s, sa, sb):
    assert r["t"] == a["t"] == b["t"]
    for k in ("x", "v", "Fs", "Fd"):
        worst = max([worst] + [abs(p - q) for p, q in zip(r[k], a[k] + b[k])])
assert worst < 1e-6, worst
assert [(x["element"], x["kind"]) for x in got] == [(x["element"], x["kind"]) for x in want], (got, want)
assert max(abs(x["t"] - y["t"]) for x, y in zip(got, want)) < 1e-6, [(x["t"], y["t"]) for x, y in zip(got, want)]
'

# ---- docs/networks.md: its examples print what it shows (the conventions of tests/test_docs.sh) ----
doc_examples "$ROOT/docs/networks.md" net

stop_daemon net
check "SIGTERM: exit 0" is "$RC_net" 0
finish
