#!/usr/bin/env bash
# tests/corpus/record.sh - records the answer corpus (tests/corpus/README.md) from the current build: every case
# of tests/corpus/cases.tsv run with $BUILD/dashpot and daemons from $BUILD/dashpotd, masked, stored in
# tests/corpus/answers/ (what tests/test_corpus.sh compares against). `make corpus` runs it. Re-record only
# for an intended change of behaviour, and describe that change in CHANGELOG.md.
#
#   record.sh            re-records the answers from the frozen inputs (tests/corpus/inputs/)
#   record.sh --inputs   first gathers the inputs afresh from README.md, docs/, api/openapi.yaml, tests/fuzz/,
#                        the shell tests and web/presets.js (needs node and python3-yaml), rewriting inputs/ and
#                        cases.tsv: for new examples; `git diff tests/corpus` shows what changed
#   record.sh --twice    also records a second time and compares: the answers must not vary from run to run
# Env BUILD (default build).
source "$(dirname "$0")/../lib/daemon.bash"
source "$ROOT/tests/corpus/daemons.bash"
CORPUS=$ROOT/tests/corpus
inputs=0 twice=0
for a in "$@"; do
    case $a in
    --inputs) inputs=1 ;;
    --twice) twice=1 ;;
    *) echo "usage: record.sh [--inputs] [--twice]" >&2; exit 2 ;;
    esac
done
[ -x "$BUILD/dashpot" ] && [ -x "$BUILD/dashpotd" ] || { echo "record.sh: build $BUILD first (make all)" >&2; exit 1; }
if [ $inputs = 1 ]; then
    python3 "$CORPUS/corpus.py" gather || exit 1
fi
start_corpus_daemons || exit 1
t0=$(date +%s.%N)
python3 "$CORPUS/corpus.py" run "$SCRATCH/one" "$BUILD/dashpot" "$URL_corpus" "$URL_corpus_fuzz" || exit 1
echo "recorded in $(echo "$(date +%s.%N) - $t0" | bc) s"
if [ $twice = 1 ]; then
    python3 "$CORPUS/corpus.py" run "$SCRATCH/two" "$BUILD/dashpot" "$URL_corpus" "$URL_corpus_fuzz" || exit 1
    python3 "$CORPUS/corpus.py" store "$SCRATCH/one" "$SCRATCH/stored" 2>/dev/null || exit 1
    if python3 "$CORPUS/corpus.py" compare "$SCRATCH/stored" "$SCRATCH/two" >"$SCRATCH/twice"; then
        echo "recorded twice: the same answers"
    else
        grep -v '^    corpus:' "$SCRATCH/twice"
        echo "record.sh: two recordings differ: something in them is not deterministic (see above)" >&2
        exit 1
    fi
fi
stop_corpus_daemons
python3 "$CORPUS/corpus.py" store "$SCRATCH/one" "$CORPUS/answers"
