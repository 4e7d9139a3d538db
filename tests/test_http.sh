#!/usr/bin/env bash
# tests/test_http.sh - dashpotd against curl on loopback: every route, every format, every error class
# (400, 404, 405 + Allow, 406, 413, 422 with pointers, 503 beyond --max-connections), a 10^7-sample NDJSON
# stream, a client that hangs up mid-stream (its run stops: /metrics), the wall-time limit as an error line,
# and SIGTERM with a stream in flight (exit 0; the stream ends with its summary or an error line).
# Env BUILD (default build). Prints "N passed, M failed"; exit 1 on any failure.
source "$(dirname "$0")/lib/daemon.bash"

BODY=$SCRATCH/body
HDRS=$SCRATCH/headers

# req METHOD URL [curl args...]: status in STATUS, body in $BODY, headers in $HDRS.
req() {
    local m=$1 u=$2
    shift 2
    STATUS=$(hcurl -X "$m" -D "$HDRS" -o "$BODY" -w '%{http_code}' "$@" "$u")
}
header() { grep -i "^$1:" "$HDRS" | head -1 | cut -d: -f2- | tr -d '\r' | sed 's/^ *//'; }
is() { [ "$1" = "$2" ] || { echo "    got '$1', expected '$2'"; return 1; }; }
# pyjson FILE EXPR: EXPR holds for d = the JSON in FILE (a Python expression).
pyjson() {
    python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if eval(sys.argv[2]) else 1)' "$1" "$2" ||
        { echo "    $2 fails for: $(head -c 600 "$1")"; return 1; }
}
problem() { # problem STATUS [TYPE]: the body is a problem document with that status (and type)
    pyjson "$BODY" "d['status'] == $1 and {'type','title','status','detail'} <= d.keys()" &&
        is "$(header Content-Type)" application/problem+json &&
        { [ -z "${2:-}" ] || pyjson "$BODY" "d['type'] == '$2'"; }
}
metric() { hcurl "$1/metrics" | awk -v n="$2" '$1 == n { print $2 }'; }

# Sticks and slips three times each within t_end (6 events).
SPEC='{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.5},
 "forcing": {"kind": "harmonic", "amplitude": 1, "omega": 0.5}}, "initial": {"x": 1, "v": 0},
 "solver": {"kind": "stick-slip", "dt": 0.01, "t_end": 20}}'
# t_end / dt steps at output every 1: LONG is 10^8 steps (the default --max-steps), BIG is 10^7.
long_spec() { echo "{\"model\": {\"mass\": 1, \"spring\": {\"law\": \"linear\", \"k\": 1}, \"damper\": {\"law\": \"coulomb\", \"phi0\": 0.3}, \"forcing\": {\"kind\": \"harmonic\", \"amplitude\": 0.5, \"omega\": 1.3}}, \"initial\": {\"x\": 1, \"v\": 0}, \"solver\": {\"dt\": 1e-6, \"t_end\": $1}, \"output\": {\"every\": 1}}"; }

TINY_SPEC='{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.3}}, "solver": {"dt": 1, "t_end": 2}}'

start_daemon main || finish
U=$URL_main

# ---- operations routes ----
req GET "$U/healthz"
check "GET /healthz is 200 {status: ok}" pyjson "$BODY" "d == {'status': 'ok'}"
check "GET /healthz is application/json" is "$(header Content-Type)" application/json
check "HEAD /healthz is 200" is "$(hcurl -I -o /dev/null -w '%{http_code}' "$U/healthz")" 200
req GET "$U/readyz"
check "GET /readyz is 200 {status: ready}" pyjson "$BODY" "d == {'status': 'ready'}"
req GET "$U/openapi.yaml"
check "GET /openapi.yaml is 200 application/yaml" is "$STATUS $(header Content-Type)" "200 application/yaml"
check "GET /openapi.yaml serves api/openapi.yaml" cmp -s "$BODY" "$ROOT/api/openapi.yaml"

