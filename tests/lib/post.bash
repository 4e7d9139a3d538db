# tests/lib/post.bash - shared by the shell tests that POST documents to a test daemon and check the answers
# with python3 (not the program's own parser). Sourced after tests/lib/daemon.bash.
#
#   req URL ACCEPT DATA     POSTs DATA (through a file: a large matrix is over ARG_MAX); STATUS, $BODY, $HDRS
#   header NAME             that response header's value
#   is GOT WANT             equal strings, or prints both
#   py FILE CODE            the python CODE (asserts) holds with `text` = FILE's content and `loads`, a JSON
#                           reader that refuses NaN and Infinity; prints the failed assert
#   doc_examples DOC NAME   runs the `<!-- example -->` blocks of the Markdown file DOC (after writing its
#                           `<!-- file: -->` blocks) against daemon NAME and checks each prints what it shows
BODY=$SCRATCH/body
HDRS=$SCRATCH/headers

req() {
    printf '%s' "$3" >"$SCRATCH/request"
    STATUS=$(hcurl -D "$HDRS" -o "$BODY" -w '%{http_code}' -H "Accept: $2" --data-binary @"$SCRATCH/request" "$1")
}
header() { grep -i "^$1:" "$HDRS" | head -1 | cut -d: -f2- | tr -d '\r' | sed 's/^ *//'; }
is() { [ "$1" = "$2" ] || { echo "    got '$1', expected '$2'"; return 1; }; }
py() {
    python3 - "$1" "$2" <<'PY' || return 1
import json, math, sys
text = open(sys.argv[1]).read()
def no_constant(c):
    raise ValueError("JSON holds " + c)
loads = lambda s: json.loads(s, parse_constant=no_constant)
try:
    exec(sys.argv[2])
except AssertionError as e:
    print("    " + (str(e) or "assertion failed")[:600]); sys.exit(1)
except Exception as e:
    print("    " + type(e).__name__ + ": " + str(e)[:600]); sys.exit(1)
PY
}

# The README's conventions (tests/test_docs.sh): `$ ./build/dashpot ...` on the block's first line, then what
# it prints; `localhost:8080` stands for the test daemon.
doc_examples() {
    local doc=$1 name=$2 dir=$SCRATCH/doc-$2 port_var=PORT_$2 count i cmd
    mkdir -p "$dir/build"
    ln -sf "$BUILD/dashpot" "$dir/build/dashpot"
    python3 - "$doc" "$dir" <<'PY'
import os, re, sys
text, out = open(sys.argv[1]).read(), sys.argv[2]
n = 0
for kind, name, body in re.findall(r'<!-- (example|file: ([^ ]+)) -->\n```[a-z]*\n(.*?)```', text, re.S):
    if kind.startswith('file'):
        open(os.path.join(out, name), 'w').write(body)
        continue
    cmd, _, expected = body.partition('\n')
    n += 1
    open(os.path.join(out, 'cmd%02d' % n), 'w').write(cmd[2:] + '\n')
    open(os.path.join(out, 'want%02d' % n), 'w').write(expected)
open(os.path.join(out, 'count'), 'w').write(str(n))
PY
    count=$(cat "$dir/count")
    check "$(basename "$doc") has examples ($count)" test "$count" -ge 2
    for i in $(seq -f %02g "$count"); do
        cmd=$(sed "s/localhost:8080/127.0.0.1:${!port_var}/g" "$dir/cmd$i")
        (cd "$dir" && timeout 30 bash -c "$cmd") >"$dir/got$i" 2>&1
        if ! check "$(basename "$doc") example $i: $(head -c 70 "$dir/cmd$i")" cmp -s "$dir/got$i" "$dir/want$i"; then
            diff "$dir/want$i" "$dir/got$i" | head -10 | sed 's/^/    /'
        fi
    done
}
