#!/usr/bin/env bash
# tests/test_contact.sh - contacts and impacts (docs/systems.md §4, docs/contact.md) end to end, over HTTP and the
# CLI: the bouncing ball in every format (the Fn column, impact events with the rate before and after and the
# impulse, against the closed form), /v1/wellposedness's contact entries, every kind of bad contact input
# refused with 422 and the exact JSON Pointer, and the examples of docs/contact.md print what it shows.
# The JSON checks are python3 so that nothing here trusts the program's own parser. Env BUILD (default build).
source "$(dirname "$0")/lib/daemon.bash"
source "$(dirname "$0")/lib/post.bash"
CLI=$BUILD/dashpot

# The ball of docs/contact.md: dropped from 1 m on a table, e = 0.5, rows every 100 steps.
BALL='{"model": {"masses": [1],
 "elements": [{"between": ["ground", 0], "contact": {"distance": 0, "restitution": 0.5}}],
 "forcing": [{"node": 0, "kind": "constant", "value": -9.81}]},
 "initial": {"x": [1], "v": [0]},
 "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 2, "theta": 0.5},
 "output": {"every": 100}}'
# Impacts at t1 = sqrt(2/g), then every 2 e^k v1 / g; rebound speeds e^k v1, v1 = sqrt(2 g); rest from
# t_inf = t1 + 2 e v1 / (g (1 - e)) on.
CLOSED='
g, e = 9.81, 0.5
v1, t = math.sqrt(2 * g), math.sqrt(2 / g)
t_inf = t + 2 * e * v1 / (g * (1 - e))
def check_impacts(events):
    global t
    speed, tk = v1, t
    assert len(events) > 20, len(events)
    for ev in events[:10]:
        assert ev["kind"] == "impact" and ev["element"] == 0, ev
        assert abs(ev["t"] - tk) < 1e-9 and abs(ev["du"] + speed) < 1e-9 and abs(ev["du_after"] - e * speed) < 1e-9, (ev, tk, speed)
        assert abs(ev["impulse"] - (1 + e) * speed) < 1e-9 and abs(ev["u"]) < 1e-12, ev
        tk += 2 * e * speed / g; speed *= e
    assert abs(events[-1]["t"] - t_inf) < 1e-9, (events[-1], t_inf)
def check_rows(samples):
    assert [round(r["t"], 9) for r in samples] == [round(0.1 * i, 9) for i in range(21)], [r["t"] for r in samples]
    for r in samples:
        assert set(r) >= {"x", "v", "Fs", "Fd", "phase", "Fn"} and len(r["Fn"]) == 1, r
        assert r["x"][0] >= -1e-12, r
        if r["t"] > t_inf:
            assert abs(r["x"][0]) < 1e-12 and r["v"] == [0] and abs(r["Fn"][0] + g) < 1e-9, r
        elif r["x"][0] > 1e-9:
            assert r["Fn"] == [0], r
'

start_daemon contact || finish
U=$URL_contact/v1/simulate

req "$U" application/x-ndjson "$BALL"
cp "$BODY" "$SCRATCH/ndjson1"
check "ball NDJSON: 200" is "$STATUS" 200
check "ball NDJSON: impacts and rows against the closed form" py "$BODY" "$CLOSED"'
rows = [loads(l) for l in text.splitlines()]
check_impacts([r for r in rows if r["type"] == "event"])
check_rows([r for r in rows if r["type"] == "sample"])
assert rows[-1]["type"] == "summary" and rows[-1]["events"] == len([r for r in rows if r["type"] == "event"]), rows[-1]
'
req "$U" application/json "$BALL"
check "ball JSON: the same events and rows" py "$BODY" "$CLOSED"'
d = loads(text)
check_impacts(d["events"]); check_rows(d["samples"])
'
req "$U" text/csv "$BALL"
check "ball CSV: header with the Fn column, rest on the table" py "$BODY" '
lines = text.splitlines()
assert lines[0] == "t,x0,v0,Fs0,Fd0,phase0,Fn0", lines[0]
last = lines[-1].split(",")
assert float(last[0]) == 2 and abs(float(last[1])) < 1e-12 and float(last[2]) == 0 and abs(float(last[6]) + 9.81) < 1e-9, last
'
req "$U" text/event-stream "$BALL"
check "ball SSE: impact events" py "$BODY" '
ev = [loads(b.split("data: ", 1)[1]) for b in text.split("\n\n") if b.startswith("event: event")]
assert len(ev) > 20 and all(e["kind"] == "impact" and e["impulse"] >= 0 for e in ev), ev[:3]
'
"$CLI" simulate - --format ndjson <<<"$BALL" >"$SCRATCH/cli.out"
check "ball: the CLI prints what the daemon streamed" bash -c 'grep -v "^{\"type\":\"meta\"" "$1" >"$1.a"; grep -v "^{\"type\":\"meta\"" "$2" >"$2.a"; cmp -s "$1.a" "$2.a"' _ "$SCRATCH/cli.out" "$SCRATCH/ndjson1"