# ---- error classes ----
req GET "$U/no/such/route"
check "unknown route is 404 problem+json" problem 404 about:blank
req DELETE "$U/healthz"
check "DELETE /healthz is 405" problem 405
check "405 has Allow: GET, HEAD" is "$(header Allow)" "GET, HEAD"
req GET "$U/v1/simulate"
check "GET /v1/simulate is 405 with Allow: POST" is "$STATUS $(header Allow)" "405 POST"
req POST "$U/v1/simulate" -H 'Accept: text/html' --data-binary "$SPEC"
check "Accept: text/html is 406" problem 406
req POST "$U/v1/simulate" -H 'Accept: application/x-ndjson;q=0, text/html' --data-binary "$SPEC"
check "Accept with q=0 for the only match is 406" problem 406
req POST "$U/v1/simulate" --data-binary '{"model": '
check "malformed JSON is 400 /problems/malformed-json" problem 400 /problems/malformed-json
check "400 locates the document (pointer \"\")" pyjson "$BODY" "d['errors'][0]['pointer'] == ''"
req POST "$U/v1/simulate" --data-binary '{"model": {"mass": -1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.3}}, "solver": {"dt": 0}}'
check "invalid spec is 422 /problems/invalid-spec" problem 422 /problems/invalid-spec
check "422 lists every error by pointer" pyjson "$BODY" "[e['pointer'] for e in d['errors']] == ['/model/mass', '/solver/dt']"
req POST "$U/v1/simulate" --data-binary "$(long_spec 1e6)"
check "10^12 steps is 422 /problems/over-limit (--max-steps)" problem 422 /problems/over-limit
req POST "$U/v1/simulate" --data-binary '{"model": {"mass": 1, "spring": {"law": "linear", "k": 5.6e53},
 "damper": {"law": "coulomb", "phi0": 0.4}}, "initial": {"x": -2}, "solver": {"kind": "analytic", "dt": 0.01, "t_end": 20}}'
check "analytic with 4.8e27 turning points (a worker spun for ever) is 422 over-limit at /model/spring/k" pyjson "$BODY" \
    "d['status'] == 422 and d['type'] == '/problems/over-limit' and d['errors'][0]['pointer'] == '/model/spring/k'"
head -c 2000000 /dev/zero | tr '\0' ' ' >"$SCRATCH/big"
req POST "$U/v1/simulate" --data-binary @"$SCRATCH/big"
check "a 2 MB body is 413 (Content-Length over --body-limit)" problem 413
req POST "$U/v1/simulate" -H 'Transfer-Encoding: chunked' --data-binary @"$SCRATCH/big"
check "a 2 MB chunked body is 413 (read and dropped past the limit)" problem 413
req GET "$U/a%22b%01c"
check "a hostile path is escaped in the log" grep -qF '"/a\x22b\x01c" 404' "$LOG_main"
req GET "$U/healthz%00junk"
check "%00 does not cut a path short: /healthz%00junk is 404, not /healthz" problem 404 about:blank
req GET "$U/%72eady%7a"
check "...while other escapes still decode: /%72eady%7a is /readyz" is "$STATUS" 200
# Raw bytes on the wire, no client escaping: ESC, a quote, a backslash, DEL and a byte >= 0x80 in the path,
# a quote in the method. The log keeps one line per request, with every such byte as \xHH.
python3 - "$PORT_main" <<'PY' >"$SCRATCH/raw"
import socket, sys
for line in (b'GET /x\x1b[31m"\\\x7f\xff HTTP/1.1\r\nHost: a\r\nConnection: close\r\n\r\n',
             b'GE"T /y HTTP/1.1\r\nHost: a\r\nConnection: close\r\n\r\n'):
    s = socket.create_connection(("127.0.0.1", int(sys.argv[1])), timeout=5)
    s.sendall(line)
    print(s.recv(100).split(b"\r\n")[0].decode())
    s.close()
PY
check "raw control bytes in a path: answered 404" grep -q '^HTTP/1.1 404' "$SCRATCH/raw"
check "...and logged escaped (\x1b \x22 \x5c \x7f \xff), never raw" \
    grep -qF 'GET "/x\x1b[31m\x22\x5c\x7f\xff" 404' "$LOG_main"
