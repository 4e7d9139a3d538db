#!/usr/bin/env bash
# tests/test_right_hand.sh - the right-hand friction models (docs/systems.md §6, docs/right-hand.md) end to end,
# over HTTP and the CLI: the piston-hinge run in NDJSON and CSV (meta with the conditions and theorems, rows
# with q, qd, qdd, N, mode, margin of the right lengths, no NaN, events naming their coordinate, the normal
# force N1 recomputed here from the row by Newton's law), Painlevé's paradox at the start as a 422 problem
# with its record, a rod dropped on the floor bouncing and coming down, /v1/wellposedness for the rod, and every kind of bad input refused with 422 at its JSON
# Pointer (and by the CLI with exit 2). The JSON checks are python3, not the program's own parser.
source "$(dirname "$0")/lib/daemon.bash"
source "$(dirname "$0")/lib/post.bash"
CLI=$BUILD/dashpot


PISTON='{"model": {"kind": "piston-hinge", "m1": 1, "m2": 1, "J_C": 0.1, "r": 0.5, "alpha": 0.3, "f1": 0.2, "f2": 0.02},
 "initial": {"x": [0, 0.8], "v": [0, 0]},
 "solver": {"kind": "right-hand", "t_end": 1, "dt": 0.05}}'

start_daemon rh || { finish; exit 1; }
U=$URL_rh/v1/simulate

req "$U" application/x-ndjson "$PISTON"
check "piston NDJSON: 200" is "$STATUS" 200
check "piston NDJSON: meta, rows, events, summary" py "$BODY" '
lines = [loads(l) for l in text.splitlines()]
meta, rows = lines[0], [l for l in lines if l["type"] == "sample"]
events, summary = [l for l in lines if l["type"] == "event"], lines[-1]
assert meta["solver"] == "right-hand" and meta["model"] == "piston-hinge", meta
c = meta["conditions"]
assert set(c) == {"at", "1.2", "2.3", "6.2", "6.3", "6.4", "in_A"} and c["in_A"] is True, c
# (6.3) is a constant: J/(sqrt 2 m2 r) - f2 with J = J_C + m2 r^2
assert abs(c["6.3"] - ((0.1 + 0.25) / (math.sqrt(2) * 0.5) - 0.02)) < 1e-12, c
# (6.2) at beta = 0.8: J - f2 m2 r (|cos| + |sin|)
assert abs(c["6.2"] - (0.35 - 0.02 * 0.5 * (math.cos(0.8) + math.sin(0.8)))) < 1e-12, c
assert meta["wellposedness"]["framework"].startswith("right-hand solutions"), meta
assert len(rows) == 21 and summary["type"] == "summary", (len(rows), summary)
for r in rows:
    assert [len(r[k]) for k in ("q", "qd", "qdd", "N", "mode", "margin")] == [2, 2, 2, 2, 2, 4], r
    assert all(m in ("stick", "slip") for m in r["mode"]), r
    # N1 by Newton: the body centre'"'"'s acceleration normal to the tube, plus the weight'"'"'s normal part
    b, bd, bdd = r["q"][1], r["qd"][1], r["qdd"][1]
    n1 = 0.5 * (bdd * math.sin(b) + bd * bd * math.cos(b)) + 2 * 9.81 * math.cos(0.3)
    assert abs(r["N"][0] - n1) < 1e-9 * abs(n1), (r, n1)
    assert r["mode"][0] != "stick" or r["qd"][0] == 0, r
assert rows[0]["mode"] == ["stick", "slip"], rows[0]
assert events and all(e["element"] in (0, 1) for e in events), events
assert events[0]["kind"] == "slip" and events[0]["element"] == 0 and abs(events[0]["t"] - 0.4021431272) < 1e-9, events[0]
'

req "$U" text/csv "$PISTON"
check "piston CSV: header" is "$(head -1 "$BODY")" "t,q0,q1,qd0,qd1,qdd0,qdd1,N0,N1,mode0,mode1,margin0,margin1,margin2,margin3"
check "piston CSV: 21 rows" is "$(($(wc -l <"$BODY") - 1))" 21

EVERY=$(python3 -c 'import json,sys; d=json.loads(sys.argv[1]); d["output"]={"every": 4}; print(json.dumps(d))' "$PISTON")
req "$U" text/csv "$EVERY"
check "output.every 4 on the grid of dt: t = 0, 0.2, ..., 1" is "$(tail -n +2 "$BODY" | cut -d, -f1 | tr '\n' ' ')" "0 0.2 0.4 0.6000000000000001 0.8 1 "