# ---- metrics: the impacts of the runs that ended (the five ball runs above, each ending after t_inf) ----
IMPACTS=$(python3 -c 'import json,sys; print(sum(1 for l in open(sys.argv[1]) if "\"impact\"" in l))' "$SCRATCH/cli.out")
for _ in $(seq 50); do   # a run's counters land when its connection is freed, just after the body ends
    hcurl -o "$SCRATCH/metrics" "$URL_contact/metrics"
    grep -q "^dashpot_impacts_total $((4 * IMPACTS))\$" "$SCRATCH/metrics" && break
    sleep 0.1
done
check "metrics: dashpot_impacts_total counts the four runs' impacts ($IMPACTS each)" py "$SCRATCH/metrics" '
v = {l.split()[0]: float(l.split()[1]) for l in text.splitlines() if l and not l.startswith("#")}
assert v["dashpot_impacts_total"] == 4 * '"$IMPACTS"', v["dashpot_impacts_total"]
assert v["dashpot_events_total"] >= v["dashpot_impacts_total"], v
'

# ---- well-posedness: what the theorems say with contacts ----
WP=$URL_contact/v1/wellposedness
req "$WP" application/json "$BALL"
check "wellposedness, one contact and linear laws: unique (Ballard)" py "$BODY" '
d = loads(text)
assert d["existence"]["guaranteed"] and d["uniqueness"]["guaranteed"], d
assert "Ballard" in d["uniqueness"]["theorem"] and any(c["hypothesis"].startswith("contacts") for c in d["checks"]), d
'
TWO=$(python3 -c 'import json,sys; d=json.loads(sys.argv[1]); d["model"]["masses"]=[1,1]; d["model"]["elements"].append({"between":[0,1],"contact":{"distance":0.1,"restitution":1}}); d["initial"]={"x":[1,2],"v":[0,0]}; print(json.dumps(d))' "$BALL")
req "$WP" application/json "$TWO"
check "wellposedness, two contacts: existence, uniqueness not guaranteed (simultaneous impacts)" py "$BODY" '
d = loads(text)
assert d["existence"]["guaranteed"] and not d["uniqueness"]["guaranteed"], d
assert "several rigid contacts" in d["uniqueness"]["reason"], d["uniqueness"]
'

# ---- bad input: 422 problem+json naming the member ----
bad() {
    local doc
    doc=$(python3 -c 'import json,sys; d=json.loads(sys.argv[1]); exec(sys.argv[2]); print(json.dumps(d))' "$BALL" "$3") || return 1
    req "$U" '*/*' "$doc"
    check "$1: 422 at $2" py "$BODY" '
d = loads(text)
assert d["status"] == '"$STATUS"' == 422 and d["type"] == "/problems/invalid-spec", (d["status"], d.get("type"))
ptrs = sorted(e["pointer"] for e in d["errors"])
assert ptrs == sorted("'"$2"'".split()), ptrs
assert d["errors"][0]["detail"], d
'
    check "$1: application/problem+json" is "$(header Content-Type)" application/problem+json
    "$CLI" simulate "$SCRATCH/request" >/dev/null 2>"$SCRATCH/cli.err"
    local rc=$?
    check "$1: CLI exit 2 naming ${2%% *}" bash -c '[ "$1" = 2 ] && grep -q "^dashpot: [^:]*: $2: " "$3"' _ "$rc" "${2%% *}" "$SCRATCH/cli.err"
}
C='d["model"]["elements"][0]["contact"]'
bad "restitution above 1" /model/elements/0/contact/restitution "$C[\"restitution\"] = 1.5"
bad "restitution below 0" /model/elements/0/contact/restitution "$C[\"restitution\"] = -0.1"
bad "restitution not a number" /model/elements/0/contact/restitution "$C[\"restitution\"] = \"elastic\""
bad "contact without a distance" /model/elements/0/contact/distance "del $C[\"distance\"]"
bad "rigid and compliant at once" /model/elements/0/contact/compliance "$C[\"compliance\"] = 1000"
bad "a zero compliance" /model/elements/0/contact/compliance "del $C[\"restitution\"]; $C[\"compliance\"] = 0"
bad "an unknown contact member" /model/elements/0/contact/mu "$C[\"mu\"] = 0.3"
bad "contact not an object" /model/elements/0/contact "$C = 0.5"
bad "initial state inside the stop" /initial/x/0 'd["initial"]["x"] = [-0.01]'
# (no initial state satisfies a rope shorter than the contact's distance: that is named at /initial/x/0 too)
bad "a rope that forbids every admissible elongation" "/model/elements/0/contact/distance /initial/x/0" \
    'd["model"]["elements"][0]["spring"] = {"law": "rope", "k": 1, "length": 0.5}; '"$C"'["distance"] = 0.8; d["initial"]["x"] = [0.4]; d["solver"]["theta"] = 1'
