# tests/corpus/daemons.bash - the two daemons the corpus runs against, for record.sh and tests/test_corpus.sh
# (sourced after tests/lib/daemon.bash):
#   corpus       the default limits, no token: the POST and GET cases of cases.tsv
#   corpus_fuzz  tests/fuzz/fuzz_http.c's bearer token (fuzz-token) and small limits (2000 steps, 16 KiB of
#                body, 400 map points), for the raw requests of tests/fuzz/corpus-http they were written for;
#                not its 0.25 s of wall time, which would make answers depend on the machine's speed.
start_corpus_daemons() {
    start_daemon corpus || return 1
    DASHPOT_TOKEN=fuzz-token start_daemon corpus_fuzz --max-steps 2000 --body-limit 16384 --max-map-points 400 ||
        return 1
}
stop_corpus_daemons() {
    stop_daemon corpus
    stop_daemon corpus_fuzz
}
