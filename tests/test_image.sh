#!/usr/bin/env bash
# tests/test_image.sh - the container image built and run, not only read: `make image` (scripts/image.sh:
# docker or podman, the Debian base made with debootstrap where no registry answers), then the image's
# entrypoint with the image's environment and user - by `ENGINE run` where this machine can run containers,
# else chrooted into the image's exported filesystem as its USER (sandboxes that refuse an OCI runtime) - and
# what a user of the image sees: /healthz, a simulation in each of the four formats against the closed form,
# the page, the OpenAPI document, an invalid spec, the Dockerfile's HEALTHCHECK command passing (and failing
# where nothing listens), the process's uid, SIGTERM; the filesystem has no compiler and no -dev package; the
# size is printed and bounded (the slim base plus a few MB). Run by `make robustness` (a cold first build
# takes about a minute). Skips, saying why, when not root and no engine works. Prints "N passed, M failed".
source "$(dirname "$0")/lib/daemon.bash"
cd "$ROOT" || exit 1
chmod 755 "$SCRATCH"
show() { sed 's/^/    /' "$1"; }
CNAME=dashpot-test-image-$$
ENGINE=
cleanup_image() {
    local c
    [ -z "$ENGINE" ] || for c in "$CNAME" "$CNAME-fs"; do "$ENGINE" rm -f "$c" > /dev/null 2>&1; done
    cleanup
}
trap cleanup_image EXIT

if [ "$(id -u)" -ne 0 ] && ! { command -v podman || docker info; } >/dev/null 2>&1; then
    echo "skipped: no container engine, and installing podman and debootstrap needs root"
    exit 0
fi

