#!/usr/bin/env bash
# tests/test_framing.sh - dashpotd's HTTP/1.1 framing (RFC 9112 sections 3.2 and 6), sent raw over a socket
# (tests/lib/rawhttp.py) with a valid request pipelined behind each: two different Content-Length values,
# Content-Length with Transfer-Encoding, a coding other than chunked, a missing or repeated Host on HTTP/1.1
# are each answered 400 and the connection is closed, the pipelined request never served. Valid pipelining
# and HTTP/1.0 without Host still work. Env BUILD (default build). Prints "N passed, M failed".
source "$(dirname "$0")/lib/daemon.bash"
RAW=$ROOT/tests/lib/rawhttp.py

start_daemon frame || finish
python3 "$RAW" framing "$PORT_frame" >"$SCRATCH/framing" 2>&1
sed 's/^/    /' "$SCRATCH/framing"
result() { awk -v n="$1" '$1 == n { print $2, $3 }' "$SCRATCH/framing"; }
is() { [ "$1" = "$2" ] || { echo "    got '$1', expected '$2'"; return 1; }; }
for fault in two-content-lengths content-length-and-chunked transfer-encoding-gzip transfer-encoding-gzip-chunked \
    no-host two-hosts; do
    check "$fault: 400, connection closed, the pipelined request not served" is "$(result "$fault")" "400 yes"
done
check "two pipelined GETs are both served on an open connection" is "$(result get-pipelined)" "200,200 no"
check "HTTP/1.0 without Host is served" is "$(result http-1.0-without-host | cut -c1-3)" 200

hcurl -o "$SCRATCH/body" -w '%{http_code}' -H 'Transfer-Encoding: gzip' --data-binary '{}' \
    "$URL_frame/v1/simulate" >"$SCRATCH/code"
check "a framing fault is a problem document /problems/bad-framing naming it" python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
sys.exit(0 if d["status"] == 400 and d["type"] == "/problems/bad-framing" and "Transfer-Encoding" in d["detail"] else 1)' \
    "$SCRATCH/body"
check "...with status 400" is "$(cat "$SCRATCH/code")" 400
hcurl -o /dev/null -w '%{http_code}' "$URL_frame/healthz" >"$SCRATCH/code"
check "the daemon serves on after the faults" is "$(cat "$SCRATCH/code")" 200
stop_daemon frame
check "exit 0" is "$RC_frame" 0
finish
