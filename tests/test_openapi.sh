#!/usr/bin/env bash
# tests/test_openapi.sh - api/openapi.yaml is a valid OpenAPI 3.1 document (Redocly's linter, recommended
# rules, no warnings) and the daemon does what it says: every request example is sent to a live dashpotd,
# once per media type that documents a response example of the same name (errors: with Accept */*, or the
# example's x-accept), and the answer must have the expected status (x-expect-status, default 200), that
# content type and the shape of the response example of the same name (the same members, the same error pointers,
# the same sequence of stream objects, the same CSV header) and, but for SVG, be the example exactly (JSON member for
# member in the same order, text byte for byte).
#
# The linter comes from npm (@redocly/cli, pinned). It is installed once into a cache directory
# (DASHPOT_CACHE, default ~/.cache/dashpot); if it cannot be installed the test fails, it is never skipped.
source "$(dirname "$0")/lib/daemon.bash"

REDOCLY_VERSION=2.77.0
CACHE=${DASHPOT_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/dashpot}/redocly-$REDOCLY_VERSION
REDOCLY=$CACHE/node_modules/.bin/redocly

install_redocly() {
    [ -x "$REDOCLY" ] && return 0
    command -v npm >/dev/null || { echo "    npm not found: install Node.js and npm to lint the OpenAPI document"; return 1; }
    mkdir -p "$CACHE"
    echo "    installing @redocly/cli@$REDOCLY_VERSION into $CACHE"
    timeout 300 npm install --prefix "$CACHE" --no-audit --no-fund --loglevel=error "@redocly/cli@$REDOCLY_VERSION" \
        >"$SCRATCH/npm.log" 2>&1 || { sed 's/^/    /' "$SCRATCH/npm.log" | tail -20; return 1; }
    [ -x "$REDOCLY" ]
}

lint() {
    (cd "$ROOT/api" && timeout 120 "$REDOCLY" lint openapi.yaml --format=stylish) >"$SCRATCH/lint.log" 2>&1
    local rc=$?
    grep -E '^\s+[0-9]+:[0-9]+\s+(error|warning)' "$SCRATCH/lint.log" | sed 's/^/    /'
    [ $rc -eq 0 ] && ! grep -qE '^\s+[0-9]+:[0-9]+\s+(error|warning)' "$SCRATCH/lint.log"
}

check "@redocly/cli $REDOCLY_VERSION is installed (npm)" install_redocly || finish
check "api/openapi.yaml lints clean (recommended rules, no errors, no warnings)" lint
bundle() {
    timeout 120 "$REDOCLY" bundle "$ROOT/api/openapi.yaml" --ext json -o "$SCRATCH/openapi.json" >"$SCRATCH/bundle.log" 2>&1 ||
        { sed 's/^/    /' "$SCRATCH/bundle.log" | grep -v '[║╔╚]'; return 1; }
}
check "api/openapi.yaml bundles to JSON" bundle

start_daemon api || finish
python3 - "$SCRATCH/openapi.json" "$URL_api" "$ROOT/api/openapi.yaml" "$SCRATCH/counts" <<'PY'
import json, subprocess, sys

doc, base, yaml_path = json.load(open(sys.argv[1])), sys.argv[2], sys.argv[3]
passed = failed = 0

def deref(node):
    """Resolves local $refs outside schemas (responses, examples); schemas may be recursive and are not needed."""
    if isinstance(node, list):
        return [deref(n) for n in node]
    if not isinstance(node, dict):
        return node
    if "$ref" in node:
        target = doc
        for part in node["$ref"].lstrip("#/").split("/"):
            target = target[part.replace("~1", "/").replace("~0", "~")]
        return deref(target)
    return {k: (v if k == "schema" else deref(v)) for k, v in node.items()}

doc["paths"] = deref(doc["paths"])

def report(ok, what, why=""):
    global passed, failed
    print(("ok - " if ok else "not ok - ") + what + ("" if ok else "\n    " + why))
    passed, failed = passed + ok, failed + (not ok)

def send(method, path, accept, body=None):
    cmd = ["curl", "-s", "--max-time", "30", "-X", method, "-H", "Accept: " + accept,
           "-w", "\n%{http_code} %{content_type}", base + path]
    if body is not None:
        cmd[1:1] = ["--data-binary", body]
    out = subprocess.run(cmd, capture_output=True).stdout.decode()
    text, _, tail = out.rpartition("\n")
    status, _, ctype = tail.partition(" ")
    return int(status or 0), ctype.split(";")[0], text

def lines_shape(text, media):
    """The sequence of object types of a stream (runs of samples collapsed), or the CSV header."""
    if media == "text/csv":
        return text.splitlines()[:1]
    if media == "text/event-stream":
        types = [b.split("\n")[0][len("event: "):] for b in text.split("\n\n") if b]
    else:
        types = [json.loads(l)["type"] for l in text.splitlines() if l]
    return [t for i, t in enumerate(types) if i == 0 or t != types[i - 1]]