# Painlevé's example (alpha = 0, f2 = 0, m1 = m2 = 1, J_C = 0) sliding at tan(beta) = f1/4: no acceleration.
PAINLEVE='{"model": {"kind": "piston-hinge", "m1": 1, "m2": 1, "r": 0.8, "alpha": 0, "f1": 5},
 "initial": {"x": [0, 0.8960553845713439], "v": [1, 0]}, "solver": {"t_end": 1, "dt": 0.1}}'
req "$U" application/json "$PAINLEVE"
check "Painleve paradox at t = 0: 422 problem with the record" py "$BODY" '
d = loads(text)
assert d["status"] == 422, d
assert "Painleve inconsistency" in d["detail"] and "t=0," in d["detail"] and "qd=[1,0]" in d["detail"], d
'
"$CLI" simulate "$SCRATCH/request" >/dev/null 2>"$SCRATCH/cli.err"
check "Painleve paradox: CLI says which" grep -q "Painleve inconsistency" "$SCRATCH/cli.err"

# A second acceleration appears at t = 0.0853 (tests/test_right_hand.c): the stream carries the rows before it,
# then the record as its error object.
MID='{"model": {"kind": "piston-hinge", "m1": 2.2125, "m2": 3.6783, "J_C": 0.6877, "r": 0.4161, "alpha": 0.7352, "f1": 5.2068, "f2": 0.2532},
 "initial": {"x": [0, -1.2397], "v": [-0.6889, -4.7616]}, "solver": {"t_end": 0.2, "dt": 0.01}}'
req "$U" application/x-ndjson "$MID"
check "indeterminacy mid-run: 200, 9 rows to t = 0.08, then the record" py "$BODY" '
lines = [loads(l) for l in text.splitlines()]
rows, last = [l for l in lines if l["type"] == "sample"], lines[-1]
assert '"$STATUS"' == 200 and len(rows) == 9 and abs(rows[-1]["t"] - 0.08) < 1e-12, (len(rows), rows[-1]["t"])
assert last["type"] == "error" and last["status"] == 422, last
assert "Painleve indeterminacy (2 accelerations) at t=0.0853" in last["detail"], last
'

ROD='{"model": {"kind": "painleve-rod", "m": 1, "length": 1, "mu": 1}, "initial": {"x": [0, 1.1], "v": [-0.5, 0]}}'
req "$URL_rh/v1/wellposedness" application/json "$ROD"
check "rod wellposedness: Theorems 4.1, 4.2 and 5.1" py "$BODY" '
d = loads(text)
assert d["existence"]["theorem"] == "Matrosov-Finogenko Theorems 4.1, 4.2", d
assert d["uniqueness"]["theorem"] == "Matrosov-Finogenko Theorem 5.1", d
assert any(c["hypothesis"].startswith("(2.3) for every state") and c["holds"] for c in d["checks"]), d
'
"$CLI" wellposedness "$SCRATCH/request" >"$SCRATCH/wp.json"
check "rod wellposedness: CLI answers the same" cmp -s "$SCRATCH/wp.json" "$BODY"

# A rod dropped from 0.5 above a rough floor (restitution 0.5): it bounces (impact, then lift-off), comes down
# to stick or slide; the rows carry the end's height (gap) and the meta line the restitution. The impact's
# rates are the end's height's before and after (0 height), and a bounce's lift-off carries the rebound.
DROP='{"model": {"kind": "painleve-rod", "m": 1, "length": 1, "mu": 0.3, "restitution": 0.5},
 "initial": {"x": [0, 1.2, 0.5], "v": [0.5, 1, 0]}, "solver": {"t_end": 1.2, "dt": 0.01}}'
req "$U" application/x-ndjson "$DROP"
check "dropped rod: bounces, then stick or slip" py "$BODY" '
lines = [loads(l) for l in text.splitlines()]
meta, rows = lines[0], [l for l in lines if l["type"] == "sample"]
events = [l for l in lines if l["type"] == "event"]
assert meta["parameters"]["restitution"] == 0.5 and meta["columns"]["gap"] == ["y_A", "yd_A"], meta
assert lines[-1]["type"] == "summary" and len(rows) == 121, lines[-1]
imp = [i for i, e in enumerate(events) if e["kind"] == "impact"]
assert len(imp) >= 5, events
for i in imp:
    e, nxt = events[i], events[i + 1]
    assert e["u"] == 0 and e["du"] < 0 <= e["du_after"] and e["impulse"] > 0, e
    assert nxt["t"] == e["t"] and nxt["kind"] in ("liftoff", "stick", "slip"), (e, nxt)
    assert nxt["kind"] != "liftoff" or nxt["du"] == e["du_after"] > 0, (e, nxt)
