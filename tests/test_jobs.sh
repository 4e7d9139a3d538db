#!/usr/bin/env bash
# tests/test_jobs.sh - the routes answered whole (/v1/lcp, /v1/modes, /v1/response, /v1/convergence, stability
# maps) compute on the compute threads (src/http/jobs.c), not on libmicrohttpd's connection threads, and stop
# on the wall limit, the client's hang-up and SIGTERM (src/http/watch.c):
#   1. while two long convergence studies compute (--threads 2), 20 /healthz each answer within 0.5 s: half
#      on connections opened (and served once) before the studies began, like the studies' own, which
#      libmicrohttpd pinned to its pool threads (when a thread computed, the probes pinned to it waited),
#      half on new ones; the studies then answer 503 /problems/timeout within --max-wall + 1.5 s;
#   2. with --threads 1 a second study waits for the slot, then stops at once (its time is up): 503 timeout;
#   3. several jobs in turn on one kept-alive connection, then /healthz on it: each answered right;
#   4. a client that hangs up mid-study frees its slot: /readyz 503 busy before, 200 within 2 s after;
#   5. SIGTERM with a study in flight and --shutdown-grace 1: the client gets 503 /problems/shutting-down and
#      the daemon exits 0 within grace + 1.5 s;
#   6. the library polls the hook inside Lemke's pivots and a response curve's points: with --max-wall 1,
#      Murty's 300 x 300 LCP (2^300 pivots, cut at Lemke's limit of 61 000: seconds of work) and a 300-node
#      response with non-proportional damping at its most points answer 503 /problems/timeout within 2.5 s,
#      and an LCS whose algebraic part at t = 0 is Murty's 250 x 250 ends its stream at the limit.
# The bounds are coarse functional guarantees, not benchmarks (the probes' is 2 s under DASHPOT_VALGRIND=1,
# which runs one thread at a time). Env BUILD (default build), DASHPOT_VALGRIND (tests/lib/daemon.bash).
source "$(dirname "$0")/lib/daemon.bash"

is() { [ "$1" = "$2" ] || { echo "    got '$1', expected '$2'"; return 1; }; }
below() { python3 -c "import sys; sys.exit(0 if $1 < $2 else 1)" || { echo "    $1 is not below $2"; return 1; }; }
metric() { hcurl "$1/metrics" | awk -v n="$2" '$1 == n { print $2 }'; }
# pyjson FILE EXPR: EXPR holds for d = the JSON in FILE.
pyjson() {
    python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if eval(sys.argv[2]) else 1)' "$1" "$2" ||
        { echo "    $2 fails for: $(head -c 800 "$1")"; return 1; }
}
wait_metric() { # wait_metric URL NAME VALUE: until the metric has that value (at most 5 s)
    local i
    for i in $(seq 100); do [ "$(metric "$1" "$2")" = "$3" ] && return 0; sleep 0.05; done
    echo "    $2 is $(metric "$1" "$2"), not $3"
    return 1
}

# An explicit stepper at n = 10^5 and 10^6 to t_end 1000: ~80 s of work, polled between blocks.
STUDY='{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 1}},
 "initial": {"x": 4.5, "v": 0}, "solver": {"kind": "regularized", "n": [100000, 1000000], "stepper": "rkf45",
 "t_end": 1000, "dt": 0.5}}'
printf '%s' "$STUDY" >"$SCRATCH/study.json"

# probe.py PORT WALL OUT: the scenario of 1. as JSON in OUT.
cat >"$SCRATCH/probe.py" <<'PY'
import http.client, json, sys, threading, time
port, wall, out = int(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
study = open(sys.argv[4], "rb").read()
kept = []
for _ in range(10): # each served once, so that libmicrohttpd has accepted it into one of its threads
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    c.request("GET", "/healthz"); c.getresponse().read()
    kept.append(c)
    time.sleep(0.02)
studies = []
def run_study(c): # on a connection libmicrohttpd holds already, likely in the same thread as some probes'
    t0 = time.monotonic()
    c.request("POST", "/v1/convergence", body=study)
    r = c.getresponse()
    studies.append({"status": r.status, "body": json.loads(r.read()), "seconds": time.monotonic() - t0,
                    "ended": time.monotonic()})
threads = [threading.Thread(target=run_study, args=(kept[i],)) for i in range(2)]
for t in threads: t.start()
def busy():
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=5)
    c.request("GET", "/metrics")
    m = c.getresponse().read().decode()
    return [l for l in m.splitlines() if l.startswith("dashpot_studies_in_flight ")] == ["dashpot_studies_in_flight 2"]
