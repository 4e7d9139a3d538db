#!/usr/bin/env bash
# tests/test_quakes.sh - the quake catalogue (docs/quakes.md) through the daemon and the CLI: quake lines in
# NDJSON and SSE, the `quakes` array of the JSON format, nothing in CSV, the CLI and the daemon byte for byte
# alike, the moments against the closed form of blocks sliding to rest (v0^2 / 2 phi), and bad members as 422
# problems naming /output/quakes.
# Env BUILD (default build). Prints "N passed, M failed"; exit 1 on any failure.
source "$(dirname "$0")/lib/daemon.bash"

BIN=$BUILD/dashpot
T=$SCRATCH
start_daemon q
URL=$URL_q

# Two unconnected blocks from 1 and 2.003 on phi = 0.5 (moments 1 and 4.012009), and a chain of three whose
# outer blocks are joined to the middle one by springs, cut at t_end while slipping (open).
cat >"$T/two.json" <<'JSON'
{"model": {"masses": [1, 1],
           "elements": [{"between": ["ground", 0], "damper": {"law": "coulomb", "phi0": 0.5}},
                        {"between": ["ground", 1], "damper": {"law": "coulomb", "phi0": 0.5}}]},
 "initial": {"v": [1, 2.003]}, "solver": {"dt": 0.01, "t_end": 3},
 "output": {"quakes": true, "every": 50}}
JSON

pyq() { # pyq FILE FORMAT EXPR: the quakes of FILE (ndjson, sse or json) as q, a list of dicts
    python3 - "$@" <<'PY' || { echo "    $3 fails for: $(head -c 800 "$1")"; return 1; }
import json, sys
text, fmt, expr = open(sys.argv[1]).read(), sys.argv[2], sys.argv[3]
if fmt == "ndjson":
    lines = [json.loads(l) for l in text.splitlines() if l]
    q = [l for l in lines if l["type"] == "quake"]
    order = [l["type"] for l in lines]
elif fmt == "sse":
    blocks = [b for b in text.split("\n\n") if b.strip()]
    q = [json.loads(b.split("data: ", 1)[1]) for b in blocks if b.startswith("event: quake\n")]
    order = [b.split("\n")[0][7:] for b in blocks]
else:
    d = json.loads(text)
    q, order = d.get("quakes", []), list(d)
sys.exit(0 if eval("(" + expr + ")") else 1)
PY
}

hcurl -H 'Accept: application/x-ndjson' --data-binary @"$T/two.json" "$URL/v1/simulate" >"$T/two.ndjson"
check "NDJSON: block 0's quake closed (moment 1, duration 2), block 1's open at t_end = 3 (moment 3 v0 - 9 phi/2)" \
    pyq "$T/two.ndjson" ndjson "
len(q) == 2 and q[0]['hypocentre'] == 0 and not q[0]['open'] and abs(q[0]['moment'] - 1) < 1e-12 and
abs(q[0]['duration'] - 2) < 1e-12 and q[1]['hypocentre'] == 1 and q[1]['open'] and
abs(q[1]['moment'] - (3 * 2.003 - 0.25 * 9)) < 1e-12 and q[1]['duration'] == 3 and
order.index('summary') == len(order) - 1 and order.index('quake') > order.index('meta')"
"$BIN" simulate "$T/two.json" --format ndjson >"$T/two.cli"
check "the CLI writes the same NDJSON as the daemon, byte for byte (version and timing masked)" \
    bash -c "diff <(sed -E 's/\"(version|wall_ms|elapsed_ms|wall)\":[^,}]*//g' '$T/two.ndjson') \
                  <(sed -E 's/\"(version|wall_ms|elapsed_ms|wall)\":[^,}]*//g' '$T/two.cli')"
hcurl -H 'Accept: text/event-stream' --data-binary @"$T/two.json" "$URL/v1/simulate" >"$T/two.sse"
check "SSE: the same quakes as 'event: quake'" pyq "$T/two.sse" sse "
len(q) == 2 and abs(q[0]['moment'] - 1) < 1e-12 and q[1]['open']"
hcurl -H 'Accept: application/json' --data-binary @"$T/two.json" "$URL/v1/simulate" >"$T/two.doc"
check "JSON: a quakes array after events, before summary" pyq "$T/two.doc" json "
order == ['meta', 'samples', 'events', 'quakes', 'summary'] and len(q) == 2 and q[1]['magnitude'] is not None"
hcurl -H 'Accept: text/csv' --data-binary @"$T/two.json" "$URL/v1/simulate" >"$T/two.csv"
check "CSV: rows only, no quake" bash -c "! grep -q quake '$T/two.csv' && [ \$(wc -l <'$T/two.csv') -ge 2 ]"

problem() { # problem DOC POINTER: 422 naming POINTER
    local code
    code=$(hcurl -o "$T/p.json" -w '%{http_code}' -H 'Content-Type: application/json' --data-binary "$1" \
        "$URL/v1/simulate")
    [ "$code" = 422 ] && python3 -c 'import json,sys; d=json.load(open(sys.argv[1]));
sys.exit(0 if sys.argv[2] in [e["pointer"] for e in d["errors"]] else 1)' "$T/p.json" "$2" ||
        { echo "    HTTP $code: $(head -c 400 "$T/p.json")"; return 1; }
}
NET='"model": {"masses": [1], "elements": [{"between": ["ground", 0], "damper": {"law": "coulomb", "phi0": 1}}]}'
check "422 /output/quakes: not a boolean" problem "{$NET, \"output\": {\"quakes\": \"yes\"}}" /output/quakes
check "422 /output/quakes: a network without friction" problem \
    '{"model": {"masses": [1], "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 1}}]}, "output": {"quakes": true}}' \
    /output/quakes
check "422 /output/quakes: a one-mass document" problem \
    '{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 1}}, "output": {"quakes": true}}' \
    /output/quakes
check "422 /output/quakes: the regularized solver" problem \
    "{$NET, \"solver\": {\"kind\": \"regularized\", \"n\": 100, \"t_end\": 1}, \"output\": {\"quakes\": true}}" /output/quakes
code=$(hcurl -o /dev/null -w '%{http_code}' -H 'Accept: application/x-ndjson' --data-binary \
    "{$NET, \"output\": {\"quakes\": false}}" "$URL/v1/simulate")
check "quakes false is accepted (HTTP $code)" test "$code" = 200

stop_daemon q
check "the daemon exits 0 on SIGTERM" test "$RC_q" = 0
finish
