#!/usr/bin/env bash
# tests/robustness/faults.sh - dashpotd under injected faults (the clients are tests/robustness/faults.py):
#   1. 1000 clients hanging up at random points of streams (in the head, in the body, right after the
#      request, mid-stream, with FIN or RST): then no run is in flight, /metrics counts every run as
#      cancelled, the daemon serves normally and its RSS is back near its baseline;
#   2. slowloris: 20 clients sending their head a byte at a time are closed at --timeout, others are served;
#   3. bodies over --body-limit (413), JSON nested deep (400), huge numbers (422 naming the field), NaN and
#      Infinity literals (400), a diverging solution (a clear error line, never NaN or Infinity);
#   4. SIGTERM with streams and small requests in flight: the streams finish whole, exit 0.
# Env: BUILD (default build), FAULT_CLIENTS (1000). Prints "N passed, M failed"; exit 1 on any failure.
source "$(dirname "$0")/../lib/daemon.bash"
FAULTS=$(dirname "$0")/faults.py
CLIENTS=${FAULT_CLIENTS:-1000}

# faults SUBCOMMAND ARGS...: runs faults.py, adds its counts to ours.
faults() {
    timeout 300 python3 "$FAULTS" "$@" | tee "$SCRATCH/faults.out" | grep -v '^COUNTS '
    local p f
    read -r _ p f < <(grep '^COUNTS ' "$SCRATCH/faults.out")
    [ -n "${p:-}" ] || { echo "not ok - faults.py $1 did not finish"; FAILED=$((FAILED + 1)); return; }
    PASSED=$((PASSED + p))
    FAILED=$((FAILED + f))
}

echo "# 1. $CLIENTS clients hanging up at random points"
start_daemon hangup || finish
faults disconnects "$URL_hangup" "$PID_hangup" "$CLIENTS" 50
stop_daemon hangup
check "exit 0 after the hang-ups" [ "$RC_hangup" = 0 ]

echo "# 2. slowloris"
start_daemon slow --timeout 2 || finish
faults slowloris "$URL_slow" 20 2
check "the log says which connections the deadline closed" grep -q 'connection(s) whose request did not arrive within 2 s' "$LOG_slow"
stop_daemon slow
check "exit 0 after slowloris" [ "$RC_slow" = 0 ]

echo "# 3. limits and hostile bodies"
start_daemon limits || finish
faults limits "$URL_limits"
stop_daemon limits
check "exit 0 after the hostile bodies" [ "$RC_limits" = 0 ]

echo "# 4. SIGTERM under load"
start_daemon drain --shutdown-grace 20 || finish
t0=$(date +%s.%N)
faults sigterm "$URL_drain" "$PID_drain" 8
wait_pid "$PID_drain" 30
t1=$(date +%s.%N)
echo "    the daemon exited $(python3 -c "print(f'{$t1 - $t0:.2f}')") s after the load began"
check "SIGTERM under load: the daemon exits 0 after the drain" [ "$WAIT_RC" = 0 ]
check "the log shows the drain and the stop" grep -q 'received SIGTERM: draining' "$LOG_drain"
check "no stream had to be cut (none ended by the grace period)" bash -c "! grep -q 'grace period over' '$LOG_drain'"
finish