check "the log has no raw control byte or byte >= 0x80 at all" bash -c "! LC_ALL=C grep -q \$'[\x01-\x09\x0b-\x1f\x7f-\xff]' '$LOG_main'"
check "a quote in the method is escaped too" grep -qF 'GE\x22T "/y" 404' "$LOG_main"
check "the daemon listens on 127.0.0.1 only by default (/proc/net/tcp)" \
    grep -qE "^ *[0-9]+: 0100007F:$(printf %04X "$PORT_main") 00000000:0000 0A" /proc/net/tcp
timeout 10 "$DAEMON" --port "$PORT_main" 2>"$SCRATCH/busy.log"
check "a second daemon on a busy port exits 1" is "$?" 1
check "...and its message says how to pick another port" \
    grep -qF "cannot listen on 127.0.0.1 port $PORT_main (in use? pick another with --port N or DASHPOT_PORT=N" "$SCRATCH/busy.log"

# ---- formats ----
req POST "$U/v1/simulate" --data-binary "$SPEC"
check "simulate without Accept is JSON" is "$STATUS $(header Content-Type)" "200 application/json"
check "simulate streams chunked" is "$(header Transfer-Encoding)" chunked
check "JSON document: meta, 2001 samples, events, summary" pyjson "$BODY" \
    "list(d) == ['meta','samples','events','summary'] and len(d['samples']) == 2001 and d['summary']['samples'] == 2001 and d['meta']['steps'] == 2000 and d['meta']['solver'] == 'stick-slip'"
check "JSON samples have t x v Fs Fd Fc phase" pyjson "$BODY" "all(set(s) == {'t','x','v','Fs','Fd','Fc','phase'} for s in d['samples'])"
check "JSON events are stick/slip with t x v" pyjson "$BODY" "len(d['events']) == 6 and all(e['kind'] in ('stick','slip') and set(e) == {'kind','t','x','v'} for e in d['events'])"
cp "$BODY" "$SCRATCH/doc.json"
if [ -x "$BUILD/dashpot" ]; then
    printf '%s' "$SPEC" >"$SCRATCH/spec.json"
    "$BUILD/dashpot" simulate "$SCRATCH/spec.json" --format json --quiet >"$SCRATCH/cli.json"
    check "daemon JSON is byte-identical to the CLI's" cmp -s "$SCRATCH/doc.json" "$SCRATCH/cli.json"
fi
req POST "$U/v1/simulate" -H 'Accept: application/x-ndjson' --data-binary "$TINY_SPEC"
check "a run within one block (3 samples) is sent whole: Content-Length, not chunked" \
    is "$(header Content-Length) $(header Transfer-Encoding)" "$(wc -c <"$BODY") "
if [ -x "$BUILD/dashpot" ]; then
    printf '%s' "$TINY_SPEC" | "$BUILD/dashpot" simulate - --format ndjson --quiet >"$SCRATCH/tiny.ndjson"
    check "...with the CLI's bytes" cmp -s "$BODY" "$SCRATCH/tiny.ndjson"
fi
req POST "$U/v1/simulate" -H 'Accept: */*' --data-binary "$SPEC"
check "Accept: */* gets the default JSON" cmp -s "$BODY" "$SCRATCH/doc.json"

req POST "$U/v1/simulate" -H 'Accept: application/x-ndjson' --data-binary "$SPEC"
check "NDJSON content type" is "$(header Content-Type)" application/x-ndjson
check "NDJSON: every line is JSON; meta, samples and events, summary" python3 -c '
import json, sys
objs = [json.loads(l) for l in open(sys.argv[1])]
types = [o["type"] for o in objs]
ok = types[0] == "meta" and types[-1] == "summary" and set(types[1:-1]) == {"sample", "event"}
ok = ok and types.count("sample") == 2001 and objs[-1]["samples"] == 2001
doc = json.load(open(sys.argv[2]))
ok = ok and [ {k: v for k, v in o.items() if k != "type"} for o in objs if o["type"] == "sample"] == doc["samples"]
sys.exit(0 if ok else 1)' "$BODY" "$SCRATCH/doc.json"

