#!/usr/bin/env bash
# tests/robustness/load.sh - dashpotd under a mixed load: wrk (tests/robustness/load.lua) with 64
# connections for 30 s sending valid, invalid and streaming requests, while VmRSS is sampled from /proc.
# Passes when every status is one its request can get (wrk's count and /metrics by route both say so),
# nothing is 5xx, no socket error or timeout occurs, memory does not creep (mean RSS of the last third of
# the run within 10% of the first third's), no run is left in flight, and SIGTERM then exits 0.
# Env: BUILD (default build), LOAD_SECONDS (30), LOAD_CONNECTIONS (64). Prints "N passed, M failed".
source "$(dirname "$0")/../lib/daemon.bash"

DURATION=${LOAD_SECONDS:-30}
CONNS=${LOAD_CONNECTIONS:-64}
LUA=$(dirname "$0")/load.lua
command -v wrk >/dev/null || { echo "not ok - wrk is not installed (apt-get install wrk)"; FAILED=1; finish; }
metric() { hcurl "$1/metrics" | awk -v n="$2" '$1 == n { print $2 }'; }
is() { [ "$1" = "$2" ] || { echo "    got '$1', expected '$2'"; return 1; }; }

start_daemon load --max-connections 256 || finish
U=$URL_load
PID=$PID_load
rss() { awk '/^VmRSS:/ { print $2 }' "/proc/$PID/status"; }

# Warm-up: the allocator's arenas and the connection pools reach their working size.
timeout 60 wrk -t 2 -c "$CONNS" -d 3s --timeout 10s -s "$LUA" "$U" >"$SCRATCH/warm.out" 2>&1
warm_requests=$(awk '$1 == "requests" { print $2 }' "$SCRATCH/warm.out")
echo "    warm-up: ${warm_requests:-?} requests, RSS $(rss) kB"

# VmRSS every 0.25 s while wrk runs.
(while kill -0 "$PID" 2>/dev/null; do rss; sleep 0.25; done) >"$SCRATCH/rss" &
SAMPLER=$!
timeout $((DURATION + 60)) wrk -t 2 -c "$CONNS" -d "${DURATION}s" --timeout 10s -s "$LUA" "$U" >"$SCRATCH/wrk.out" 2>&1
kill "$SAMPLER" 2>/dev/null
wait "$SAMPLER" 2>/dev/null
sed -n '/Requests\/sec/p; /^status /p; /^requests /p; /^errors /p; /^latency /p' "$SCRATCH/wrk.out" | sed 's/^/    /'

requests=$(awk '$1 == "requests" { print $2 }' "$SCRATCH/wrk.out")
check "wrk ran ${DURATION} s with $CONNS connections and served requests (${requests:-0})" [ "${requests:-0}" -gt 1000 ]
check "every status is one of 200 400 404 405 406 422 (wrk)" \
    awk '$1 == "status" && $2 !~ /^(200|400|404|405|406|422)$/ { bad = 1; print "    unexpected: " $0 } END { exit bad }' \
    "$SCRATCH/wrk.out"
check "no socket error, no timeout (wrk)" grep -q '^errors connect 0 read 0 write 0 status [0-9]* timeout 0$' "$SCRATCH/wrk.out"
check "the valid requests were answered 200 (wrk)" awk '$1 == "status" && $2 == 200 && $3 > 0 { ok = 1 } END { exit !ok }' \
    "$SCRATCH/wrk.out"

# Runs the load cut off when wrk stopped end soon; then the daemon's own counts.
for i in $(seq 50); do [ "$(metric "$U" dashpot_runs_in_flight)" = 0 ] && break; sleep 0.1; done
check "no run left in flight after the load" is "$(metric "$U" dashpot_runs_in_flight)" 0
hcurl "$U/metrics" >"$SCRATCH/metrics"
check "/metrics: each route answered only what its requests can get, nothing 5xx" python3 - "$SCRATCH/metrics" \
    "$requests" "${warm_requests:-0}" "$CONNS" <<'PY'
import re, sys
allowed = {"/healthz": {"200"}, "/v1/simulate": {"200", "400", "406", "422"}, "/v1/stability": {"200", "405"},
           "unmatched": {"404"}, "/metrics": {"200"}}
text = open(sys.argv[1]).read()
total, ok, cut = 0, True, 0
for route, status, n in re.findall(r'^dashpot_http_requests_total\{route="([^"]+)",status="([^"]+)"\} (\d+)$', text, re.M):
    if status == "other" and route != "/metrics":
        # no status at all: a request whose client left before its answer (wrk stopping mid-request),
        # counted below with the allowance for requests cut off when wrk stopped
        cut += int(n)
        total += int(n)
        continue
    if status not in allowed.get(route, set()):
        print(f"    unexpected: {route} {status} x {n}")
        ok = False
    if route != "/metrics":
        total += int(n)
failed = int(re.search(r"^dashpot_runs_failed_total (\d+)$", text, re.M).group(1))
served = int(sys.argv[2]) + int(sys.argv[3])
# wrk counts the requests it completed; the daemon also those cut off when wrk stopped (one per connection
# at most, twice: warm-up and load).
print(f"    daemon answered {total} requests, wrk completed {served}; runs failed {failed}")
print(f"    answered without a status (client gone mid-request): {cut}")
ok = ok and failed == 0 and served <= total <= served + 2 * int(sys.argv[4]) and cut <= 2 * int(sys.argv[4])
sys.exit(0 if ok else 1)
PY

python3 - "$SCRATCH/rss" >"$SCRATCH/rss.out" <<'PY'
import sys
v = [int(l) for l in open(sys.argv[1]) if l.strip().isdigit()]
k = max(1, len(v) // 3)
first, last = sum(v[:k]) / k, sum(v[-k:]) / k
print(f"{len(v)} {first:.0f} {last:.0f} {max(v)} {100 * (last / first - 1):.1f}")
PY
read -r nrss first last peak growth <"$SCRATCH/rss.out"
echo "    VmRSS: $nrss samples; first third ${first} kB, last third ${last} kB ($growth%), peak ${peak} kB"
check "RSS of the last third within 10% of the first third's" python3 -c "import sys; sys.exit(0 if $last <= 1.10 * $first else 1)"

stop_daemon load 30
check "SIGTERM after the load: exit 0" is "$RC_load" 0
finish
