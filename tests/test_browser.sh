#!/usr/bin/env bash
# tests/test_browser.sh - the browser page at / (web/, src/http/page.c): first with curl (content types,
# Cache-Control + ETag, 304, HEAD, 404 problem+json for unknown files, nothing outside web/ ever served:
# "..", encoded dots, symlinks, dot files, subdirectories, --web-dir / DASHPOT_WEB_DIR, the directory found
# from another working directory), then in a real browser: tests/browser/test_page.mjs drives Debian's
# Chromium with playwright-core (runs presets, counts plotted points against the samples streamed, checks
# the console, decodes screenshots, the problem+json display, the stability map, a path prefix, the
# bearer token of a daemon that wants one).
#
# What it needs is installed when missing, never skipped: Debian's `chromium` (and `nodejs npm` if there is
# no npm) with apt-get (as root; as a normal user the test prints the command and fails) and playwright-core
# (pinned) from npm into DASHPOT_CACHE (default ~/.cache/dashpot) with browser downloads off. Screenshots go to
# DASHPOT_SCREENSHOTS (default $BUILD/screenshots). Env BUILD (default build). Prints "N passed, M failed".
source "$(dirname "$0")/lib/daemon.bash"

# 1.61.1: the last playwright-core that runs on Debian 12's Node.js 18 (later ones need Node 20).
PLAYWRIGHT_VERSION=1.61.1
PLAYWRIGHT_DIR=${DASHPOT_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/dashpot}/playwright-core-$PLAYWRIGHT_VERSION
CHROMIUM=${DASHPOT_CHROMIUM:-/usr/bin/chromium}
SHOTS=${DASHPOT_SCREENSHOTS:-$BUILD/screenshots}
BODY=$SCRATCH/body
HDRS=$SCRATCH/headers

req() { # req METHOD URL [curl args...]: status in STATUS, body in $BODY, headers in $HDRS
    local m=$1 u=$2
    shift 2
    : >"$BODY"
    STATUS=$(hcurl -X "$m" -D "$HDRS" -o "$BODY" -w '%{http_code}' "$@" "$u")
}
header() { grep -i "^$1:" "$HDRS" | head -1 | cut -d: -f2- | tr -d '\r' | sed 's/^ *//'; }
is() { [ "$1" = "$2" ] || { echo "    got '$1', expected '$2'"; return 1; }; }
problem404() { is "$STATUS $(header Content-Type)" "404 application/problem+json" && grep -q '"status":404' "$BODY"; }

# ---- serving, with curl ----
start_daemon web || finish
U=$URL_web
req GET "$U/"
check "GET / is 200 text/html; charset=utf-8" is "$STATUS $(header Content-Type)" "200 text/html; charset=utf-8"
check "GET / serves web/index.html" cmp -s "$BODY" "$ROOT/web/index.html"
check "GET / has Cache-Control: no-cache and a strong ETag" \
    bash -c '[ "$1" = no-cache ] && [[ $2 =~ ^\"[0-9a-f]{16}\"$ ]]' _ "$(header Cache-Control)" "$(header ETag)"
check "GET / has a Content-Security-Policy of 'self' (no CDN, no web fonts)" \
    bash -c '[[ $1 == "default-src '"'self'"';"* ]]' _ "$(header Content-Security-Policy)"
ETAG=$(header ETag)
LEN=$(stat -c %s "$ROOT/web/index.html")
SIZE=$(hcurl -I -D "$HDRS" -o /dev/null -w '%{http_code} %{size_download}' "$U/")
check "HEAD / is 200 with the headers of GET and no body" \
    is "$SIZE $(header Content-Type) $(header ETag) $(header Content-Length)" "200 0 text/html; charset=utf-8 $ETAG $LEN"
