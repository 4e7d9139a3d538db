#!/usr/bin/env bash
# tests/test_cli.sh - the `dashpot` CLI end to end: every format, stdin, exit codes, located errors on
# stderr, and the thesis-figures data checked against the closed form (seed 000 (4.14)).
set -uo pipefail
cd "$(dirname "$0")/.."
bin=${BUILD:-build}/dashpot
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
check() { # check DESCRIPTION COMMAND...
  local what=$1; shift
  if "$@"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $what"; fi
}
py() { python3 -c "$@"; }

cat > "$tmp/decay.json" <<'JSON'
{"model": {"mass": 1, "spring": {"law": "linear", "k": 1}, "damper": {"law": "coulomb", "phi0": 1}},
 "initial": {"x": 4.5, "v": 0},
 "solver": {"kind": "stick-slip", "dt": 0.001, "t_end": 10, "theta": 0.5},
 "output": {"every": 2000}}
JSON

"$bin" simulate "$tmp/decay.json" > "$tmp/out.json"; rc=$?
check "json exit 0" test $rc -eq 0
check "json document parses, 6 samples, 1 stick event near 2 pi, rest at 0.5" py "
import json, math
d = json.load(open('$tmp/out.json'))
assert len(d['samples']) == 6, len(d['samples'])
assert [e['kind'] for e in d['events']] == ['stick']
assert abs(d['events'][0]['t'] - 2 * math.pi) < 1e-5
assert abs(d['summary']['final']['x'] - 0.5) < 1e-9 and d['summary']['final']['phase'] == 'stick'
assert d['meta']['solver'] == 'stick-slip' and d['meta']['steps'] == 10000
"
"$bin" simulate "$tmp/decay.json" --format ndjson > "$tmp/out.ndjson"
check "ndjson: meta, 6 samples, 1 event, summary" py "
import json
rows = [json.loads(l) for l in open('$tmp/out.ndjson')]
types = [r['type'] for r in rows]
assert types[0] == 'meta' and types[-1] == 'summary', types
assert types.count('sample') == 6 and types.count('event') == 1, types
"
"$bin" simulate "$tmp/decay.json" --format csv > "$tmp/out.csv"
check "csv header and 6 rows" py "
rows = open('$tmp/out.csv').read().splitlines()
assert rows[0] == 't,x,v,Fs,Fd,Fc,phase', rows[0]
assert len(rows) == 7, len(rows)
"
check "stdin gives identical bytes" bash -c "'$bin' simulate - < '$tmp/decay.json' | cmp -s - '$tmp/out.json'"
check "deterministic output" bash -c "'$bin' simulate '$tmp/decay.json' | cmp -s - '$tmp/out.json'"

echo '{"model":{"mass":-1,"spring":{"law":"linear","k":1},"damper":{"law":"colomb"}}}' \
  | "$bin" simulate - > "$tmp/bad.out" 2> "$tmp/bad.err"; rc=$?
check "invalid spec exits 2" test $rc -eq 2
check "stderr names /model/mass" grep -q '/model/mass: must be a finite number > 0, got -1' "$tmp/bad.err"
check "stderr names /model/damper/law" grep -q '/model/damper/law: unknown law "colomb"' "$tmp/bad.err"
check "nothing on stdout for an invalid spec" test ! -s "$tmp/bad.out"
echo '{"model":' | "$bin" simulate - 2> "$tmp/syn.err" >/dev/null; rc=$?
check "malformed JSON exits 2" test $rc -eq 2
check "malformed JSON message" grep -q 'malformed JSON' "$tmp/syn.err"
"$bin" simulate /nonexistent.json 2>/dev/null; rc=$?
check "missing file exits 2" test $rc -eq 2
"$bin" simulate "$tmp/decay.json" --format xml 2>/dev/null; rc=$?
check "unknown format exits 2" test $rc -eq 2
"$bin" frobnicate 2>/dev/null; rc=$?
check "unknown command exits 2" test $rc -eq 2
check "--version" bash -c "'$bin' --version | grep -q '^dashpot '"

# Negative damping (gamma = 50 v adds energy: growth like e^(25 t)) overflows: a diverging run is an error with a final error line, never NaN in the output.
cat > "$tmp/diverge.json" <<'JSON'
{"model": {"mass": 1, "spring": {"law": "linear", "k": 1},
           "damper": {"law": "linear", "c": 0, "relaxation": {"kind": "linear", "L": 50}}},
 "initial": {"x": 1}, "solver": {"dt": 0.01, "t_end": 100}}
JSON
"$bin" simulate "$tmp/diverge.json" --format ndjson > "$tmp/div.out" 2> "$tmp/div.err"; rc=$?
check "divergence exits 1" test $rc -eq 1
check "divergence ends with an error line" bash -c "tail -n 1 '$tmp/div.out' | grep -q '\"type\":\"error\"'"
check "no NaN or Infinity in output" bash -c "! grep -qiE 'nan|inf' '$tmp/div.out'"

# Thesis Figs. 4.2-4.5: rest positions and stick times against the closed form, to O(dt).
bash scripts/thesis-figures.sh "$bin" "$tmp/thesis" > /dev/null
check "thesis figures: 12 runs of 10001 samples" bash -c "[ \$(ls '$tmp'/thesis/x0_*.csv | wc -l) -eq 12 ] && [ \$(wc -l < '$tmp/thesis/x0_5_plain.csv') -eq 10002 ]"
check "thesis figures: rest and stick time within 1e-2 of (4.14)" py "
import csv
for r in csv.DictReader(open('$tmp/thesis/summary.csv')):
    if r['relaxation'] == 'plain':
        assert abs(float(r['rest_x']) - float(r['closed_form_rest_x'])) < 1e-2, r
        assert abs(float(r['stick_time']) - float(r['closed_form_stick_time'])) < 1e-2, r
"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