bad "a spring whose domain already keeps the contact open" /model/elements/0/contact/distance \
    'd["model"]["elements"][0]["spring"] = {"law": "graph", "points": [[-0.5, -1e9], [-0.5, 0], [1, 1]]}; '"$C"'["distance"] = -1; d["solver"]["theta"] = 1'
bad "the newmark solver" /model/elements/0/contact 'd["solver"] = {"kind": "newmark", "dt": 0.001, "t_end": 1}'
bad "a rigid contact with the regularized solver" /model/elements/0/contact \
    'd["solver"] = {"kind": "regularized", "n": 100, "dt": 0.001, "t_end": 1}'
# a compliant contact is theta-stepped at any theta (network_smooth.c); a spring graph with a vertical piece is not
bad "a graph spring with a vertical piece at theta 1/2 without located events" /model/elements/0/spring \
    'd["model"]["elements"][0]["spring"] = {"law": "graph", "points": [[-1, -2], [0, 0], [0, 1], [1, 2]]}; d["solver"]["events"] = "none"'


# ---- a one-mass document with a contact: the one-node network it is ----
ONE='{"model": {"mass": 1, "spring": {"law": "linear", "k": 0}, "damper": {"law": "none"}, "contact": {"distance": 0, "restitution": 0.5}, "forcing": {"kind": "constant", "value": -9.81}},
 "initial": {"x": 1, "v": 0}, "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 2, "theta": 0.5}, "output": {"every": 100}}'
req "$U" application/x-ndjson "$ONE"
check "one-mass document with a contact: 200" is "$STATUS" 200
check "one-mass document with a contact: the network's rows and impacts, bit for bit" py "$BODY" '
got = [l for l in text.splitlines() if not l.startswith("{\"type\":\"meta\"")]
want = [l for l in open("'"$SCRATCH/ndjson1"'").read().splitlines() if not l.startswith("{\"type\":\"meta\"")]
assert got == want, (got[:2], want[:2])
'
badone() {
    local doc
    doc=$(python3 -c 'import json,sys; d=json.loads(sys.argv[1]); exec(sys.argv[2]); print(json.dumps(d))' "$ONE" "$3") || return 1
    req "$U" '*/*' "$doc"
    check "one mass, $1: 422 at $2" py "$BODY" '
d = loads(text)
assert d["status"] == 422 and [e["pointer"] for e in d["errors"]] == ["'"$2"'"], d
'
}
badone "restitution 7" /model/contact/restitution 'd["model"]["contact"]["restitution"] = 7'
badone "starting inside the stop" /initial/x 'd["initial"]["x"] = -0.2'
badone "rigid and compliant at once" /model/contact/compliance 'd["model"]["contact"]["compliance"] = 100'
badone "the newmark solver" /model/contact 'd["solver"] = {"kind": "newmark", "dt": 0.001, "t_end": 1}'

# ---- the examples of docs/contact.md ----
doc_examples "$ROOT/docs/contact.md" contact

stop_daemon contact
check "SIGTERM: exit 0" is "$RC_contact" 0
finish