req GET "$U/" -H "If-None-Match: $ETAG"
check "If-None-Match with the ETag is 304 with no body" is "$STATUS $(stat -c %s "$BODY") $(header ETag)" "304 0 $ETAG"
req GET "$U/" -H 'If-None-Match: W/"0000000000000000", '"$ETAG"
check "If-None-Match with a list holding the ETag is 304" is "$STATUS" 304
req GET "$U/" -H 'If-None-Match: "0000000000000000"'
check "If-None-Match with another ETag is 200" is "$STATUS" 200
req GET "$U/index.html"
check "GET /index.html is the page too" cmp -s "$BODY" "$ROOT/web/index.html"
for f in app.js plot.js editor.js presets.js; do
    req GET "$U/$f"
    check "GET /$f is 200 text/javascript, no-cache, as in web/" \
        bash -c '[ "$1" = "200 text/javascript; charset=utf-8 no-cache" ] && cmp -s "$2" "$3"' _ \
        "$STATUS $(header Content-Type) $(header Cache-Control)" "$BODY" "$ROOT/web/$f"
done
req GET "$U/style.css"
check "GET /style.css is 200 text/css" is "$STATUS $(header Content-Type)" "200 text/css; charset=utf-8"
SIZE=$(hcurl -I -D "$HDRS" -o /dev/null -w '%{http_code} %{size_download}' "$U/app.js")
check "HEAD /app.js is 200 text/javascript, no body" is "$SIZE $(header Content-Type)" "200 0 text/javascript; charset=utf-8"
req GET "$U/favicon.svg"
check "GET /favicon.svg is image/svg+xml" is "$STATUS $(header Content-Type)" "200 image/svg+xml"
req GET "$U/nope.js"
check "an unknown file is 404 problem+json" problem404
req POST "$U/" --data-binary '{}'
check "POST / is 405 with Allow: GET, HEAD" is "$STATUS $(header Allow)" "405 GET, HEAD"
check "the page's requests are counted under route \"/\" in /metrics" \
    grep -q 'dashpot_http_requests_total{route="/",status="304"} 2' <(hcurl "$U/metrics")
# Nothing outside web/: curl --path-as-is sends the dots as written; %2e and %2f arrive decoded or not.
for p in /../README.md /../../etc/passwd /%2e%2e/README.md /..%2fREADME.md /%2e%2e%2fREADME.md //etc/passwd \
    /web/index.html /./index.html /../web/index.html /.%2e/Makefile '/index.html/..' /app.js/; do
    req GET "$U$p" --path-as-is
    check "GET $p is 404 problem+json" problem404
