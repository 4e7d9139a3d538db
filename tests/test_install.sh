#!/usr/bin/env bash
# tests/test_install.sh - `make install` into a scratch DESTDIR, then what an installed dashpot must do: the
# files are in place; a C program builds and runs against them through `pkg-config --cflags --libs dashpot`;
# the installed dashpotd, started from another directory with no flag and no environment, finds its OpenAPI
# document and web page under PREFIX/share/dashpot by itself; it runs as the Deployment's non-root user with only the environment the manifests give
# it (deploy/kubernetes), answers the smoke tests, passes the Dockerfile's HEALTHCHECK command, serves the
# sweep Job's script, and exits 0 on SIGTERM; `make uninstall` leaves no file behind. Every wait is bounded;
# the scratch tree and the daemon go away on any exit (tests/lib/daemon.bash).
BUILD_ARG=${BUILD:-build}
source "$(dirname "$0")/lib/daemon.bash"
cd "$ROOT" || exit 1
# The daemon runs as another user and must reach its files through the scratch directory (mktemp: 0700).
chmod 755 "$SCRATCH"
dest=$SCRATCH/root
prefix=/usr/local
p=$dest$prefix
# The install goes through the Makefile as a user would type it, for the build this test was given; a make
# calling this test must not hand its flags or jobserver down.
san=
[ "$(basename "$BUILD_ARG")" = build-san ] && san=1
make_() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make --no-print-directory BUILD="$BUILD_ARG" ${san:+SAN=1} "$@"; }
manifest() { python3 tests/lib/manifests.py "$@"; }

# ---- the files --------------------------------------------------------------------------------------------
# show FILE: its lines indented, after a failed check that it explains.
show() { sed 's/^/    /' "$1"; }
# The port a daemon logging to $1 listens on, once it says so (up to 20 s; empty if process $2 dies first).
listening_port() {
    local port=
    for _ in $(seq 200); do
        port=$(grep -o 'listening on http://127.0.0.1:[0-9]*' "$1" 2>/dev/null | grep -o '[0-9]*$')
        [ -n "$port" ] && break
        kill -0 "$2" 2>/dev/null || break
        sleep 0.1
    done
    echo "$port"
}
make_ install DESTDIR="$dest" PREFIX="$prefix" > "$SCRATCH/install.log" 2>&1
rc=$?
check "make install DESTDIR=... PREFIX=$prefix" test $rc -eq 0
[ $rc -eq 0 ] || show "$SCRATCH/install.log"
mode() { test "$(stat -c %a "$1" 2>/dev/null)" = "$2"; }
check "bin/dashpotd installed, mode 755" mode "$p/bin/dashpotd" 755
check "bin/dashpot installed, mode 755" mode "$p/bin/dashpot" 755
check "lib/libdashpot.a installed, mode 644" mode "$p/lib/libdashpot.a" 644
check "lib/pkgconfig/dashpot.pc installed, mode 644" mode "$p/lib/pkgconfig/dashpot.pc" 644
check "every public header installed under include/dashpot" \
    test "$(cd include/dashpot && ls)" = "$(cd "$p/include/dashpot" 2>/dev/null && ls)"
check "share/dashpot/openapi.yaml is api/openapi.yaml" cmp -s api/openapi.yaml "$p/share/dashpot/openapi.yaml"
# The browser page: every plainly named file of web/ (none while there is no web/).
check "share/dashpot/web holds the files of web/" \
    test "$(find web -maxdepth 1 -type f ! -name '.*' -printf '%f\n' 2>/dev/null | sort)" = \
    "$(find "$p/share/dashpot/web" -maxdepth 1 -type f -printf '%f\n' | sort)"
check "nothing installed outside PREFIX" test "$(ls "$dest")" = usr -a "$(ls "$dest/usr")" = local
check "the .pc names the final prefix, not the DESTDIR" grep -qx "prefix=$prefix" "$p/lib/pkgconfig/dashpot.pc"

# ---- a program against the installed library -----------------------------------------------------------------
pc() { PKG_CONFIG_PATH=$p/lib/pkgconfig PKG_CONFIG_SYSROOT_DIR=$dest pkg-config "$@"; }
version=$(sed -n 's/^#define DP_VERSION "\(.*\)"$/\1/p' include/dashpot/json.h)
check "pkg-config --modversion dashpot is $version" test "$(pc --modversion dashpot)" = "$version"
flags=$(pc --cflags --libs dashpot)
check "pkg-config --cflags --libs dashpot: staged include and lib dirs, -ldashpot" \
    grep -q -- "-I$p/include .*-L$p/lib -ldashpot" <<< "$flags"
