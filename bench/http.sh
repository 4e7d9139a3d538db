#!/usr/bin/env bash
# bench/http.sh - dashpotd under load, each figure next to its peer on the same daemon, ratios printed:
#   1. requests/s of a small POST /v1/stability and of a 2-sample /v1/simulate (wrk, 32 connections, Lua
#      scripts) against GET /healthz;
#   2. NDJSON streaming, samples/s and MB/s (curl to /dev/null) against the same bytes served from a file
#      through the same chunked content-reader path (--bench-static);
#   3. dp_format_double against printf("%.17g") (bench/encode_bench.c).
# Goals: small request >= 80% of /healthz; >= 5 M samples/s streamed; >= 50% of the static rate.
# Requests/s swing with whatever else the machine runs (wrk and the daemon share its cores), so part 1 also
# prints the steadier CPU time per request: the daemon's from /proc/PID/stat, wrk's from `times`, and the
# ratio their sums imply when the two saturate the same cores.
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
ticks() { awk '{ print $14 + $15 }' "/proc/$pid/stat"; } # the daemon's user + system clock ticks
hz=$(getconf CLK_TCK)
# small NAME WRK-ARGS...: one wrk run; prints "req/s daemon-us wrk-us" (CPU microseconds per request).
small() {
    local name=$1 t0 t1
    shift
    t0=$(ticks)
    (wrk -t 2 -c 32 -d "$secs" "$@" >"$tmp/$name.out"; times >"$tmp/$name.times") # times: wrk's CPU, line 2
    t1=$(ticks)
    awk -v d=$((t1 - t0)) -v hz="$hz" -v f="$tmp/$name.times" '
        function sec(t) { split(t, p, "m"); return p[1] * 60 + p[2] }
        /requests in/ { n = $1 } /Requests\/sec/ { r = $2 }
        END { getline l < f; getline l < f; split(l, w, " ")
              printf "%s %.2f %.2f\n", r, d / hz / n * 1e6, (sec(w[1]) + sec(w[2])) / n * 1e6 }' "$tmp/$name.out"
}
wrk -t 2 -c 32 -d 1 "$url/healthz" >/dev/null # warm-up
read -r health health_d health_w < <(small healthz "$url/healthz")
read -r stab stab_d stab_w < <(small stability -s "$tmp/stability.lua" "$url/v1/stability")
read -r tiny tiny_d tiny_w < <(small simulate -s "$tmp/simulate.lua" "$url/v1/simulate")
status=$(curl -s -o /dev/null -w '%{http_code}' -d '{"mass": 1, "law": {"lambda": [1, 0.5], "mu": [1, 1]}}' "$url/v1/stability")
[ "$status" = 200 ] || { echo "http: the stability request answered $status"; exit 1; }

# ---- 2. streaming: t_end = samples * dt, a sample every step ----
spec="{\"model\": {\"mass\": 1, \"spring\": {\"law\": \"linear\", \"k\": 1}, \"damper\": {\"law\": \"coulomb\", \"phi0\": 0.3}, \"forcing\": {\"kind\": \"harmonic\", \"amplitude\": 0.5, \"omega\": 1.3}}, \"initial\": {\"x\": 1, \"v\": 0}, \"solver\": {\"dt\": 1e-6, \"t_end\": $(awk -v n="$samples" 'BEGIN { print n * 1e-6 }'), \"theta\": 1}, \"output\": {\"every\": 1}}"
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

awk -v h="$health" -v s="$stab" -v y="$tiny" -v n="$samples" -v b="$bytes" -v ts="$t_stream" -v tf="$t_static" \
    -v hd="$health_d" -v hw="$health_w" -v sd="$stab_d" -v sw="$stab_w" -v yd="$tiny_d" -v yw="$tiny_w" 'BEGIN {
    printf "small requests, wrk 2 threads 32 connections, same daemon; CPU us per request (daemon + wrk)\n"
    printf "  GET /healthz                 %10.0f req/s                %5.1f + %4.1f us\n", h, hd, hw
    printf "  POST /v1/stability (small)   %10.0f req/s   ratio %.2f   %5.1f + %4.1f us   by CPU %.2f (goal >= 0.80)\n", s, s / h, sd, sw, (hd + hw) / (sd + sw)
    printf "  POST /v1/simulate (2 samples)%10.0f req/s   ratio %.2f   %5.1f + %4.1f us   by CPU %.2f\n", y, y / h, yd, yw, (hd + hw) / (yd + yw)
    printf "NDJSON stream of %d samples (%.0f MB), curl to /dev/null, best of 3\n", n + 1, b / 1e6
    printf "  POST /v1/simulate            %6.3f s  %6.2f M samples/s  %7.1f MB/s   (goal >= 5 M samples/s)\n", ts, (n + 1) / ts / 1e6, b / ts / 1e6
    printf "  GET /bench/static same bytes %6.3f s  %6.2f M lines/s    %7.1f MB/s\n", tf, (n + 1) / tf / 1e6, b / tf / 1e6
    printf "  ratio stream/static %.2f (goal >= 0.50)\n", tf / ts
}'
kill -TERM "$pid"
wait "$pid"
pid=