req POST "$U/v1/simulate" -H 'Accept: text/event-stream' --data-binary "$SPEC"
check "SSE content type" is "$(header Content-Type)" text/event-stream
check "SSE: event/data pairs with matching types" python3 -c '
import json, sys
blocks = open(sys.argv[1]).read().split("\n\n")
assert blocks[-1] == ""
evs = [b.split("\n") for b in blocks[:-1]]
ok = all(len(e) == 2 and e[0].startswith("event: ") and e[1].startswith("data: ") and
         json.loads(e[1][6:])["type"] == e[0][7:] for e in evs)
ok = ok and evs[0][0] == "event: meta" and evs[-1][0] == "event: summary"
sys.exit(0 if ok else 1)' "$BODY"

req POST "$U/v1/simulate" -H 'Accept: text/csv' --data-binary "$SPEC"
check "CSV content type" is "$(header Content-Type)" "text/csv; charset=utf-8"
check "CSV: header and 2001 rows of 7 fields" python3 -c '
import sys
rows = open(sys.argv[1]).read().splitlines()
ok = rows[0] == "t,x,v,Fs,Fd,Fc,phase" and len(rows) == 2002 and all(len(r.split(",")) == 7 for r in rows[1:])
ok = ok and all(float(r.split(",")[0]) >= 0 for r in rows[1:])
sys.exit(0 if ok else 1)' "$BODY"
req POST "$U/v1/simulate" -H 'Accept: text/html;q=0.9, text/csv;q=0.5' --data-binary "$SPEC"
check "Accept picks the best acceptable offer (text/csv)" is "$STATUS $(header Content-Type)" "200 text/csv; charset=utf-8"
# Every spelling of each format, and what a wildcard picks (docs/http.md, "POST /v1/simulate").
for spelling in 'application/json -> application/json' 'application/* -> application/json' '*/* -> application/json' \
    'application/x-ndjson -> application/x-ndjson' 'application/ndjson -> application/x-ndjson' \
    'Application/NDJSON -> application/x-ndjson' 'application/ndjson;q=0.5, text/csv;q=0.4 -> application/x-ndjson' \
    'text/event-stream -> text/event-stream' 'text/csv -> text/csv; charset=utf-8' 'text/* -> text/csv; charset=utf-8' \
    'text/*;q=0.9, application/json;q=0.1 -> text/csv; charset=utf-8' 'text/plain, */*;q=0.1 -> application/json'; do
    req POST "$U/v1/simulate" -H "Accept: ${spelling%% -> *}" --data-binary "$TINY_SPEC"
    check "Accept: $spelling" is "$STATUS $(header Content-Type)" "200 ${spelling#* -> }"
done
req POST "$U/v1/simulate" -H 'Accept: application/ndjson' --data-binary "$TINY_SPEC"
check "Accept: application/ndjson is the same NDJSON as application/x-ndjson" cmp -s "$BODY" "$SCRATCH/tiny.ndjson"
req POST "$U/v1/simulate" -H 'Accept: application/ndjson;q=0' --data-binary "$TINY_SPEC"
check "Accept: application/ndjson;q=0 is 406" problem 406
req POST "$U/v1/stability" -H 'Accept: text/*' --data-binary '{"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]},
  "map": {"x": {"param": "mu[1]", "from": 0, "to": 2, "steps": 2}, "y": {"param": "lambda[1]", "from": 0.25, "to": 1.75, "steps": 2}}}'
check "stability map with Accept: text/* is CSV" is "$STATUS $(header Content-Type)" "200 text/csv; charset=utf-8"

REG='{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 1}},
 "initial": {"x": 4.5, "v": 0}, "solver": {"kind": "regularized", "n": 1000, "dt": 1, "t_end": 10}}'
req POST "$U/v1/simulate" -H 'Accept: application/x-ndjson' --data-binary "$REG"
check "regularized summary counts rejected steps and right-hand side evaluations" pyjson <(tail -n 1 "$BODY") \
    "d['type'] == 'summary' and d['rejected'] > 0 and d['fevals'] > d['steps'] > 0"
