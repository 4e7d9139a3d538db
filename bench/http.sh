#!/usr/bin/env bash
# bench/http.sh - dashpotd under load, each figure next to its peer on the same daemon, ratios printed:
#   1. requests/s of a small POST /v1/stability and of a 2-sample /v1/simulate (wrk, 32 connections, Lua
#      scripts) against GET /healthz;
#   2. NDJSON streaming, samples/s and MB/s (curl to /dev/null) against the same bytes served from a file
#      through the same chunked content-reader path (--bench-static);
#   3. dp_format_double against printf("%.17g") (bench/encode_bench.c).
# Goals (issue 3): small request >= 80% of /healthz; >= 5 M samples/s streamed; >= 50% of the static rate.
# Usage: BUILD=build bash bench/http.sh [SAMPLES] (default 4e6 samples; the file peer needs ~140 B each).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
samples=${1:-4000000}
secs=${WRK_SECONDS:-5}
tmp=$(mktemp -d)
pid=
cleanup() { [ -n "$pid" ] && kill -KILL "$pid" 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT
command -v wrk >/dev/null || { echo "http: wrk missing (apt-get install wrk)"; exit 1; }

mkdir -p "$build/bench"
cc -std=c17 -Wall -Wextra -Werror -O2 -g -Iinclude -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE \
  bench/encode_bench.c -o "$build/bench/encode_bench" "$build/libdashpot.a" -lm
"$build/bench/encode_bench"

(exec "$build/dashpotd" --port 0 --bench-static "$tmp/static.ndjson" --max-connections 1024) 2>"$tmp/log" &
pid=$!
for i in $(seq 100); do grep -qs listening "$tmp/log" && break; sleep 0.1; done
port=$(grep -o 'listening on http://[^ ]*' "$tmp/log" | grep -o '[0-9]*$')
url=http://127.0.0.1:$port

# ---- 1. small requests ----
cat >"$tmp/stability.lua" <<'LUA'
wrk.method = "POST"
wrk.body = '{"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]}}'
wrk.headers["Content-Type"] = "application/json"
LUA
cat >"$tmp/simulate.lua" <<'LUA'
wrk.method = "POST"
wrk.body = '{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.3}}, "solver": {"dt": 1, "t_end": 1}}'
wrk.headers["Content-Type"] = "application/json"
LUA
rate() { awk '/Requests\/sec/ { print $2 }'; }
wrk -t 2 -c 32 -d 1 "$url/healthz" >/dev/null # warm-up
health=$(wrk -t 2 -c 32 -d "$secs" "$url/healthz" | rate)
stab=$(wrk -t 2 -c 32 -d "$secs" -s "$tmp/stability.lua" "$url/v1/stability" | rate)
tiny=$(wrk -t 2 -c 32 -d "$secs" -s "$tmp/simulate.lua" "$url/v1/simulate" | rate)
status=$(curl -s -o /dev/null -w '%{http_code}' -d '{"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]}}' "$url/v1/stability")
[ "$status" = 200 ] || { echo "http: the stability request answered $status"; exit 1; }

# ---- 2. streaming: t_end = samples * dt, a sample every step ----
spec="{\"model\": {\"mass\": 1, \"spring\": {\"law\": \"linear\", \"k\": 1}, \"damper\": {\"law\": \"coulomb\", \"phi0\": 0.3}, \"forcing\": {\"kind\": \"harmonic\", \"amplitude\": 0.5, \"omega\": 1.3}}, \"initial\": {\"x\": 1, \"v\": 0}, \"solver\": {\"dt\": 1e-6, \"t_end\": $(awk -v n="$samples" 'BEGIN { print n * 1e-6 }')}}"
curl -s -H 'Accept: application/x-ndjson' --data-binary "$spec" "$url/v1/simulate" -o "$tmp/static.ndjson"
bytes=$(stat -c %s "$tmp/static.ndjson")
best() { # best of 3 wall times of a curl to /dev/null
    local b=1e9 t
    for i in 1 2 3; do
        t=$(curl -s -o /dev/null -w '%{time_total}' "$@")
        b=$(awk -v a="$b" -v c="$t" 'BEGIN { print (c < a) ? c : a }')
    done
    echo "$b"
}
t_stream=$(best -H 'Accept: application/x-ndjson' --data-binary "$spec" "$url/v1/simulate")
t_static=$(best "$url/bench/static")

awk -v h="$health" -v s="$stab" -v y="$tiny" -v n="$samples" -v b="$bytes" -v ts="$t_stream" -v tf="$t_static" 'BEGIN {
    printf "small requests, wrk 2 threads 32 connections, same daemon\n"
    printf "  GET /healthz                 %10.0f req/s\n", h
    printf "  POST /v1/stability (small)   %10.0f req/s   ratio %.2f (goal >= 0.80)\n", s, s / h
    printf "  POST /v1/simulate (2 samples)%10.0f req/s   ratio %.2f\n", y, y / h
    printf "NDJSON stream of %d samples (%.0f MB), curl to /dev/null, best of 3\n", n + 1, b / 1e6
    printf "  POST /v1/simulate            %6.3f s  %6.2f M samples/s  %7.1f MB/s   (goal >= 5 M samples/s)\n", ts, (n + 1) / ts / 1e6, b / ts / 1e6
    printf "  GET /bench/static same bytes %6.3f s  %6.2f M lines/s    %7.1f MB/s\n", tf, (n + 1) / tf / 1e6, b / tf / 1e6
    printf "  ratio stream/static %.2f (goal >= 0.50)\n", tf / ts
}'
kill -TERM "$pid"
wait "$pid"
pid=