# Decay of m x'' + x + F_c = 0 with phi0 = 1 from x = 4.5 at rest: it sticks at x = 0.5 after t = 2 pi
# (Babováková 2012 (4.14); README "A first run"). Built in the scratch directory, so only the installed headers exist.
cat > "$SCRATCH/tiny.c" <<'C'
#include <stdio.h>
#include <string.h>
#include <dashpot/json.h>
#include <dashpot/run.h>

int main(void)
{
    const char *text = "{\"model\": {\"mass\": 1, \"spring\": {\"law\": \"linear\", \"k\": 1},"
                       " \"damper\": {\"law\": \"coulomb\", \"phi0\": 1}}, \"initial\": {\"x\": 4.5, \"v\": 0},"
                       " \"solver\": {\"kind\": \"stick-slip\", \"dt\": 0.001, \"t_end\": 10, \"theta\": 0.5}}";
    dp_spec spec;
    dp_errors errs;
    dp_spec_init(&spec);
    dp_errors_init(&errs);
    int status = dp_spec_parse(text, strlen(text), 0, &spec, &errs);
    dp_run *run = status == DP_OK ? dp_run_alloc(&spec, 0, &errs, &status) : NULL;
    dp_spec_clear(&spec);
    if (run == NULL) {
        fprintf(stderr, "tiny: %s\n", dp_strerror(status));
        return 1;
    }
    dp_record buf[256];
    size_t n;
    while ((status = dp_run_next(run, buf, 256, &n)) == DP_MORE)
        ;
    if (status == DP_DONE)
        printf("%s %.9f %s\n", DP_VERSION, dp_run_summary(run)->final.x,
               dp_run_summary(run)->final.phase == DP_PHASE_STICK ? "stick" : "slip");
    dp_run_free(run);
    return status == DP_DONE ? 0 : 1;
}
C
# shellcheck disable=SC2086 # $flags is a list of words
(cd "$SCRATCH" && cc -std=c17 -Wall -Wextra -Werror ${san:+-fsanitize=address,undefined} tiny.c -o tiny $flags) \
    > "$SCRATCH/cc.log" 2>&1
rc=$?
check "a C program compiles and links with pkg-config --cflags --libs dashpot" test $rc -eq 0
[ $rc -eq 0 ] || show "$SCRATCH/cc.log"
check "it runs against libdashpot: rests at x = 0.5, sticking" \
    test "$(timeout 30 "$SCRATCH/tiny" 2>&1)" = "$version 0.500000000 stick"

# ---- the installed daemon with no flag and no environment, from another directory ------------------------
# The defaults (api/openapi.yaml, web) are source-tree paths; an installed binary finds the files beside its
# own directory, in ../share/dashpot, wherever the prefix is (here under the DESTDIR it was staged in).
mkdir -p "$SCRATCH/elsewhere"
bare=$SCRATCH/bare.log
env -i -C "$SCRATCH/elsewhere" "$p/bin/dashpotd" --port 0 2> "$bare" &
bpid=$!
DAEMON_PIDS+=("$bpid")
bport=$(listening_port "$bare" "$bpid")
check "the installed dashpotd starts with no flag and no environment, from another directory" test -n "$bport"
[ -n "$bport" ] || show "$bare"
check "its start-up log names the installed OpenAPI document" \
    grep -q "serving the OpenAPI document from $p/bin/../share/dashpot/openapi.yaml\$" "$bare"
check "its start-up log names the installed web directory" \
    grep -q "serving [0-9]* web files* from $p/bin/../share/dashpot/web\$" "$bare"
check "GET /openapi.yaml is 200, the installed api/openapi.yaml" \
    bash -c "[ \"\$(curl -s --max-time 10 -o '$SCRATCH/bare-openapi' -w '%{http_code}' \
              'http://127.0.0.1:$bport/openapi.yaml')\" = 200 ] && cmp -s '$SCRATCH/bare-openapi' api/openapi.yaml"
if [ -f web/index.html ]; then
    check "GET / is 200, the installed web/index.html" \
        bash -c "[ \"\$(curl -s --max-time 10 -o '$SCRATCH/bare-index' -w '%{http_code}' 'http://127.0.0.1:$bport/')\" = 200 ] &&
                 cmp -s '$SCRATCH/bare-index' web/index.html"
fi
kill -TERM "$bpid"
wait_pid "$bpid" 20
check "SIGTERM: it exits 0" test "$WAIT_RC" -eq 0