check "stick-slip summary has rejected 0 and fevals 0" pyjson "$SCRATCH/doc.json" \
    "d['summary']['rejected'] == 0 and d['summary']['fevals'] == 0"
check "regularized meta names its scheme, n, stepper and tolerances, none of the stick-slip fields" \
    pyjson <(head -n 1 "$BODY") "list(d)[:9] == ['type','version','solver','scheme','n','stepper','rtol','atol','dt'] \
    and (d['scheme'], d['n'], d['stepper'], d['rtol'], d['atol']) == ('PC', 1000, 'msbdf', 1e-8, 1e-10) \
    and not {'variant','events_mode','branch','theta'} & set(d)"
check "stick-slip meta keeps variant, events_mode, branch, theta in that order" pyjson "$SCRATCH/doc.json" \
    "list(d['meta'])[2:6] == ['variant','events_mode','branch','theta']"

STAB='{"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]}}'
MAP='{"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]}, "map": {"x": {"param": "mu[1]", "from": 0, "to": 2, "steps": 3},
 "y": {"param": "lambda[1]", "from": 0.25, "to": 1.75, "steps": 2}}}'
req POST "$U/v1/stability" --data-binary "$STAB"
check "stability JSON: verdict asymptotically stable" pyjson "$BODY" "d['verdict'] == 'asymptotically stable'"
req POST "$U/v1/stability" -H 'Accept: text/csv' --data-binary "$MAP"
check "stability map CSV: header and 3 x 2 rows" is "$STATUS $(header Content-Type) $(wc -l <"$BODY")" "200 text/csv; charset=utf-8 7"
req POST "$U/v1/stability" -H 'Accept: image/svg+xml' --data-binary "$MAP"
check "stability map SVG" is "$STATUS $(header Content-Type) $(head -c 4 "$BODY")" "200 image/svg+xml <svg"
big_map() { echo "{\"mass\": 1, \"law\": {\"lambda\": [1, 0.5], \"mu\": [1, 1]}, \"map\": {\"x\": {\"param\": \"mu[1]\", \"from\": 0, \"to\": 2, \"steps\": $1}, \"y\": {\"param\": \"lambda[1]\", \"from\": 0.25, \"to\": 1.75, \"steps\": $2}}}"; }
req POST "$U/v1/stability" -H 'Accept: text/csv' --data-binary "$(big_map 2000 2000)"
check "a 2000 x 2000 stability map is 422 /problems/over-limit at /map (--max-map-points 40000)" pyjson "$BODY" \
    "d['status'] == 422 and d['type'] == '/problems/over-limit' and d['errors'][0]['pointer'] == '/map'"
req POST "$U/v1/stability" -H 'Accept: text/csv' --data-binary "$(big_map 201 200 | sed 's/"map"/"\\u006dap"/')"
check "...also when \"map\" is spelled with a \\u escape" pyjson "$BODY" "d['status'] == 422 and d['errors'][0]['pointer'] == '/map'"
req POST "$U/v1/stability" -H 'Accept: text/csv' --data-binary "$(big_map 200 200)"
check "a 200 x 200 map (the limit) is 200 with 40000 rows" is "$STATUS $(wc -l <"$BODY")" "200 40001"
req POST "$U/v1/stability" -H 'Accept: application/x-ndjson' --data-binary "$STAB"
check "stability with Accept: application/x-ndjson is 406" problem 406
req POST "$U/v1/stability" --data-binary '{"mass": 0, "law": {"lambda": [1], "mu": [1]}}'
check "stability with mass 0 is 422 at /mass" pyjson "$BODY" "d['status'] == 422 and d['errors'][0]['pointer'] == '/mass'"
req POST "$U/v1/wellposedness" --data-binary "$SPEC"
check "wellposedness: existence and uniqueness guaranteed" pyjson "$BODY" "d['existence']['guaranteed'] and d['uniqueness']['guaranteed']"