def shape(value, media):
    if media in ("application/json", "application/problem+json"):
        d = json.loads(value) if isinstance(value, str) else value
        if isinstance(d, dict) and "errors" in d:
            return sorted(d), [e["pointer"] for e in d["errors"]]
        return sorted(d) if isinstance(d, dict) else type(d).__name__
    if media == "image/svg+xml":
        return value.lstrip()[:4]
    return lines_shape(value, media)

def run_order(text, media):
    """A sweep's run lines come in completion order (docs/sweep.md), each with its index: put them in index
    order, every other line where it was, so that the comparison below is exact about everything else."""
    if '"type":"run"' not in text:
        return text
    if media == "application/json":
        return text
    blocks = text.split("\n\n") if media == "text/event-stream" else text.split("\n")
    def index(b):
        line = b[b.index("{"):] if "{" in b else ""
        try:
            obj = json.loads(line)
        except ValueError:
            return None
        return obj.get("index") if isinstance(obj, dict) and obj.get("type") == "run" else None
    slots = [i for i, b in enumerate(blocks) if index(b) is not None]
    runs = sorted((blocks[i] for i in slots), key=index)
    for i, b in zip(slots, runs):
        blocks[i] = b
    return ("\n\n" if media == "text/event-stream" else "\n").join(blocks)

def exactly(text, value, media):
    """The response is the documented example: JSON equal member for member and in the same order, other text
    byte for byte (a YAML block scalar ends with one newline, as the streams do); a sweep's run lines in index
    order (run_order)."""
    if media in ("application/json", "application/problem+json"):
        doc = json.loads(value) if isinstance(value, str) else value
        try:
            got = json.loads(text)
        except ValueError:
            return False, json.dumps(doc)
        if isinstance(got, dict) and isinstance(got.get("runs"), list):
            got["runs"].sort(key=lambda r: r.get("index", 0))
        return json.dumps(got) == json.dumps(doc), json.dumps(doc)
    text, value = run_order(text, media), run_order(value, media)
    return text == value or text + "\n" == value, value

def try_example(path, method, name, ex, responses):
    status = int(ex.get("x-expect-status", 200))
    body = ex["value"] if isinstance(ex["value"], str) else json.dumps(ex["value"])
    content = responses[str(status)]["content"]
    # The media types whose response examples bear this example's name; errors are sent with Accept: */*.
    named = [m for m in content if name in content[m].get("examples", {})]
    accepts = [ex["x-accept"]] if "x-accept" in ex else ["*/*"] if status >= 400 else named or list(content)[:1]
    for accept in accepts:
        got_status, got_type, text = send(method, path, accept, body)
        media = accept if accept in content else next(iter(content))
        what = f"{method} {path} example '{name}' as {accept}: {status} {media}"
        if (got_status, got_type) != (status, media):
            report(False, what, f"got {got_status} {got_type}: {text[:300]}")
            continue
        want = content[media].get("examples", {}).get(name)
        if want is None:
            report(True, what + " (no response example to compare)")
            continue
        a, b = shape(text, media), shape(want["value"], media)
        report(a == b, what + ", shape as documented", f"got {a}\n    documented {b}")
        if media != "image/svg+xml":
            same, shown = exactly(text, want["value"], media)
            report(same, what + ", the documented example exactly", f"got        {text[:600]}\n    documented {shown[:600]}")

def try_get(path, op):
    resp = op["responses"]["200"]
    for media, c in resp["content"].items():
        got_status, got_type, text = send("GET", path, media)
        ok = (got_status, got_type) == (200, media)
        if ok and media == "application/yaml":
            ok = text + "\n" == open(yaml_path).read() or text == open(yaml_path).read()
        for ex in c.get("examples", {}).values():
            if ok and media == "application/json":
                ok = json.loads(text) == ex["value"]
            if ok and media == "text/plain":
                names = [l.split()[0] for l in ex["value"].splitlines() if not l.startswith("#")]
                ok = all(n in text for n in names)
        report(ok, f"GET {path} as {media}: 200 as documented", f"got {got_status} {got_type}: {text[:200]}")

for path, item in doc["paths"].items():
    for method, op in item.items():
        if method == "get":
            try_get(path, op)
            continue
        examples = op.get("requestBody", {}).get("content", {}).get("application/json", {}).get("examples", {})
        report(len(examples) > 0, f"{method.upper()} {path} documents request examples")
        for name, ex in examples.items():
            try_example(path, method.upper(), name, ex, op["responses"])
open(sys.argv[4], "w").write(f"{passed} {failed}\n")
PY
# The examples' own checks count with the others.
read -r p f <"$SCRATCH/counts" 2>/dev/null || { p=0; f=1; echo "not ok - the examples did not run"; }
PASSED=$((PASSED + p))
FAILED=$((FAILED + f))
stop_daemon api
check "SIGTERM: exit 0" [ "$RC_api" = 0 ]
finish
