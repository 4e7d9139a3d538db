#!/usr/bin/env bash
# tests/test_readme.sh - the README's examples print what the README shows. Each `<!-- example -->` block
# is "$ COMMAND" then the expected output; `<!-- file: NAME -->` blocks are written to NAME first. Commands
# run in a scratch directory with ./build/ pointing at this build and localhost:8080 at a test daemon.
source "$(dirname "$0")/lib/daemon.bash"

start_daemon readme || finish
python3 - "$ROOT/README.md" "$SCRATCH/examples" <<'PY'
import os, re, sys
text = open(sys.argv[1]).read()
out = sys.argv[2]
os.makedirs(out, exist_ok=True)
blocks = re.findall(r'<!-- (example|file: ([^ ]+)) -->\n```[a-z]*\n(.*?)```', text, re.S)
n = 0
for kind, name, body in blocks:
    if kind.startswith('file'):
        open(os.path.join(out, name), 'w').write(body)
        continue
    cmd, _, expected = body.partition('\n')
    assert cmd.startswith('$ '), cmd
    n += 1
    open(os.path.join(out, 'cmd%02d' % n), 'w').write(cmd[2:] + '\n')
    open(os.path.join(out, 'want%02d' % n), 'w').write(expected)
print(n, file=open(os.path.join(out, 'count'), 'w'))
PY
count=$(cat "$SCRATCH/examples/count")
check "the README has examples ($count)" test "$count" -ge 4
mkdir -p "$SCRATCH/examples/build"
ln -s "$BUILD/dashpot" "$SCRATCH/examples/build/dashpot"
for i in $(seq -f %02g "$count"); do
    cmd=$(sed "s/localhost:8080/127.0.0.1:$PORT_readme/g" "$SCRATCH/examples/cmd$i")
    (cd "$SCRATCH/examples" && timeout 30 bash -c "$cmd") > "$SCRATCH/got$i" 2>&1
    if ! check "README example $i: $(head -c 70 "$SCRATCH/examples/cmd$i")" cmp -s "$SCRATCH/got$i" "$SCRATCH/examples/want$i"; then
        diff "$SCRATCH/examples/want$i" "$SCRATCH/got$i" | head -10 | sed 's/^/    /'
    fi
done
stop_daemon readme
finish