# ---- the build ---------------------------------------------------------------------------------------------
start=$SECONDS
env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make --no-print-directory image BUILD="$BUILD" > "$SCRATCH/image.log" 2>&1
rc=$?
check "make image ($((SECONDS - start)) s)" test $rc -eq 0
[ $rc -eq 0 ] || { tail -40 "$SCRATCH/image.log" | show /dev/stdin; finish; }
grep '^image: ' "$SCRATCH/image.log" | sed 's/^/    /'
# shellcheck source=/dev/null
source "$BUILD/image.env"
"$ENGINE" image inspect "$IMAGE" > "$SCRATCH/inspect.json"
# img FIELD: the image's configuration value (docker keeps Healthcheck in Config, podman beside it).
img() {
    python3 -c 'import json, sys
d = json.load(open(sys.argv[1]))[0]
c = dict(d["Config"], Healthcheck=d.get("Healthcheck") or d["Config"].get("Healthcheck"), Size=d["Size"])
v = c.get(sys.argv[2])
print(v if isinstance(v, (str, int)) else json.dumps(v))' "$SCRATCH/inspect.json" "$1"
}
user=$(img User)
check "the image's USER is non-root and numeric ($user)" bash -c "[[ '$user' =~ ^[1-9][0-9]*:[1-9][0-9]*$ ]]"
uid=${user%%:*} gid=${user##*:}
check "the image's ENTRYPOINT is /usr/local/bin/dashpotd" test "$(img Entrypoint)" = '["/usr/local/bin/dashpotd"]'

# ---- the image's filesystem ----------------------------------------------------------------------------------
fs=$SCRATCH/fs
mkdir "$fs"
"$ENGINE" create --name "$CNAME-fs" "$IMAGE" > /dev/null && "$ENGINE" export "$CNAME-fs" | tar -C "$fs" -xf -
check "the image's filesystem exports" test -x "$fs/usr/local/bin/dashpotd"
check "its /etc/passwd names uid $uid dashpot, with no login shell" \
    grep -qx "dashpot:x:$uid:$gid::/nonexistent:/usr/sbin/nologin" "$fs/etc/passwd"
# toolchain ROOT: the compilers and linkers found in ROOT's PATH, and the installed packages that are -dev or
# a toolchain, one a line; empty for a runtime image.
toolchain() {
    find "$1"/usr/bin "$1"/usr/local/bin "$1"/bin -maxdepth 1 \( -name 'gcc*' -o -name 'cc' -o -name 'c++' \
        -o -name 'g++*' -o -name 'clang*' -o -name 'cpp*' -o -name 'tcc' -o -name 'ld' -o -name 'ld.bfd' -o -name 'ld.gold' -o -name 'ld.lld' \
        -o -name 'as' -o -name 'make' \) -printf '%p\n' 2>/dev/null
    awk '/^Package: / { p = $2 } /^Status: .* installed$/ { print p }' "$1/var/lib/dpkg/status" |
        grep -E -- '-dev$|^(gcc|g\+\+|cpp|clang|binutils|make|build-essential|libc6-dev)(-[0-9.]+)?$'
}
mkdir -p "$SCRATCH/fake/usr/bin" "$SCRATCH/fake/var/lib/dpkg"
touch "$SCRATCH/fake/usr/bin/gcc-12"
printf 'Package: libgsl-dev\nStatus: install ok installed\n' > "$SCRATCH/fake/var/lib/dpkg/status"
check "the toolchain check finds gcc-12 and libgsl-dev in a tree that has them" \
    test "$(toolchain "$SCRATCH/fake" | wc -l)" -eq 2
check "the image holds no compiler, linker, make or -dev package" test -z "$(toolchain "$fs")"
[ -z "$(toolchain "$fs")" ] || toolchain "$fs" | sed 's/^/    /'
check "the image's dpkg database is there and has the runtime libraries" bash -c \
    "[ \$(grep -cE '^Package: (libmicrohttpd12|libcjson1|libgsl27|libgslcblas0)$' '$fs/var/lib/dpkg/status') = 4 ]"

# ---- the size ------------------------------------------------------------------------------------------------
# The runtime stage adds the four libraries (about 3 MB with their own dependencies), the two stripped
# binaries and the share files to its base: 2 to 15 MB. A compiler (gcc-12 alone is ~70 MB), -dev packages,
# apt's lists or its package cache (tens of MB each) left in a layer would exceed it.
base=$(awk 'toupper($1) == "FROM" { b = $2 } END { print b }' Dockerfile)
size=$(img Size)
base_size=$("$ENGINE" image inspect --format '{{.Size}}' "$base")
delta=$(((size - base_size) / 1000000))
echo "    image $IMAGE: $((size / 1000000)) MB; base $base: $((base_size / 1000000)) MB; added: $delta MB"
check "the image is its base plus 2 to 15 MB ($delta MB)" test "$delta" -ge 2 -a "$delta" -le 15

# ---- the daemon, as the image starts it ---------------------------------------------------------------------
# The image's environment with DASHPOT_PORT=0 (any free port, logged) and loopback, on a shared machine.
lines() { python3 -c 'import json, sys; print("\n".join(json.loads(sys.argv[1])))' "$1"; }
mapfile -t ienv < <(lines "$(img Env)")
mapfile -t entry < <(lines "$(img Entrypoint)")
log=$SCRATCH/dashpotd.log
mode=run
timeout 60 "$ENGINE" run --rm --network none --entrypoint /bin/true "$IMAGE" > "$SCRATCH/run-probe.log" 2>&1 ||
    mode=chroot
if [ $mode = run ]; then
    echo "    running it with $ENGINE run"
    "$ENGINE" run -d --name "$CNAME" -p 127.0.0.1::8080 "$IMAGE" > /dev/null 2> "$SCRATCH/run.log"
    port=$("$ENGINE" port "$CNAME" 8080/tcp 2>/dev/null | head -1 | sed 's/.*://')
    for _ in $(seq 200); do curl -s --max-time 1 "http://127.0.0.1:$port/healthz" > /dev/null && break; sleep 0.1; done
    "$ENGINE" logs "$CNAME" > "$log" 2>&1
    # in_image CMD...: CMD inside the running container, as the image's user (DASHPOT_PORT=$IN_PORT if set).
    in_image() { timeout 10 "$ENGINE" exec ${IN_PORT:+-e DASHPOT_PORT=$IN_PORT} "$CNAME" "$@"; }
    closed_port=1
else
    echo "    $ENGINE run does not work here ($(tail -1 "$SCRATCH/run-probe.log")):"
    echo "    running the entrypoint chrooted into the image's filesystem as $user"
    # The device nodes a container gets (no bind mounts: the scratch tree is removed with rm -rf).
    for d in null:1:3 zero:1:5 random:1:8 urandom:1:9; do
        IFS=: read -r n ma mi <<< "$d"
        rm -f "$fs/dev/$n"; mknod -m 666 "$fs/dev/$n" c "$ma" "$mi"
    done
    # env and chroot exec in turn, so $! is the daemon itself; chroot --userspec drops to the image's user.
    env -i "${ienv[@]}" DASHPOT_PORT=0 DASHPOT_BIND=127.0.0.1 \
        /usr/sbin/chroot --userspec="$uid:$gid" --groups="$gid" "$fs" "${entry[@]}" 2> "$log" &
    pid=$!
    DAEMON_PIDS+=("$pid")
    port=
    for _ in $(seq 200); do
        port=$(grep -o 'listening on http://[^ ]*' "$log" 2>/dev/null | grep -o '[0-9]*$')
        [ -n "$port" ] && break
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.1
    done
    in_image() {
        timeout 10 env -i "${ienv[@]}" DASHPOT_PORT="${IN_PORT:-$port}" \
            /usr/sbin/chroot --userspec="$uid:$gid" --groups="$gid" "$fs" "$@"
    }
    closed_port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
fi
check "the image's dashpotd starts and listens (within 20 s)" test -n "$port"
[ -n "$port" ] || { show "$log"; finish; }
url=http://127.0.0.1:$port
# The daemon's /proc entry: PID 1 seen from inside the container (its uid as the image sees it, whatever
# the engine maps it to), or the chrooted process itself.
proc() { if [ $mode = run ]; then in_image cat "/proc/1/$1"; else cat "/proc/$pid/$1"; fi; }
[ $mode = run ] || check "the process is the image's /usr/local/bin/dashpotd" \
    test "$(readlink "/proc/$pid/exe")" = "$fs/usr/local/bin/dashpotd"
check "it runs as uid $uid (real, effective, saved, filesystem)" \
    grep -Eq "^Uid:\s+$uid\s+$uid\s+$uid\s+$uid$" <(proc status)
check "it runs as gid $gid (real, effective, saved, filesystem)" \
    grep -Eq "^Gid:\s+$gid\s+$gid\s+$gid\s+$gid$" <(proc status)
check "its command line is the image's ENTRYPOINT" \
    test "$(proc cmdline | tr '\0' '\n')" = "$(printf '%s\n' "${entry[@]}")"
check "its start-up log names the image's OpenAPI document and web directory" \
    bash -c "grep -q 'serving the OpenAPI document from /usr/local/share/dashpot/openapi.yaml\$' '$log' &&
             grep -q 'serving [0-9]* web files* from /usr/local/share/dashpot/web\$' '$log'"

code() { hcurl -o "$SCRATCH/body" -w '%{http_code} %{content_type}' "$@"; }
healthz() {
    [ "$(code "$url/healthz")" = "200 application/json" ] &&
        python3 -c 'import json, sys; assert json.load(open(sys.argv[1])) == {"status": "ok"}' "$SCRATCH/body"
}
check "GET /healthz is 200 application/json {\"status\": \"ok\"}" healthz
check "GET /openapi.yaml is 200 application/yaml, api/openapi.yaml" \
    bash -c "[ \"\$(curl -s --max-time 10 -o '$SCRATCH/openapi' -w '%{http_code} %{content_type}' '$url/openapi.yaml')\" = \
              '200 application/yaml' ] && cmp -s '$SCRATCH/openapi' api/openapi.yaml"
for f in web/*; do
    name=${f#web/}
    path=/$name
    [ "$name" = index.html ] && path=/
    check "GET $path is 200 and web/$name" \
        bash -c "[ \"\$(curl -s --max-time 10 -o '$SCRATCH/page' -w '%{http_code}' '$url$path')\" = 200 ] &&
                 cmp -s '$SCRATCH/page' '$f'"
done
check "GET / is text/html" bash -c "curl -s --max-time 10 -o /dev/null -w '%{content_type}' '$url/' | grep -q '^text/html'"

# The README's decay: m = k = phi0 = 1 from x = 4.5 at rest. Closed form (Babováková 2012 (4.14)): x = 1 + 3.5 cos t
# while it slides left (to -2.5 at pi), x = -1 - 1.5 cos(t - pi) while it slides right (to 0.5 at 2 pi),
# then it sticks at 0.5 for good (|k x| <= phi0).
spec='{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 1}},
       "initial": {"x": 4.5, "v": 0}, "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 10, "theta": 0.5},
       "output": {"every": 500}}'
# closed FORMAT: the body's samples (t, x) match the closed form to 1e-5 (the theta = 1/2 scheme's error at
# dt = 1e-3 is ~1e-6), there are 21 (t = 0, 0.5, ..., 10), and a final summary rests at 0.5, sticking.
closed() {
    python3 - "$1" "$SCRATCH/body" <<'PY'
import csv, io, json, math, sys
fmt, text = sys.argv[1], open(sys.argv[2]).read()
if fmt == "json":
    d = json.loads(text)
    samples, summary = d["samples"], d["summary"]
elif fmt in ("ndjson", "sse"):
    if fmt == "sse":
        blocks = [b.split("\n") for b in text.split("\n\n") if b]
        assert all(b[0] == "event: " + json.loads(b[1][6:])["type"] for b in blocks), "SSE event/data mismatch"
        objs = [json.loads(b[1][6:]) for b in blocks]
    else:
        objs = [json.loads(l) for l in text.splitlines()]
    assert objs[0]["type"] == "meta" and objs[-1]["type"] == "summary", (objs[0], objs[-1])
    samples, summary = [o for o in objs if o["type"] == "sample"], objs[-1]
else:
    rows = list(csv.DictReader(io.StringIO(text)))
    samples = [{"t": float(r["t"]), "x": float(r["x"]), "phase": r["phase"]} for r in rows]
    summary = {"final": {"x": samples[-1]["x"], "phase": samples[-1]["phase"]}}
def exact(t):
    if t <= math.pi:
        return 1 + 3.5 * math.cos(t)
    return -1 - 1.5 * math.cos(t - math.pi) if t <= 2 * math.pi else 0.5
assert len(samples) == 21, len(samples)
for s in samples:
    assert abs(s["x"] - exact(s["t"])) < 1e-5, (s, exact(s["t"]))
assert abs(summary["final"]["x"] - 0.5) < 1e-9 and summary["final"]["phase"] == "stick", summary
PY
}
for f in "json application/json" "ndjson application/x-ndjson" "sse text/event-stream" "csv text/csv"; do
    read -r fmt type <<< "$f"
    got=$(code -H "Accept: $type" -H 'Content-Type: application/json' -d "$spec" "$url/v1/simulate")
    check "POST /v1/simulate, Accept: $type: 200 $type" bash -c "[[ '$got' == '200 $type'* ]]"
    check "...its samples follow the closed form; it rests at x = 0.5, sticking" closed "$fmt"
done
check "an invalid spec is 422 problem+json naming /model/mass" bash -c "
    [ \"\$(curl -s --max-time 10 -o '$SCRATCH/body' -w '%{http_code} %{content_type}' \
           -d '{\"model\": {\"mass\": -1, \"spring\": {\"law\": \"linear\", \"k\": 1}}}' '$url/v1/simulate')\" = \
      '422 application/problem+json' ] && grep -q '\"/model/mass\"' '$SCRATCH/body'"

# ---- the HEALTHCHECK ------------------------------------------------------------------------------------------
# The image carries the Dockerfile's command (podman keeps it only in the docker format), and that command,
# run inside the image as its user with its environment, passes against the daemon and fails without one.
mapfile -d '' hc < <(python3 tests/lib/manifests.py healthcheck)
check "the image's HEALTHCHECK is the Dockerfile's command" \
    test "$(img Healthcheck | python3 -c 'import json, sys; print(json.dumps(json.load(sys.stdin)["Test"]))')" = \
    "$(python3 -c 'import json, sys; print(json.dumps(["CMD"] + sys.argv[1:]))' "${hc[@]}")"
check "the HEALTHCHECK command passes inside the image against the daemon" in_image "${hc[@]}"
hc_closed() { ! IN_PORT=$closed_port in_image "$@" 2> /dev/null; }
check "the HEALTHCHECK command fails inside the image where nothing listens" hc_closed "${hc[@]}"

# ---- STOPSIGNAL ----------------------------------------------------------------------------------------------
if [ $mode = run ]; then
    check "$ENGINE stop: the daemon exits 0" bash -c "timeout 30 '$ENGINE' stop -t 20 '$CNAME' >/dev/null 2>&1 &&
        [ \"\$('$ENGINE' inspect --format '{{.State.ExitCode}}' '$CNAME')\" = 0 ]"
else
    kill -"$(img StopSignal | sed 's/^SIG//')" "$pid"
    wait_pid "$pid" 20
    check "the image's STOPSIGNAL ($(img StopSignal)): the daemon exits 0 within 20 s" test "$WAIT_RC" -eq 0
fi
finish