# ---- the convergence study ----
STUDY='{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 1}},
 "initial": {"x": 4.5, "v": 0}, "solver": {"kind": "regularized", "n": [10, 100, 1000], "t_end": 10, "dt": 0.5}}'
req POST "$U/v1/convergence" --data-binary "$STUDY"
check "convergence: 200 application/json" is "$STATUS $(header Content-Type)" "200 application/json"
check "convergence: 3 rows against the closed form, order 1 (0.9 .. 1.1), n err_x -> 0.5 (10 - 2 pi)" pyjson "$BODY" \
    "len(d['rows']) == 3 and d['reference']['solver'] == 'analytic' and 0.9 < d['rate_x'] < 1.1 and abs(1000 * d['rows'][2]['err_x'] - 0.5 * (10 - 2 * 3.141592653589793)) < 0.01 and d['rows'][0]['rate_x'] is None"
if [ -x "$BUILD/dashpot" ]; then
    printf '%s' "$STUDY" | "$BUILD/dashpot" convergence - >"$SCRATCH/study.json"
    check "convergence: byte-identical to dashpot convergence" cmp -s "$BODY" "$SCRATCH/study.json"
fi
req POST "$U/v1/convergence" --data-binary "$SPEC"
check "convergence of a stick-slip spec is 422 at /solver/kind" pyjson "$BODY" \
    "d['status'] == 422 and d['type'] == '/problems/invalid-spec' and d['errors'][0]['pointer'] == '/solver/kind'"
req POST "$U/v1/convergence" --data-binary '{"solver": '
check "convergence of malformed JSON is 400" problem 400 /problems/malformed-json
req POST "$U/v1/convergence" -H 'Accept: text/csv' --data-binary "$STUDY"
check "convergence with Accept: text/csv is 406" problem 406
req GET "$U/v1/convergence"
check "GET /v1/convergence is 405 with Allow: POST" is "$STATUS $(header Allow)" "405 POST"

# ---- a 10^7-sample stream: t_end = 10, dt = 1e-6, every step a sample (not under valgrind: ~30 min) ----
if [ "${DASHPOT_VALGRIND:-0}" != 1 ]; then
t0=$(date +%s.%N)
CURL_TIME=600 hcurl -H 'Accept: application/x-ndjson' --data-binary "$(long_spec 10)" "$U/v1/simulate" |
    tee >(wc -l >"$SCRATCH/lines") | tail -n 1 >"$SCRATCH/last"
t1=$(date +%s.%N)
sleep 0.2 # the wc in the process substitution may still be writing
echo "    10^7 samples in $(echo "$t1 - $t0" | bc) s"
check "10^7-sample NDJSON: meta + 10000001 samples + summary lines" is "$(tr -d ' ' <"$SCRATCH/lines")" 10000003
check "10^7-sample NDJSON ends with its summary" pyjson "$SCRATCH/last" \
    "d['type'] == 'summary' and d['samples'] == 10000001 and d['steps'] == 10000000 and d['final']['t'] == 10"
else
    echo "    (DASHPOT_VALGRIND=1: the 10^7-sample stream is skipped)"
fi

# ---- a client that hangs up: the run stops and is counted as cancelled ----
before=$(metric "$U" dashpot_runs_cancelled_total)
hcurl -H 'Accept: application/x-ndjson' --data-binary "$(long_spec 100)" "$U/v1/simulate" | head -c 1000000 >/dev/null
cancelled=
for i in $(seq 100); do
    [ "$(metric "$U" dashpot_runs_cancelled_total)" = $((before + 1)) ] && [ "$(metric "$U" dashpot_runs_in_flight)" = 0 ] &&
        { cancelled=yes; break; }
    sleep 0.1
done
check "a client hanging up cancels its run (dashpot_runs_cancelled_total + 1, none in flight)" is "$cancelled" yes
s1=$(metric "$U" dashpot_samples_streamed_total)
sleep 0.5
check "...and the solver stopped (samples streamed unchanged)" is "$(metric "$U" dashpot_samples_streamed_total)" "$s1"
check "/metrics counts requests by route and status" \
    grep -q 'dashpot_http_requests_total{route="/v1/simulate",status="422"} 3' <(hcurl "$U/metrics")
