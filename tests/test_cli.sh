#!/usr/bin/env bash
# tests/test_cli.sh - the `dashpot` CLI end to end: every format, stdin, exit codes, located errors on
# stderr, and the thesis-figures data checked against the closed form (Babováková 2012 (4.14)).
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
printf '{"model": {\n  "mass": 1,\n  "spring": {"law": "linear", "k": Infinity}}}\n' >"$tmp/inf.json"
for sub in simulate wellposedness convergence stability lcp modes response; do
    "$bin" $sub "$tmp/inf.json" >/dev/null 2>"$tmp/inf.$sub"; echo $? >>"$tmp/inf.$sub"
done
check "a file's malformed JSON: its line and column and a hint, in the same words for every subcommand" bash -c "
for sub in simulate wellposedness convergence stability lcp modes response; do
    printf '%s\n' 'dashpot: $tmp/inf.json: (document): malformed JSON near byte 60 (line 3, column 36): JSON has no NaN or Infinity; send a number or null' 2 |
        cmp -s - '$tmp/inf.'\$sub || { echo \"    \$sub: \$(cat '$tmp/inf.'\$sub)\"; exit 1; }
done"
"$bin" simulate /nonexistent.json 2>/dev/null; rc=$?
check "missing file exits 2" test $rc -eq 2
"$bin" simulate "$tmp/decay.json" --format xml 2>/dev/null; rc=$?
check "unknown format exits 2" test $rc -eq 2
"$bin" frobnicate 2>/dev/null; rc=$?
check "unknown command exits 2" test $rc -eq 2
check "--version" bash -c "'$bin' --version | grep -q '^dashpot '"

# Help and usage errors: --help on stdout with exit 0, a bad value named on stderr with exit 2.
for cmd in simulate stability wellposedness convergence; do
  "$bin" $cmd --help > "$tmp/help.out" 2> "$tmp/help.err"; rc=$?
  check "$cmd --help exits 0 with its usage on stdout, nothing on stderr" \
    bash -c "[ $rc -eq 0 ] && grep -q '^usage: dashpot $cmd ' '$tmp/help.out' && [ ! -s '$tmp/help.err' ]"
done
check "simulate --help documents --quiet and when the progress bar shows" \
  bash -c "'$bin' simulate -h | grep -q -- '--quiet  *no progress bar (one is drawn on standard error only when it is a terminal'"
"$bin" simulate "$tmp/decay.json" --format svg 2> "$tmp/fmt.err"; rc=$?
check "--format svg exits 2 naming the bad value" \
  bash -c "[ $rc -eq 2 ] && grep -qF 'dashpot: simulate: unknown format (expected json, ndjson or csv): \"svg\"' '$tmp/fmt.err'"
"$bin" simulate "$tmp/decay.json" --frobnicate 2> "$tmp/opt.err"; rc=$?
check "an unknown option exits 2 naming it" bash -c "[ $rc -eq 2 ] && grep -qF 'unknown option \"--frobnicate\"' '$tmp/opt.err'"
"$bin" simulate 2> "$tmp/nospec.err"; rc=$?
check "no spec exits 2 saying so" bash -c "[ $rc -eq 2 ] && grep -qF 'no spec given' '$tmp/nospec.err'"
"$bin" simulate "$tmp/decay.json" > /dev/full 2> "$tmp/full.err"; rc=$?
check "output that cannot be written (/dev/full) exits 1, never 0" \
  bash -c "[ $rc -eq 1 ] && grep -qF 'cannot write the output' '$tmp/full.err'"

# The input limit is 64 MiB exactly (docs/spec.md, "Limits"): a spec padded to 64 MiB is read, one byte more is not.
py "
import sys
spec = open('$tmp/decay.json').read().rstrip()
open('$tmp/max.json', 'w').write(spec + ' ' * (64 * 2**20 - len(spec)))
open('$tmp/over.json', 'w').write(spec + ' ' * (64 * 2**20 + 1 - len(spec)))
"
"$bin" simulate "$tmp/max.json" --format csv > "$tmp/max.csv" 2>&1; rc=$?
check "a 64 MiB spec is read" bash -c "[ $rc -eq 0 ] && cmp -s '$tmp/max.csv' '$tmp/out.csv'"
"$bin" simulate "$tmp/over.json" 2> "$tmp/over.err" >/dev/null; rc=$?
check "64 MiB + 1 byte is refused (exit 2, 'larger than 64 MiB')" \
  bash -c "[ $rc -eq 2 ] && grep -qF 'larger than 64 MiB' '$tmp/over.err'"
rm -f "$tmp/max.json" "$tmp/over.json"

# The well-posedness report prints numbers shortest (0.1, not 0.10000000000000001), witnesses included.
echo '{"model": {"mass": 1, "spring": {"law": "linear", "k": 0.1}, "damper": {"law": "graph", "points": [[-0.1, -1], [0, 0.3], [0.7, 0.1]]}}}' \
  | "$bin" wellposedness - > "$tmp/wp.json"
check "well-posedness: k = 0.1 and the witness (0, 0.3), (0.7, 0.1) printed shortest; only the failing check named" py "
import json
d = json.load(open('$tmp/wp.json'))
details = {c['hypothesis']: c['detail'] for c in d['checks']}
assert details['linear spring F_s = k x (Pražák & Rajagopal 2016, (1))'] == 'k = 0.1', details
assert details['A monotone (Pražák & Rajagopal 2016, (6))'].startswith('points (v, F) = (0, 0.3) and (0.7, 0.1) have'), details
assert d['existence']['reason'] == 'fails: A monotone (Pražák & Rajagopal 2016, (6))', d['existence']
assert '0000000' not in open('$tmp/wp.json').read()
"

# output.max_samples: every = ceil(steps / (N - 1)) keeps the samples at or under N (10^4 steps here).
for n in 2 3 10 999 1000 10001 20000; do
  sed "s/\"every\": 2000/\"max_samples\": $n/" "$tmp/decay.json" | "$bin" simulate - --format ndjson > "$tmp/budget.ndjson"
  check "max_samples $n: at most $n samples, more than half of them, every as in the meta line" py "
import json, math
rows = [json.loads(l) for l in open('$tmp/budget.ndjson')]
every = math.ceil(10000 / ($n - 1))
samples = sum(r['type'] == 'sample' for r in rows)
assert rows[0]['every'] == every, (rows[0]['every'], every)
assert samples == 10000 // every + 1 + (10000 % every != 0) <= $n, samples
assert samples >= min($n, 10001) / 2, samples
"
done
check "max_samples 10001 keeps every step (every 1)" py "
import json
rows = [json.loads(l) for l in open('$tmp/budget.ndjson')]
assert rows[0]['every'] == 1 and sum(r['type'] == 'sample' for r in rows) == 10001
"
for bad in '"max_samples": 1' '"max_samples": 2.5' '"max_samples": "many"' '"max_samples": 10, "every": 2'; do
  sed "s/\"every\": 2000/$bad/" "$tmp/decay.json" | "$bin" simulate - 2> "$tmp/budget.err" >/dev/null; rc=$?
  check "output {$bad} exits 2 naming /output/max_samples" \
    bash -c "[ $rc -eq 2 ] && grep -q '^dashpot: -: /output/max_samples: ' '$tmp/budget.err'"
done

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

# An elastoplastic spring's plastic offset p is a CSV column too (last, after phase), the same numbers as the
# NDJSON samples' "p"; a model without one keeps the old header.
cat > "$tmp/plastic.json" <<'JSON'
{"model": {"mass": 1, "spring": {"law": "elastoplastic", "k": 1, "yield": 0.5}, "damper": {"law": "none"}},
 "initial": {"x": 0, "v": 1}, "solver": {"dt": 0.01, "t_end": 3, "theta": 0.5}, "output": {"every": 50}}
JSON
"$bin" simulate "$tmp/plastic.json" --format csv > "$tmp/plastic.csv"
"$bin" simulate "$tmp/plastic.json" --format ndjson > "$tmp/plastic.ndjson"
check "csv of an elastoplastic spring: header ends in p, the values are the NDJSON samples' p" py "
import csv, json
rows = list(csv.DictReader(open('$tmp/plastic.csv')))
js = [json.loads(l) for l in open('$tmp/plastic.ndjson') if '\"sample\"' in l]
assert open('$tmp/plastic.csv').readline().strip() == 't,x,v,Fs,Fd,Fc,phase,p'
assert len(rows) == len(js) == 7 and [float(r['p']) for r in rows] == [s['p'] for s in js]
assert max(s['p'] for s in js) > 0.7   # it yielded
"
check "csv without samples still has its header" bash -c "sed 's/\"every\": 50/\"samples\": false/' '$tmp/plastic.json' | '$bin' simulate - --format csv | grep -qx 't,x,v,Fs,Fd,Fc,phase'"

# A damper graph whose stick interval at rest does not hold 0 ([-inf, -1] here: a vertical first piece): at
# the start the mass slips off it with the force at the bound it passes (-1), not a non-finite one
# (a fuzzer find; the interval's side used to be taken from the sign of the force needed).
cat > "$tmp/interval.json" <<'JSON'
{"model":{"mass":8,"spring":{"law":"graph","points":[[-0,-2],[0,0],[1,1],[1,5]]},"damper":{"law":"graph","points":[[-0,-9],[0,-1],[1,0],[1,2]],"belt_velocity":0.3}},"initial":{"x":0.5,"v":0.3},"solver":{"dt":0.005,"t_end":0.05}}
JSON
check "a stick interval without 0: the initial sample's damper force is its bound, -1" bash -c \
  "'$bin' simulate '$tmp/interval.json' --format csv | sed -n 2p | grep -qx '0,0.5,0.3,0.5,-1,-1,slip'"

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
