#!/usr/bin/env bash
# bench/sweep.sh - runs per second of one POST /v1/sweep against the same runs sent one POST /v1/simulate at a
# time (each with "output": {"samples": false, "events": false}, its summary only), on one daemon, and the
# ratio. The sweep saves a request, a parse of the answer and the samples' encoding per run, and computes the
# features besides; the lone requests save the sweep's every-step records. The sweep runs its runs in parallel on
# every solver slot free (the daemon's --threads, THREADS here, default one per CPU), the lone requests go one
# after another; so on n idle cores the wall ratio is up to n times the per-CPU one. Measured and printed, not
# enforced.
# Usage: BUILD=build [RUNS=200] [THREADS=n] bash bench/sweep.sh
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
runs=${RUNS:-200}
make -s BUILD="$build" "$build/dashpotd"
dir=$(mktemp -d)
log=$dir/daemon.log
"$build/dashpotd" --port 0 ${THREADS:+--threads "$THREADS"} 2>"$log" &
pid=$!
trap 'kill $pid 2>/dev/null; wait $pid 2>/dev/null; rm -rf "$dir"' EXIT
for _ in $(seq 100); do port=$(grep -o 'listening on http://[^ ]*' "$log" | grep -o '[0-9]*$' || true); [ -n "$port" ] && break; sleep 0.1; done
url=http://127.0.0.1:$port
python3 - "$url" "$runs" "$pid" <<'PY'
import json, os, sys, time, urllib.request
url, runs, pid = sys.argv[1], int(sys.argv[2]), sys.argv[3]
def cpu():  # the daemon's user + system seconds: the machine may be shared, wall time then says little
    f = open("/proc/%s/stat" % pid).read().rsplit(")", 1)[1].split()
    return (int(f[11]) + int(f[12])) / os.sysconf("SC_CLK_TCK")
base = {"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 0.1},
                  "forcing": {"kind": "harmonic", "amplitude": 1, "omega": 2}},
        "solver": {"dt": 0.01, "t_end": 100}}
omegas = [0.5 + 2.5 * i / (runs - 1) for i in range(runs)]
def post(path, doc):
    req = urllib.request.Request(url + path, json.dumps(doc).encode(), {"Content-Type": "application/json",
                                                                       "Accept": "application/x-ndjson"})
    with urllib.request.urlopen(req) as r:
        return r.read()
t, c = time.perf_counter(), cpu()
out = post("/v1/sweep", {"base": base, "vary": [{"pointer": "/model/forcing/omega", "values": omegas}],
                         "record": {"after": 50, "features": ["amplitude"]}})
sweep, sweep_cpu = runs / (time.perf_counter() - t), runs / max(cpu() - c, 1e-9)
assert out.count(b'"type":"run"') == runs
t, c = time.perf_counter(), cpu()
for w in omegas:
    doc = json.loads(json.dumps(base))
    doc["model"]["forcing"]["omega"] = w
    doc["output"] = {"samples": False, "events": False}
    post("/v1/simulate", doc)
lone, lone_cpu = runs / (time.perf_counter() - t), runs / max(cpu() - c, 1e-9)
print("sweep of %d runs (10^4 steps each, in parallel): %.0f runs/s wall, %.0f per daemon CPU second" % (runs, sweep, sweep_cpu))
print("one simulate request at a time:       %.0f runs/s wall, %.0f per daemon CPU second" % (lone, lone_cpu))
print("ratio sweep / one at a time: %.2f wall, %.2f CPU" % (sweep / lone, sweep_cpu / lone_cpu))
PY
