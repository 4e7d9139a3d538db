#!/usr/bin/env bash
# tests/test_lcs.sh - `dashpot lcp` and POST /v1/lcp end to end (issue 20): seed 002's Examples 1.6 and 2.4
# with their own numbers (closed forms in the comments, checked here in Python), a 3-solution problem whose
# solutions are computed by hand, the CLI and the daemon answering byte for byte alike, and bad input (422
# with JSON Pointers, CLI exit 2, 400 for malformed JSON), then the LCS circuits of docs/lcs.md.
# Env BUILD (default build). Prints "N passed, M failed"; exit 1 on any failure.
source "$(dirname "$0")/lib/daemon.bash"

BIN=$BUILD/dashpot
T=$SCRATCH

pyjson() {
    python3 -c 'import json,math,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if eval("(" + sys.argv[2] + ")") else 1)' "$1" "$2" ||
        { echo "    $2 fails for: $(head -c 600 "$1")"; return 1; }
}

# Example 1.6: 0 <= u ⊥ v + u >= 0 -> u = max(-v, 0), w = v + u = max(v, 0); v = (-1.5, 2, 0, -3).
echo '{"M": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]], "q": [-1.5, 2, 0, -3]}' >"$T/ex16.json"
"$BIN" lcp "$T/ex16.json" >"$T/ex16.out"
check "lcp Example 1.6: u = v^-, w = v^+, one solution, P-matrix, mu = 1" pyjson "$T/ex16.out" "
d['lemke']['z'] == [1.5, 0, 0, 3] and d['lemke']['w'] == [0, 2, 0, 0] and d['count'] == 1 and
d['solutions'][0]['z'] == [1.5, 0, 0, 3] and d['theory']['p_matrix'] is True and d['theory']['mu'] == 1 and
d['theory']['lipschitz'] == 1 and d['verdict'].startswith('exactly one solution')"

# Example 2.4: p in a u + N_R+(u) is M = [a], q = [-p]. a = -2, p = -3: u = 0 and u = p/a = 1.5 (Fig. 7, a < 0).
echo '{"M": [[-2]], "q": [3]}' >"$T/ex24.json"
"$BIN" lcp "$T/ex24.json" >"$T/ex24.out"
check "lcp Example 2.4, a < 0: two solutions 0 and p/a, not a P-matrix (minor -2)" pyjson "$T/ex24.out" "
sorted(s['z'][0] for s in d['solutions']) == [0, 1.5] and d['count'] == 2 and
d['theory']['p_matrix'] is False and d['theory']['minor_witness'] == {'rows': [0], 'minor': -2} and
d['theory']['mu'] == -2 and d['theory']['lipschitz'] is None and d['verdict'].startswith('2 solutions')"
# a = 0.5, p = 2: u = p/a = 4, mu = a, Lipschitz constant L/mu = 2 (Theorem 2.3).
echo '{"M": [[0.5]], "q": [-2]}' | "$BIN" lcp - >"$T/ex24b.out"
check "lcp Example 2.4, a > 0: u = p/a = 4, mu = 0.5, Lipschitz 2" pyjson "$T/ex24b.out" "
d['lemke']['z'] == [4] and d['count'] == 1 and d['theory']['mu'] == 0.5 and d['theory']['lipschitz'] == 2"
# a = 0, p = 1: no solution (Lemke's ray); a = 0, p = 0: u = 0 and the singular basis (every u >= 0 solves).
echo '{"M": [[0]], "q": [-1]}' | "$BIN" lcp - >"$T/ex24c.out"
check "lcp Example 2.4, a = 0, p > 0: no solution, Lemke's ray" pyjson "$T/ex24c.out" "
d['lemke']['outcome'] == 'ray' and d['lemke']['z'] is None and d['count'] == 0 and d['verdict'].startswith('no solution: Lemke')"
echo '{"M": [[0]], "q": [0]}' | "$BIN" lcp - >"$T/ex24d.out"
check "lcp Example 2.4, a = 0, p = 0: u = 0 and a singular basis (a continuum)" pyjson "$T/ex24d.out" "
d['count'] == 1 and d['singular_bases'] == 1 and 'continuum' in d['verdict']"

# M = [[1, 2], [3, 1]], q = (-1, -1): z = (1, 0), (0, 1), and both w = 0: z = M^-1 (1, 1) = (1/5, 2/5).
echo '{"M": [[1, 2], [3, 1]], "q": [-1, -1]}' >"$T/three.json"
"$BIN" lcp "$T/three.json" >"$T/three.out"
check "lcp: three solutions of a non-P matrix, Lemke's is one of them" pyjson "$T/three.out" "
d['count'] == 3 and
sorted([round(x, 15) for x in s['z']] for s in d['solutions']) == [[0, 1], [0.2, 0.4], [1, 0]] and
d['lemke']['z'] in [s['z'] for s in d['solutions']] and d['theory']['minor_witness']['minor'] == -5"

bad() { # bad NAME DOC POINTER: exit 2 and the pointer on stderr
    echo "$2" | "$BIN" lcp - >/dev/null 2>"$T/err"
    local rc=$?
    [ $rc = 2 ] && grep -q -- "-: $3: " "$T/err" || { echo "    exit $rc: $(cat "$T/err")"; return 1; }
}
check "lcp: a short row named" bad row '{"M": [[1, 2], [3]], "q": [1, 1]}' /M/1
check "lcp: q of another length named" bad q '{"M": [[1]], "q": [1, 2]}' /q
check "lcp: a string entry named" bad entry '{"M": [[1, "x"], [0, 1]], "q": [1, 1]}' /M/0/1
check "lcp: a missing M named" bad missing '{"q": [1]}' /M
check "lcp: an unknown key" bad key '{"M": [[1]], "q": [1], "r": 1}' '(document)'

start_daemon lcp || finish
U=$URL_lcp
post() { # post PATH FILE -> status and content type in $T/ct, body in $T/body
    hcurl -X POST --data-binary @"$2" -o "$T/body" -w '%{http_code} %{content_type}' "$U$1" >"$T/ct"
}
post /v1/lcp "$T/three.json"
check "POST /v1/lcp: 200 application/json, the CLI's answer byte for byte" \
    bash -c "[ \"\$(cat '$T/ct')\" = '200 application/json' ] && cmp -s '$T/body' '$T/three.out'"
echo '{"M": [[1, 2], [3, 4]], "q": [1]}' >"$T/badq.json"
post /v1/lcp "$T/badq.json"
check "POST /v1/lcp, q too short: 422 problem at /q" pyjson "$T/body" "
d['status'] == 422 and [e['pointer'] for e in d['errors']] == ['/q']"
printf '{"M": ' >"$T/trunc.json"
post /v1/lcp "$T/trunc.json"
check "POST /v1/lcp, malformed JSON: 400" [ "$(cut -d' ' -f1 "$T/ct")" = 400 ]
check "/metrics counts /v1/lcp" bash -c "curl -s '$U/metrics' | grep -q 'route=\"/v1/lcp\"'"
stop_daemon lcp
check "SIGTERM: exit 0" [ "$RC_lcp" = 0 ]
finish