for _ in range(100):
    if busy(): break
    time.sleep(0.05)
probes = []
for i in range(20):
    c = kept[2 + i // 2 % 8] if i % 2 == 0 else http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    t0 = time.monotonic()
    try:
        c.request("GET", "/healthz"); r = c.getresponse(); ok = r.status == 200 and r.read() == b'{"status":"ok"}\n'
    except Exception as e:
        ok = False
    probes.append({"kept": i % 2 == 0, "ok": ok, "seconds": time.monotonic() - t0, "at": time.monotonic()})
    time.sleep(0.05)
last_probe = probes[-1]["at"]
for t in threads: t.join()
json.dump({"probes": probes, "studies": studies, "during": all(s["ended"] > last_probe for s in studies)},
          open(out, "w"))
PY

echo "# 1. /healthz while two studies compute"
start_daemon two --threads 2 --max-wall 5 || finish
python3 "$SCRATCH/probe.py" "$PORT_two" 5 "$SCRATCH/two.json" "$SCRATCH/study.json"
python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
print("    slowest /healthz: %.3f s (kept-alive), %.3f s (new); studies answered after %s s" % (
    max(p["seconds"] for p in d["probes"] if p["kept"]), max(p["seconds"] for p in d["probes"] if not p["kept"]),
    ", ".join("%.2f" % s["seconds"] for s in d["studies"])))' "$SCRATCH/two.json"
check "20 /healthz answered 200 while the studies computed" pyjson "$SCRATCH/two.json" \
    "len(d['probes']) == 20 and all(p['ok'] for p in d['probes']) and d['during']"
PROBE_BOUND=0.5
[ "${DASHPOT_VALGRIND:-0}" = 1 ] && PROBE_BOUND=2 # valgrind runs one thread at a time
check "...each within $PROBE_BOUND s, on kept-alive and on new connections" pyjson "$SCRATCH/two.json" \
    "max(p['seconds'] for p in d['probes']) < $PROBE_BOUND"
check "both studies: 503 /problems/timeout naming the limit" pyjson "$SCRATCH/two.json" \
    "len(d['studies']) == 2 and all(s['status'] == 503 and s['body']['type'] == '/problems/timeout' and s['body']['detail'] == 'the study exceeded the wall-time limit of 5 s' for s in d['studies'])"
check "...within --max-wall + 1.5 s" pyjson "$SCRATCH/two.json" "all(s['seconds'] < 6.5 for s in d['studies'])"
check "no study left computing, no slot taken" is "$(metric "$URL_two" dashpot_studies_in_flight) $(metric "$URL_two" dashpot_workers_busy)" "0 0"
stop_daemon two
check "exit 0" is "$RC_two" 0

echo "# 2. a job waiting for the one slot (--threads 1, --max-wall 2)"
start_daemon one --threads 1 --max-wall 2 || finish
PIDS=()
for k in a b; do
    curl -s -m 20 -o "$SCRATCH/$k" -w '%{time_total}' --data-binary @"$SCRATCH/study.json" \
        "$URL_one/v1/convergence" >"$SCRATCH/$k.time" &
    PIDS+=($!)
done
wait "${PIDS[@]}"
echo "    answered after $(cat "$SCRATCH/a.time") s and $(cat "$SCRATCH/b.time") s"
for k in a b; do
    check "study $k: 503 /problems/timeout" pyjson "$SCRATCH/$k" "d['status'] == 503 and d['type'] == '/problems/timeout'"
    check "...within 2 s + 1.5 s" below "$(cat "$SCRATCH/$k.time")" 3.5
done

echo "# 3. jobs in turn on one kept-alive connection"
python3 - "$PORT_one" >"$SCRATCH/keep" <<'PY'
import http.client, json, sys
c = http.client.HTTPConnection("127.0.0.1", int(sys.argv[1]), timeout=30)
def post(path, body, accept="application/json"):
    c.request("POST", path, body=json.dumps(body), headers={"Accept": accept})
    r = c.getresponse()
    return r.status, r.getheader("Content-Type"), r.read()
s, t, b = post("/v1/lcp", {"M": [[2, 1], [1, 2]], "q": [-5, -6]})
print("lcp", s, t, json.loads(b)["lemke"]["z"])
chain = {"model": {"masses": [1, 1], "elements": [{"between": ["ground", 0], "spring": {"law": "linear", "k": 1}},
                                                  {"between": [0, 1], "spring": {"law": "linear", "k": 1}}]}}
s, t, b = post("/v1/modes", chain)
print("modes", s, t, len(json.loads(b)["modes"]))
s, t, b = post("/v1/response", dict(chain, force_node=1, response_node=1,
                                    omega={"from": 0.1, "to": 2, "points": 5}), "text/csv")
print("response", s, t, len(b.decode().splitlines()))
s, t, b = post("/v1/lcp", {"M": [[1]], "q": "x"})
print("bad", s, t, json.loads(b)["type"])
c.request("GET", "/healthz")
r = c.getresponse()
print("healthz", r.status, r.read().decode().strip())
PY
cat "$SCRATCH/keep" | sed 's/^/    /'
check "/v1/lcp: 200 with Lemke's z = (4/3, 7/3)" grep -qE '^lcp 200 application/json \[1\.333333333333333[0-9]*, 2\.333333333333333[0-9]*\]$' "$SCRATCH/keep"
check "then /v1/modes on the same connection: 200, 2 modes" grep -qx 'modes 200 application/json 2' "$SCRATCH/keep"
check "then /v1/response as CSV: 200, header and 5 rows" grep -qx 'response 200 text/csv; charset=utf-8 6' "$SCRATCH/keep"
check "then a bad body: 422 problem" grep -qx 'bad 422 application/problem+json /problems/invalid-spec' "$SCRATCH/keep"
check "then /healthz on it: 200" grep -qx 'healthz 200 {"status":"ok"}' "$SCRATCH/keep"
stop_daemon one
check "exit 0" is "$RC_one" 0

echo "# 4. a client that hangs up mid-study frees its slot"
start_daemon gone --threads 1 --max-wall 60 || finish
curl -s -m 30 -o /dev/null --data-binary @"$SCRATCH/study.json" "$URL_gone/v1/convergence" &
CURL=$!
check "the study computes (dashpot_workers_busy 1)" wait_metric "$URL_gone" dashpot_workers_busy 1
check "/readyz says 503 /problems/busy" is "$(hcurl -o /dev/null -w '%{http_code}' "$URL_gone/readyz")" 503
kill "$CURL"
wait "$CURL" 2>/dev/null
t0=$(date +%s.%N)
ready=
for _ in $(seq 250); do
    [ "$(hcurl -o /dev/null -w '%{http_code}' "$URL_gone/readyz")" = 200 ] && { ready=yes; break; }
    sleep 0.01
done
t1=$(date +%s.%N)
freed=$(python3 -c "print(round($t1 - $t0, 3))")
echo "    /readyz was 200 again ${freed} s after the hang-up"
check "/readyz is 200 again" is "$ready" yes
check "...within 2 s (the study polls its hook every 10^5 integrator steps)" below "$freed" 2
check "...and the study stopped (dashpot_studies_in_flight 0)" wait_metric "$URL_gone" dashpot_studies_in_flight 0
stop_daemon gone
check "exit 0" is "$RC_gone" 0

echo "# 5. SIGTERM with a study in flight"
start_daemon term --threads 2 --max-wall 60 --shutdown-grace 1 || finish
curl -s -m 30 -o "$SCRATCH/term" --data-binary @"$SCRATCH/study.json" "$URL_term/v1/convergence" &
CURL=$!
check "the study computes" wait_metric "$URL_term" dashpot_studies_in_flight 1
t0=$(date +%s.%N)
stop_daemon term 20
t1=$(date +%s.%N)
took=$(python3 -c "print(round($t1 - $t0, 3))")
wait "$CURL"
echo "    exited ${took} s after SIGTERM"
check "SIGTERM: exit 0" is "$RC_term" 0
check "...within grace + 1.5 s" below "$took" 2.5
check "...and the study was answered 503 /problems/shutting-down" pyjson "$SCRATCH/term" \
    "d['status'] == 503 and d['type'] == '/problems/shutting-down'"

echo "# 6. the wall limit inside Lemke's pivots and a response curve (--max-wall 1)"
start_daemon wall --threads 2 --max-wall 1 || finish
python3 - >"$SCRATCH/murty.json" <<'PY'
import json
m = 300  # Murty 1978's matrix with 3/2 below the diagonal (tests/test_lcp.c): 2^m pivots
print(json.dumps({"M": [[1 if i == j else 1.5 if j < i else 0 for j in range(m)] for i in range(m)], "q": [-1] * m}))
PY
python3 - >"$SCRATCH/resp.json" <<'PY'
import json
n = 300  # a chain with one damper: non-proportional damping, each point a complex solve of n nodes
el = [{"between": ["ground" if i == 0 else i - 1, i], "spring": {"law": "linear", "k": 1}} for i in range(n)]
el[0]["damper"] = {"law": "linear", "c": 0.1}
print(json.dumps({"model": {"masses": [1] * n, "elements": el}, "force_node": 0, "response_node": n - 1,
                  "omega": {"from": 0.01, "to": 2, "points": 700}}))
PY
for k in murty resp; do
    route=/v1/lcp; [ $k = resp ] && route=/v1/response
    curl -s -m 20 -o "$SCRATCH/$k.out" -w '%{time_total}' --data-binary @"$SCRATCH/$k.json" "$URL_wall$route" \
        >"$SCRATCH/$k.time"
    echo "    $route answered after $(cat "$SCRATCH/$k.time") s"
    check "$route: 503 /problems/timeout" pyjson "$SCRATCH/$k.out" "d['status'] == 503 and d['type'] == '/problems/timeout'"
    check "...within 1 s + 1.5 s" below "$(cat "$SCRATCH/$k.time")" 2.5
done
python3 - >"$SCRATCH/lcs.json" <<'PY'
import json
m = 250  # an LCS whose algebraic part at t = 0 is Murty's LCP: the document's check leaves it undecided
D = [[1 if i == j else 1.5 if j < i else 0 for j in range(m)] for i in range(m)]
print(json.dumps({"model": {"lcs": {"A": [[-1]], "B": [[0] * m], "C": [[0]] * m, "D": D, "q": [-1] * m},
                            "laws": [{"law": "complementarity"}] * m},
                  "initial": {"x": [0]}, "solver": {"kind": "stick-slip", "dt": 0.01, "t_end": 0.05}}))
PY
curl -s -m 20 -o "$SCRATCH/lcs.out" -w '%{time_total}' -H 'Accept: application/x-ndjson' \
    --data-binary @"$SCRATCH/lcs.json" "$URL_wall/v1/simulate" >"$SCRATCH/lcs.time"
echo "    an LCS with Murty's 250 x 250 at t = 0: answered after $(cat "$SCRATCH/lcs.time") s"
check "simulate, an LCS whose t = 0 problem is Murty's: its stream ends with the wall limit's error line" \
    grep -q '"status":503.*wall-time limit' "$SCRATCH/lcs.out"
check "...within 1 s + 1.5 s (the document's check stops within its budget, the run on its hook)" \
    below "$(cat "$SCRATCH/lcs.time")" 2.5
check "no slot left taken" is "$(metric "$URL_wall" dashpot_workers_busy)" 0
stop_daemon wall
check "exit 0" is "$RC_wall" 0

finish
