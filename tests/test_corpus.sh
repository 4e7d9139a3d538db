#!/usr/bin/env bash
# tests/test_corpus.sh - the regression guard: every request document a user can send (frozen in
# tests/corpus/inputs/ from the README and docs/ examples, api/openapi.yaml, tests/fuzz/, the shell tests and
# the page's presets), run through `dashpot` in every format its command has and through dashpotd in every
# media type its route offers (tests/corpus/cases.tsv), must answer bit for bit as recorded in
# tests/corpus/answers/ - exit status, stderr and stdout; HTTP status line, headers and body - after masking
# only the version and the HTTP headers that carry the time or the framing (tests/corpus/corpus.py says what
# and why). A failure prints the case and a short diff of what changed.
#
# A change of an answer that is intended is re-recorded with `make corpus` (tests/corpus/record.sh) and
# described in CHANGELOG.md; tests/corpus/README.md says how. Env BUILD (default build); CORPUS_JOBS cases at
# once (default 2). Prints "N passed, M failed" (one per case, and the daemons' exits); exit 1 on any failure.
source "$(dirname "$0")/lib/daemon.bash"
source "$ROOT/tests/corpus/daemons.bash"
CORPUS=$ROOT/tests/corpus

[ -x "$BUILD/dashpot" ] || { echo "not ok - $BUILD/dashpot not built"; FAILED=$((FAILED + 1)); finish; }
start_corpus_daemons || finish
t0=$(date +%s.%N)
python3 "$CORPUS/corpus.py" run "$SCRATCH/got" "$BUILD/dashpot" "$URL_corpus" "$URL_corpus_fuzz"
python3 "$CORPUS/corpus.py" compare "$CORPUS/answers" "$SCRATCH/got" "$SCRATCH/counts"
echo "    $(ls "$SCRATCH/got" | wc -l) answers in $(echo "$(date +%s.%N) - $t0" | bc) s"
read -r p f <"$SCRATCH/counts" 2>/dev/null || { p=0; f=1; echo "not ok - the corpus did not run"; }
PASSED=$((PASSED + p))
FAILED=$((FAILED + f))
stop_corpus_daemons
check "the daemons exit 0 on SIGTERM (no sanitizer report)" [ "$RC_corpus $RC_corpus_fuzz" = "0 0" ]
finish
