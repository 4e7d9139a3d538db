# tests/lib/daemon.bash - shared by the shell tests of dashpotd: start a daemon on a free port, check and
# count results, clean up on any exit. Sourced, not run (the Makefile runs tests/*.sh only).
#
#   start_daemon NAME [FLAGS...]   starts $BUILD/dashpotd --port 0 FLAGS; sets PORT_NAME, URL_NAME, PID_NAME
#   stop_daemon NAME               SIGTERM, waits (bounded); sets RC_NAME to its exit status
#   check DESC CMD...              runs CMD; counts and prints "ok - DESC" or "not ok - DESC"
#   finish                         prints "N passed, M failed" and exits 1 if any failed
# Every wait is bounded; the EXIT trap kills whatever daemon is left and removes the scratch directory.
#
# DASHPOT_VALGRIND=1 runs every daemon under valgrind memcheck (leak check on exit; definite and indirect
# leaks and any memory error make it exit 99, so stop_daemon's RC_NAME is not 0 and the test says so, with
# valgrind's report). Waits for start-up are longer then.

set -uo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
BUILD=${BUILD:-build}
case $BUILD in /*) ;; *) BUILD=$ROOT/$BUILD ;; esac
DAEMON=$BUILD/dashpotd
SCRATCH=$(mktemp -d "${TMPDIR:-/tmp}/dashpot-test.XXXXXX")
PASSED=0
FAILED=0
DAEMON_PIDS=()

cleanup() {
    local p
    for p in "${DAEMON_PIDS[@]}"; do
        kill -KILL "$p" 2>/dev/null
    done
    rm -rf "$SCRATCH"
}
trap cleanup EXIT

VALGRIND=()
if [ "${DASHPOT_VALGRIND:-0}" = 1 ]; then
    command -v valgrind >/dev/null || { echo "not ok - DASHPOT_VALGRIND=1 but valgrind is not installed"; exit 1; }
    VALGRIND=(valgrind --quiet --leak-check=full --errors-for-leak-kinds=definite,indirect --error-exitcode=99)
fi

start_daemon() {
    local name=$1 log=$SCRATCH/$1.log i port= tries=100
    shift
    [ -x "$DAEMON" ] || { echo "not ok - $DAEMON not built"; FAILED=$((FAILED + 1)); return 1; }
    if [ ${#VALGRIND[@]} -gt 0 ]; then
        tries=600
        (cd "$ROOT" && exec "${VALGRIND[@]}" --log-file="$SCRATCH/$name.valgrind" "$DAEMON" --port 0 "$@") 2>"$log" &
    else
        (cd "$ROOT" && exec "$DAEMON" --port 0 "$@") 2>"$log" &
    fi
    local pid=$!
    DAEMON_PIDS+=("$pid")
    for i in $(seq $tries); do
        port=$(grep -o 'listening on http://[^ ]*' "$log" 2>/dev/null | grep -o '[0-9]*$')
        [ -n "$port" ] && break
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.1
    done
    if [ -z "$port" ]; then
        echo "not ok - start $name: no listening line in $((tries / 10)) s"; sed 's/^/    /' "$log"
        FAILED=$((FAILED + 1))
        return 1
    fi
    printf -v "PORT_$name" %s "$port"
    printf -v "URL_$name" %s "http://127.0.0.1:$port"
    printf -v "PID_$name" %s "$pid"
    printf -v "LOG_$name" %s "$log"
}

# Waits up to $2 seconds (default 20) for process $1 to exit; its status in WAIT_RC (124 on timeout).
wait_pid() {
    local pid=$1 limit=${2:-20} i
    for i in $(seq $((limit * 10))); do
        kill -0 "$pid" 2>/dev/null || { wait "$pid"; WAIT_RC=$?; return 0; }
        sleep 0.1
    done
    WAIT_RC=124
    return 1
}

# Stops daemon $1 with signal $3 (default TERM), waiting up to $2 seconds; its exit status in RC_$1.
stop_daemon() {
    local name=$1 pidvar=PID_$1
    kill -"${3:-TERM}" "${!pidvar}" 2>/dev/null
    wait_pid "${!pidvar}" "${2:-20}"
    printf -v "RC_$name" %s "$WAIT_RC"
    if [ ${#VALGRIND[@]} -gt 0 ]; then
        [ -s "$SCRATCH/$name.valgrind" ] && { echo "    valgrind ($name, exit $WAIT_RC):"; sed 's/^/    /' "$SCRATCH/$name.valgrind"; }
        check "valgrind memcheck, daemon '$name': no leak, no memory error (exit $WAIT_RC)" [ "$WAIT_RC" = 0 ]
    fi
}

check() {
    local desc=$1
    shift
    if "$@"; then
        PASSED=$((PASSED + 1))
        echo "ok - $desc"
    else
        FAILED=$((FAILED + 1))
        echo "not ok - $desc"
    fi
}

finish() {
    echo "$PASSED passed, $FAILED failed"
    [ "$FAILED" -eq 0 ]
    exit $?
}

# curl with a bound on time; -s, status code last on its own line via -w when asked.
hcurl() {
    curl -s --max-time "${CURL_TIME:-30}" "$@"
}