check "/metrics has the duration histogram (a 405 counts under its route)" \
    grep -q 'dashpot_http_request_duration_seconds_bucket{route="/healthz",le="+Inf"} 3' <(hcurl "$U/metrics") # GET, HEAD, DELETE
check "one log line per request (method, path, status, bytes, duration)" \
    grep -qE '^[0-9T:.-]+Z POST "/v1/stability" 200 [0-9]+B [0-9.]+ms$' "$LOG_main"

stop_daemon main
check "SIGTERM when idle: exit 0" is "$RC_main" 0
check "--help prints the flags and exits 0" grep -q -- '--max-connections' <("$DAEMON" --help)
timeout 5 "$DAEMON" --port 99999 2>"$SCRATCH/err"
check "a bad flag value exits 2 with a message" is "$? $(cat "$SCRATCH/err")" \
    '2 dashpotd: --port: expected an integer in [0, 65535], got "99999"'
DASHPOT_BODY_LIMIT=12kb timeout 5 "$DAEMON" 2>"$SCRATCH/err"
check "a bad environment value exits 2" is "$?" 2

# ---- the bearer token: /v1/ needs it, the rest stays open ----
TINY='{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.3}}, "solver": {"dt": 1, "t_end": 2}}'
DASHPOT_TOKEN='tok.en-42~/+=' start_daemon tok || finish
T=$URL_tok
check "with a token the start-up line says so" grep -q '/v1/ routes: bearer token required' "$LOG_tok"
req POST "$T/v1/simulate" --data-binary "$TINY"
check "no Authorization: 401 /problems/unauthorized" problem 401 /problems/unauthorized
check "401 carries WWW-Authenticate: Bearer" is "$(header WWW-Authenticate)" 'Bearer realm="dashpot"'
for bad in 'Bearer tok.en-42~/+' 'Bearer tok.en-42~/+==' 'Bearer xok.en-42~/+=' 'Basic tok.en-42~/+=' 'Bearer'; do
    req POST "$T/v1/simulate" -H "Authorization: $bad" --data-binary "$TINY"
    check "Authorization: '$bad' is 401" is "$STATUS" 401
done
req POST "$T/v1/simulate" -H 'Authorization: Bearer tok.en-42~/+=' --data-binary "$TINY"
check "the right token: 200" is "$STATUS" 200
req POST "$T/v1/stability" -H 'authorization: bearer tok.en-42~/+=' --data-binary "$STAB"
check "the scheme and header name are case-insensitive (RFC 6750, 9110)" is "$STATUS" 200
req POST "$T/v1/no-such-route" --data-binary '{}'
check "an unknown /v1/ path without the token is 401, not 404 (nothing to learn without it)" is "$STATUS" 401
for path in /healthz /readyz /metrics /openapi.yaml; do
    req GET "$T$path"
    check "GET $path stays open without the token" is "$STATUS" 200
done
head -c 2000000 /dev/zero | tr '\0' ' ' >"$SCRATCH/big"
req POST "$T/v1/simulate" --data-binary @"$SCRATCH/big"
check "a 2 MB body without the token is 401 (refused before the upload)" is "$STATUS" 401
check "/metrics counts the 401s" grep -q 'dashpot_http_requests_total{route="/v1/simulate",status="401"} 7' <(hcurl "$T/metrics")
check "the token never reaches the log" bash -c "! grep -q 'tok.en' '$LOG_tok'"
stop_daemon tok
printf 'from-a-file\n' >"$SCRATCH/token"
start_daemon tokfile --token-file "$SCRATCH/token" || finish
req POST "$URL_tokfile/v1/simulate" -H 'Authorization: Bearer from-a-file' --data-binary "$TINY"
check "--token-file: its first line is the token" is "$STATUS" 200
req POST "$URL_tokfile/v1/simulate" -H 'Authorization: Bearer from-a-file\n' --data-binary "$TINY"
check "--token-file: the line break is not part of it" is "$STATUS" 401
stop_daemon tokfile
printf 'two words\n' >"$SCRATCH/token"
timeout 5 "$DAEMON" --port 0 --token-file "$SCRATCH/token" 2>"$SCRATCH/err"
check "a token with a space is refused at start (exit 2)" is "$?" 2
timeout 5 "$DAEMON" --port 0 --token-file "$SCRATCH/no-such-file" 2>"$SCRATCH/err"
check "an unreadable --token-file is refused at start (exit 2)" is "$?" 2