# ---- the installed daemon, as Kubernetes would start it ---------------------------------------------------------
# The environment is exactly the Deployment's (ConfigMap through envFrom, env, DASHPOT_THREADS from the CPU
# limit), with three changes a test on a shared machine needs: an ephemeral port instead of 8080, loopback
# instead of every interface, and paths under PREFIX found under the DESTDIR they are staged in.
mapfile -d '' menv < <(manifest env)
check "the manifests give dashpotd an environment" test "${#menv[@]}" -gt 0
denv=()
for kv in "${menv[@]}"; do
    case $kv in
        DASHPOT_PORT=*) kv=DASHPOT_PORT=0 ;;
        DASHPOT_BIND=*) kv=DASHPOT_BIND=127.0.0.1 ;;
        *=$prefix/*) kv=${kv%%=*}=$dest${kv#*=} ;;
    esac
    denv+=("$kv")
done
read -r uid gid < <(manifest user)
check "the Deployment names a non-root uid and gid ($uid:$gid)" test "${uid:-0}" -gt 0 -a "${gid:-0}" -gt 0
log=$SCRATCH/dashpotd.log
# setpriv and env exec in turn, so $! is the daemon itself; no capabilities, no new privileges, cwd /.
setpriv --reuid="$uid" --regid="$gid" --clear-groups --inh-caps=-all --no-new-privs \
    env -i -C / "${denv[@]}" "$p/bin/dashpotd" 2> "$log" &
pid=$!
DAEMON_PIDS+=("$pid")
port=$(listening_port "$log" "$pid")
check "the installed dashpotd starts with the manifests' environment (listening line within 20 s)" test -n "$port"
[ -n "$port" ] || { show "$log"; finish; }
url=http://127.0.0.1:$port
check "the process is the installed binary" test "$(readlink "/proc/$pid/exe")" = "$p/bin/dashpotd"
check "it runs as uid $uid (real, effective, saved, filesystem)" \
    grep -Eq "^Uid:\s+$uid\s+$uid\s+$uid\s+$uid$" "/proc/$pid/status"
check "it runs as gid $gid (real, effective, saved, filesystem)" \
    grep -Eq "^Gid:\s+$gid\s+$gid\s+$gid\s+$gid$" "/proc/$pid/status"
check "with no supplementary groups" test -z "$(sed -n 's/^Groups:\s*//p' "/proc/$pid/status")"
threads=$(printf '%s\n' "${denv[@]}" | sed -n 's/^DASHPOT_THREADS=//p')
check "start-up line shows the manifests' settings (threads $threads, max-steps 1e+08)" \
    grep -q "threads $threads, max-connections 256, max-steps 1e+08, max-wall 120s, body-limit 1048576" "$log"

code() { hcurl -o "$SCRATCH/body" -w '%{http_code} %{content_type}' "$@"; }
# The Deployment's probes, by the paths it names.
while read -r probe path; do
    check "$probe: GET $path is 200" test "$(code "$url$path" | cut -d' ' -f1)" = 200
done < <(manifest probes)
check "the manifests probe /readyz and /healthz" \
    test "$(manifest probes | cut -d' ' -f2 | sort | tr '\n' ' ')" = "/healthz /readyz "
check "GET /healthz says ok" bash -c "[ \"\$(curl -s --max-time 10 '$url/healthz')\" = '{\"status\":\"ok\"}' ]"
check "the page's files come from the installed web directory (DASHPOT_WEB_DIR)" \
    grep -q "serving [0-9]* web files* from $p/share/dashpot/web\$" "$log"
if [ -f web/index.html ]; then
    check "GET / serves the installed web/index.html" \
        bash -c "[ \"\$(curl -s --max-time 10 -o '$SCRATCH/index' -w '%{http_code}' '$url/')\" = 200 ] &&
                 cmp -s '$SCRATCH/index' web/index.html"
fi
check "GET /openapi.yaml serves the installed document (DASHPOT_OPENAPI)" \
    bash -c "[ \"\$(curl -s --max-time 10 -o '$SCRATCH/openapi' -w '%{http_code}' '$url/openapi.yaml')\" = 200 ] &&
             cmp -s '$SCRATCH/openapi' api/openapi.yaml"
spec='{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 1}},
       "initial": {"x": 4.5, "v": 0}, "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 10, "theta": 0.5},
       "output": {"every": 2000}}'
check "POST /v1/simulate 200 application/json" \
    test "$(code -H 'Content-Type: application/json' -d "$spec" "$url/v1/simulate")" = "200 application/json"
