#!/usr/bin/env bash
# tests/robustness/stop.sh - runs stop when told, against the issue's slow spec (generated here:
# 10^4-point graph spring and damper, rational relaxation, belt, 10^4-point table load, 10^8 steps of 10^-7,
# one sample in 10^15, i.e. one block for the whole run), on a daemon with --threads 2:
#   1. two such runs with --max-wall 2: each stream ends with its wall-time error line within 2 s + 0.5 s;
#      meanwhile /healthz answers within 100 ms every time; with --threads 1 and one such run /readyz says
#      503 /problems/busy (two runs on --threads 2 may share one pool thread, leaving a worker free);
#   2. a client that hangs up mid-run: its run is gone from /metrics within 0.5 s, counted as cancelled;
#   3. SIGTERM with two such runs in flight and --shutdown-grace 1: exit 0 within grace + 1 s;
#   4. a burst of 80 connections against --max-connections 8: exactly 8 served, 72 refused with 503.
# Env BUILD (default build). Prints "N passed, M failed"; exit 1 on any failure.
source "$(dirname "$0")/../lib/daemon.bash"
RAW=$ROOT/tests/lib/rawhttp.py
SLOW=$SCRATCH/slow.json
python3 "$RAW" slowspec 10000 10 >"$SLOW"
echo "    the slow spec: $(wc -c <"$SLOW") bytes"
metric() { hcurl "$1/metrics" | awk -v n="$2" '$1 == n { print $2 }'; }
is() { [ "$1" = "$2" ] || { echo "    got '$1', expected '$2'"; return 1; }; }
below() { python3 -c "import sys; sys.exit(0 if $1 < $2 else 1)" || { echo "    $1 is not below $2"; return 1; }; }
slow_run() { # slow_run URL OUT: streams the slow spec into OUT, its wall time into OUT.time
    curl -s -m 20 -H 'Accept: application/x-ndjson' -H 'Expect:' --data-binary @"$SLOW" -o "$2" \
        -w '%{time_total}\n' "$1/v1/simulate" >"$2.time"
}
# wait_busy URL N: until N workers compute (at most 5 s)
wait_busy() { local i; for i in $(seq 100); do [ "$(metric "$1" dashpot_workers_busy)" = "$2" ] && return 0; sleep 0.05; done; return 1; }

echo "# 1. --max-wall inside one block; /healthz and /readyz meanwhile"
start_daemon wall --threads 2 --max-wall 2 || finish
U=$URL_wall
slow_run "$U" "$SCRATCH/a" & A=$!
slow_run "$U" "$SCRATCH/b" & B=$!
worst=0
while kill -0 "$A" 2>/dev/null || kill -0 "$B" 2>/dev/null; do
    t=$(hcurl -o /dev/null -w '%{time_total}' "$U/healthz")
    worst=$(python3 -c "print(max($worst, $t))")
    sleep 0.1
done
wait "$A" "$B"
echo "    runs took $(cat "$SCRATCH/a.time") s and $(cat "$SCRATCH/b.time") s; slowest /healthz ${worst} s"
check "/healthz answered within 100 ms throughout" below "$worst" 0.1
for r in a b; do
    check "run $r ended with the wall-time error line" python3 -c '
import json, sys
d = json.loads(open(sys.argv[1]).read().splitlines()[-1])
sys.exit(0 if d["type"] == "error" and "wall-time limit of 2 s" in d["detail"] else 1)' "$SCRATCH/$r"
    check "run $r ended within 2 s + 0.5 s" below "$(cat "$SCRATCH/$r.time")" 2.5
done
stop_daemon wall
check "exit 0" is "$RC_wall" 0

echo "# 1b. /readyz while no worker is free (--threads 1: the one solver slot taken)"
start_daemon ready --threads 1 --max-wall 2 || finish
slow_run "$URL_ready" "$SCRATCH/r" & R=$!
check "the run computes (dashpot_workers_busy 1)" wait_busy "$URL_ready" 1
hcurl -o "$SCRATCH/ready" -w '%{http_code}' "$URL_ready/readyz" >"$SCRATCH/ready.code"
check "/readyz says 503 /problems/busy" python3 -c '
import json, sys
d = json.load(open(sys.argv[1])); sys.exit(0 if d["status"] == 503 and d["type"] == "/problems/busy" else 1)' "$SCRATCH/ready"
check "...while /healthz answers within 100 ms" below "$(hcurl -o /dev/null -w '%{time_total}' "$URL_ready/healthz")" 0.1
wait "$R"
check "/readyz is 200 again once the run is over" is "$(hcurl -o /dev/null -w '%{http_code}' "$URL_ready/readyz")" 200
stop_daemon ready
check "exit 0" is "$RC_ready" 0

echo "# 2. a hang-up mid-run frees the worker"
start_daemon gone --threads 2 --max-wall 60 || finish
U=$URL_gone
curl -s -m 1.5 -H 'Expect:' --data-binary @"$SLOW" -o /dev/null "$U/v1/simulate"
t0=$(date +%s.%N)
for _ in $(seq 100); do [ "$(metric "$U" dashpot_runs_in_flight)" = 0 ] && break; sleep 0.01; done
t1=$(date +%s.%N)
freed=$(python3 -c "print(round($t1 - $t0, 3))")
echo "    the run left /metrics ${freed} s after the client hung up"
check "the run is gone from /metrics within 0.5 s" below "$freed" 0.5
check "...counted as cancelled" is "$(metric "$U" dashpot_runs_cancelled_total)" 1
check "...and the worker is free (dashpot_workers_busy 0)" is "$(metric "$U" dashpot_workers_busy)" 0
stop_daemon gone
check "exit 0" is "$RC_gone" 0

echo "# 3. SIGTERM with such runs in flight"
start_daemon term --threads 2 --max-wall 60 --shutdown-grace 1 || finish
slow_run "$URL_term" "$SCRATCH/c" & C=$!
slow_run "$URL_term" "$SCRATCH/d" & D=$!
check "both runs compute" wait_busy "$URL_term" 2
t0=$(date +%s.%N)
stop_daemon term 10
t1=$(date +%s.%N)
took=$(python3 -c "print(round($t1 - $t0, 3))")
wait "$C" "$D"
echo "    exited ${took} s after SIGTERM"
check "SIGTERM: exit 0" is "$RC_term" 0
check "...within grace + 1 s" below "$took" 2
check "...and each stream ended with an error line" bash -c "tail -1 '$SCRATCH/c' | grep -q 'shutting down' && tail -1 '$SCRATCH/d' | grep -q 'shutting down'"

echo "# 4. a burst of 80 connections against --max-connections 8"
start_daemon burst --max-connections 8 || finish
read -r served refused other < <(python3 "$RAW" burst "$PORT_burst" 80)
echo "    served $served, refused $refused, other $other"
check "exactly 8 served, 72 refused" is "$served $refused $other" "8 72 0"
stop_daemon burst
check "exit 0" is "$RC_burst" 0
finish