# ---- limits: connections and wall time ----
start_daemon small --max-connections 2 --max-wall 0.5 || finish
exec 5<>"/dev/tcp/127.0.0.1/$PORT_small" 6<>"/dev/tcp/127.0.0.1/$PORT_small"
for i in $(seq 50); do # until the daemon has accepted the two idle connections
    req GET "$URL_small/healthz"
    [ "$STATUS" = 503 ] && break
    sleep 0.1
done
check "a third connection over --max-connections 2 is 503 /problems/overloaded" problem 503 /problems/overloaded
check "503 carries Retry-After" is "$(header Retry-After)" 1
exec 5>&- 6>&-
sleep 0.3
req GET "$URL_small/healthz"
check "after the idle connections close it is 200 again" is "$STATUS" 200
CURL_TIME=60 hcurl -H 'Accept: application/x-ndjson' --data-binary "$(long_spec 100)" "$URL_small/v1/simulate" |
    tail -n 1 >"$SCRATCH/last"
check "over --max-wall the stream ends with an error line (503, wall-time)" pyjson "$SCRATCH/last" \
    "d['type'] == 'error' and d['status'] == 503 and 'wall-time' in d['detail']"
# An explicit stepper at n = 10^5, 10^6: about 8 s of work, stopped at the wall-time limit of 0.5 s.
t0=$(date +%s.%N)
req POST "$URL_small/v1/convergence" --data-binary '{"model": {"mass": 1, "spring": {"law": "linear", "k": 1},
 "damper": {"law": "coulomb", "phi0": 1}}, "initial": {"x": 4.5, "v": 0}, "solver": {"kind": "regularized",
 "n": [100000, 1000000], "stepper": "rkf45", "t_end": 100, "dt": 0.5}}'
t1=$(date +%s.%N)
check "a convergence study over --max-wall is 503 /problems/timeout" problem 503 /problems/timeout
check "...answered within 1.5 s of a 0.5 s limit (4 s under valgrind)" \
    python3 -c "import sys; sys.exit(0 if $t1 - $t0 < (4 if '${DASHPOT_VALGRIND:-0}' == '1' else 1.5) else 1)"
check "...and no study is left computing" is "$(metric "$URL_small" dashpot_studies_in_flight)" 0
stop_daemon small 20 HUP
check "SIGHUP drains like SIGTERM: exit 0" is "$RC_small" 0
check "...and says so in the log" grep -q 'received SIGHUP: draining' "$LOG_small"

# ---- SIGTERM with a stream in flight ----
start_daemon drain --shutdown-grace 1 || finish
CURL_TIME=60 hcurl -H 'Accept: application/x-ndjson' --data-binary "$(long_spec 100)" "$URL_drain/v1/simulate" \
    >"$SCRATCH/drain.ndjson" &
CURL_PID=$!
for i in $(seq 100); do [ -s "$SCRATCH/drain.ndjson" ] && break; sleep 0.1; done
stop_daemon drain 30
check "SIGTERM with a stream in flight: exit 0 within the grace period" is "$RC_drain" 0
wait_pid "$CURL_PID" 10
tail -n 1 "$SCRATCH/drain.ndjson" >"$SCRATCH/last"
check "...and the stream ends with an error line, not a cut" pyjson "$SCRATCH/last" \
    "d['type'] == 'error' and d['status'] == 503 and 'shutting down' in d['detail']"
check "...after the meta line and samples" pyjson <(head -n 1 "$SCRATCH/drain.ndjson") "d['type'] == 'meta'"

finish