assert events[imp[-1] + 1]["kind"] in ("stick", "slip"), events[imp[-1]:]
for r in rows:
    assert len(r["gap"]) == 2 and r["gap"][0] >= 0, r
    assert (r["mode"][0] is None) == (r["gap"] != [0, 0]) and (r["N"][0] == 0) == (r["mode"][0] is None), r
assert rows[0]["gap"] == [0.5, 0] and rows[-1]["gap"] == [0, 0] and rows[-1]["mode"][0] in ("stick", "slip"), rows[-1]
'

# bad DESCRIPTION POINTER DOC PATCH: DOC with the python statement applied to d is refused at POINTER.
bad() {
    local doc
    doc=$(python3 -c 'import json,sys; d=json.loads(sys.argv[1]); exec(sys.argv[2]); print(json.dumps(d))' "$3" "$4") || return 1
    req "$U" '*/*' "$doc"
    check "$1: 422 at $2" py "$BODY" '
d = loads(text)
assert d["status"] == '"$STATUS"' == 422, d
ptrs = [e["pointer"] for e in d["errors"]]
assert ptrs == ["'"$2"'"], ptrs
'
    "$CLI" simulate "$SCRATCH/request" >/dev/null 2>"$SCRATCH/cli.err"
    local rc=$?
    check "$1: CLI exit 2 naming $2" bash -c '[ "$1" = 2 ] && grep -q "^dashpot: [^:]*: $2: " "$3"' _ "$rc" "$2" "$SCRATCH/cli.err"
}
bad "negative m1" /model/m1 "$PISTON" 'd["model"]["m1"] = -1'
bad "zero r" /model/r "$PISTON" 'd["model"]["r"] = 0'
bad "negative J_C" /model/J_C "$PISTON" 'd["model"]["J_C"] = -0.1'
bad "alpha above pi/2" /model/alpha "$PISTON" 'd["model"]["alpha"] = 2'
bad "negative alpha" /model/alpha "$PISTON" 'd["model"]["alpha"] = -0.1'
bad "negative f1" /model/f1 "$PISTON" 'd["model"]["f1"] = -0.2'
bad "negative f2" /model/f2 "$PISTON" 'd["model"]["f2"] = -1'
bad "no gravity" /model/g "$PISTON" 'd["model"]["g"] = 0'
bad "missing f1" /model/f1 "$PISTON" 'del d["model"]["f1"]'
bad "unknown model key" /model/mass "$PISTON" 'd["model"]["mass"] = 1'
bad "unknown kind" /model/kind "$PISTON" 'd["model"]["kind"] = "piston"'
bad "initial x of 3" /initial/x "$PISTON" 'd["initial"]["x"] = [0, 1, 2]'
bad "initial v not numbers" /initial/v/1 "$PISTON" 'd["initial"]["v"] = [0, "fast"]'
bad "the stick-slip solver" /solver/kind "$PISTON" 'd["solver"]["kind"] = "stick-slip"'
bad "rtol of 2" /solver/rtol "$PISTON" 'd["solver"]["rtol"] = 2'
bad "negative rod length" /model/length "$ROD" 'd["model"]["length"] = -1'
bad "negative rod mass" /model/m "$ROD" 'd["model"]["m"] = -1'
bad "negative mu" /model/mu "$ROD" 'd["model"]["mu"] = -0.5'
bad "rod below the floor" /initial/x/1 "$ROD" 'd["initial"]["x"] = [0, -0.1]'
bad "restitution above 1" /model/restitution "$ROD" 'd["model"]["restitution"] = 1.5'
bad "negative restitution" /model/restitution "$ROD" 'd["model"]["restitution"] = -0.1'
bad "rod end under the floor" /initial/x/2 "$ROD" 'd["initial"]["x"] = [0, 1.1, -0.2]'
bad "rod initial v of 4" /initial/v "$ROD" 'd["initial"]["v"] = [0, 1, 2, 3]'
bad "piston initial x of 3" /initial/x "$PISTON" 'd["initial"]["x"] = [0, 0.8, 1]'

stop_daemon rh
check "SIGTERM: exit 0" is "$RC_rh" 0
finish