done
relative() { # no absolute URL in the page's files: every fetch, src and href is relative
    ! grep -nE "(fetch\(|src=|href=|url\()['\"]?(/|https?:)" "$ROOT"/web/*.html "$ROOT"/web/*.js "$ROOT"/web/*.css
}
check "the page uses relative URLs only (works behind a path prefix)" relative

# A web directory with what must never be served next to what must.
W=$SCRATCH/web
mkdir -p "$W/sub"
echo '<!doctype html><title>t</title>' >"$W/index.html"
echo 'ok' >"$W/ok.js"
echo 'secret' >"$W/.secret.js"
echo 'nested' >"$W/sub/x.js"
echo 'notes' >"$W/notes.md"
echo 'text' >"$W/plain"
ln -s /etc/passwd "$W/passwd.txt"
ln -s "$ROOT/web/app.js" "$W/link.js"
head -c 5000000 /dev/zero >"$W/big.js"
DASHPOT_WEB_DIR=$W start_daemon tmpweb || finish
req GET "$URL_tmpweb/ok.js"
check "DASHPOT_WEB_DIR: a plain file of the directory is served" is "$STATUS $(cat "$BODY")" "200 ok"
for p in /.secret.js /sub/x.js /sub%2fx.js /notes.md /plain /passwd.txt /link.js /big.js /../web/app.js; do
    req GET "$URL_tmpweb$p" --path-as-is
    check "--web-dir: GET $p is 404 (dot file, subdirectory, unknown type, symlink or > 4 MiB)" problem404
done
stop_daemon tmpweb
start_daemon noweb --web-dir "$SCRATCH/none" || finish
req GET "$URL_noweb/"
check "without a web directory / is 404 problem+json naming --web-dir" \
    bash -c '[ "$1" = 404 ] && grep -q -- "--web-dir" "$2"' _ "$STATUS" "$BODY"
check "...and the start-up log warns about it" grep -q "web directory .* not found" "$LOG_noweb"
stop_daemon noweb
mkdir -p "$SCRATCH/elsewhere"
(cd "$SCRATCH/elsewhere" && exec "$DAEMON" --port 0) 2>"$SCRATCH/elsewhere.log" &
ELSEWHERE=$!
DAEMON_PIDS+=("$ELSEWHERE")
for i in $(seq 50); do grep -q listening "$SCRATCH/elsewhere.log" && break; sleep 0.1; done
check "from another working directory the daemon finds web/ beside its binary" \
    grep -q "serving [0-9]* web files from .*/\.\./web" "$SCRATCH/elsewhere.log"
kill -TERM "$ELSEWHERE"
wait_pid "$ELSEWHERE"

# ---- in the browser ----
install_chromium() {
    [ -x "$CHROMIUM" ] && return 0
    if [ "$(id -u)" != 0 ]; then
        echo "    $CHROMIUM not found; install it with: sudo apt-get install -y chromium"
        return 1
    fi
    echo "    installing Debian's chromium with apt-get"
    { timeout 900 apt-get install -y --no-install-recommends chromium ||
        { timeout 300 apt-get update && timeout 900 apt-get install -y --no-install-recommends chromium; }; } \
        >"$SCRATCH/apt.log" 2>&1 || { tail -20 "$SCRATCH/apt.log" | sed 's/^/    /'; return 1; }
    [ -x "$CHROMIUM" ]
}
install_playwright() {
    [ -f "$PLAYWRIGHT_DIR/node_modules/playwright-core/package.json" ] && return 0
    if ! command -v npm >/dev/null && [ "$(id -u)" = 0 ]; then
        echo "    installing Debian's nodejs and npm with apt-get"
        { timeout 900 apt-get install -y --no-install-recommends nodejs npm ||
            { timeout 300 apt-get update && timeout 900 apt-get install -y --no-install-recommends nodejs npm; }; } \
            >"$SCRATCH/apt-node.log" 2>&1 || tail -20 "$SCRATCH/apt-node.log" | sed 's/^/    /'
    fi
    command -v npm >/dev/null || { echo "    npm not found: install Node.js (>= 18) and npm"; return 1; }
    mkdir -p "$PLAYWRIGHT_DIR"
    echo "    installing playwright-core@$PLAYWRIGHT_VERSION into $PLAYWRIGHT_DIR (no browser download)"
    PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 timeout 300 npm install --prefix "$PLAYWRIGHT_DIR" --no-audit --no-fund \
        --loglevel=error "playwright-core@$PLAYWRIGHT_VERSION" >"$SCRATCH/npm.log" 2>&1 ||
        { tail -20 "$SCRATCH/npm.log" | sed 's/^/    /'; return 1; }
    [ -f "$PLAYWRIGHT_DIR/node_modules/playwright-core/package.json" ]
}
check "Debian's chromium is installed ($CHROMIUM)" install_chromium || finish
check "playwright-core $PLAYWRIGHT_VERSION is installed (npm, $PLAYWRIGHT_DIR)" install_playwright || finish
mkdir -p "$SHOTS"
TOKEN=page-test-$RANDOM$RANDOM
DASHPOT_TOKEN=$TOKEN start_daemon tok || finish
TOKEN_URL=$URL_tok/ TOKEN=$TOKEN PLAYWRIGHT_DIR=$PLAYWRIGHT_DIR CHROMIUM=$CHROMIUM timeout 330 node "$ROOT/tests/browser/test_page.mjs" "$U/" "$SHOTS" \
    "$SCRATCH/counts" 2>&1 | sed 's/^\(not ok\|ok\) - /\1 - browser: /'
read -r p f <"$SCRATCH/counts" 2>/dev/null || { p=0; f=1; echo "not ok - the browser test did not report"; }
PASSED=$((PASSED + p))
FAILED=$((FAILED + f))
echo "    screenshots: $SHOTS"
stop_daemon tok
stop_daemon web
check "SIGTERM: exit 0" is "$RC_web" 0
finish