check "the simulation rests at x = 0.5 with one stick event near 2 pi" python3 -c "
import json, math
d = json.load(open('$SCRATCH/body'))
assert abs(d['summary']['final']['x'] - 0.5) < 1e-9 and d['summary']['final']['phase'] == 'stick', d['summary']
assert [e['kind'] for e in d['events']] == ['stick'] and abs(d['events'][0]['t'] - 2 * math.pi) < 1e-5
"
check "an invalid spec is 422 problem+json" \
    test "$(code -d '{"model": {"mass": -1, "spring": {"law": "linear", "k": 1}}}' "$url/v1/simulate")" = \
    "422 application/problem+json"
check "the problem names /model/mass" python3 -c "
import json
d = json.load(open('$SCRATCH/body'))
assert d['status'] == 422 and any(e['pointer'] == '/model/mass' for e in d['errors']), d
"
# DASHPOT_MAX_STEPS=1e8 from the ConfigMap: 1e9 steps are refused (the library alone would allow them).
check "the ConfigMap's max-steps holds: 1e9 steps are 422" \
    test "$(code -d '{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "none"}},
                   "solver": {"dt": 1e-8, "t_end": 10}}' \
        "$url/v1/simulate" | cut -d' ' -f1)" = 422
check "the problem is /problems/over-limit at /solver/dt" python3 -c "
import json
d = json.load(open('$SCRATCH/body'))
assert d['type'] == '/problems/over-limit' and d['errors'][0]['pointer'] == '/solver/dt', d
"

# ---- the Dockerfile's HEALTHCHECK command against this daemon -----------------------------------------------
mapfile -d '' hc < <(manifest healthcheck)
check "HEALTHCHECK command passes against the live daemon" \
    timeout 10 env -i PATH=/usr/bin:/bin DASHPOT_PORT="$port" "${hc[@]}"
closed=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
check "HEALTHCHECK command fails where nothing listens" \
    bash -c "! timeout 10 env -i PATH=/usr/bin:/bin DASHPOT_PORT=$closed $(printf '%q ' "${hc[@]}") 2>/dev/null"

# ---- the sweep Job's script against this daemon ----------------------------------------------------------------
# Index 7 of RUNS_PER_INDEX=4 is runs 28..31: phi0 = 0.05, x0 = 0.29 .. 0.32. From rest at x0 > phi0 the mass
# swings through half periods of pi, each moving the turning point to -(x - 2 phi0 sgn x), until
# |x| <= phi0, where it sticks for good (Babováková 2012 (4.14)); t_end = 330 leaves time for all of them.
manifest job-script > "$SCRATCH/sweep.sh"
timeout 120 env -i PATH=/usr/bin:/bin JOB_COMPLETION_INDEX=7 RUNS_PER_INDEX=4 WORK_DIR="$SCRATCH" \
    DASHPOT_URL="$url/v1/simulate" sh "$SCRATCH/sweep.sh" > "$SCRATCH/sweep.out" 2> "$SCRATCH/sweep.err"
rc=$?
check "the sweep Job's script exits 0" test $rc -eq 0
[ $rc -eq 0 ] || show "$SCRATCH/sweep.err"
check "one line per run, runs 28..31, rest positions as the closed form says" python3 -c "
import json
rows = [json.loads(l) for l in open('$SCRATCH/sweep.out')]
assert [r['run'] for r in rows] == [28, 29, 30, 31], rows
for r in rows:
    phi0, x = r['phi0'], r['x0']
    assert phi0 == 0.05 and abs(x - 0.01 * (r['run'] % 1000 + 1)) < 1e-12, r
    while abs(x) > phi0:
        x = -(x - 2 * phi0 * (1 if x > 0 else -1))
    f = r['summary']['final']
    assert f['phase'] == 'stick' and abs(f['x'] - x) < 1e-9, (r, x)
"
check "the daemon's answer is the CLI's, byte for byte (run 30)" \
    bash -c "'$p/bin/dashpot' simulate '$SCRATCH/sweep-7/30.json' --format ndjson | cmp -s - '$SCRATCH/sweep-7/30.ndjson'"

# ---- stop, uninstall -------------------------------------------------------------------------------------------
kill -TERM "$pid"
wait_pid "$pid" 20
check "SIGTERM: the daemon exits 0 within 20 s" test "$WAIT_RC" -eq 0
check "and logs its shutdown" grep -q 'stopped' "$log"
make_ uninstall DESTDIR="$dest" PREFIX="$prefix" > "$SCRATCH/uninstall.log" 2>&1
rc=$?
check "make uninstall" test $rc -eq 0
[ $rc -eq 0 ] || show "$SCRATCH/uninstall.log"
check "make uninstall leaves no file under the DESTDIR" test -z "$(find "$dest" -type f)"
finish
