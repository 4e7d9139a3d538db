#!/usr/bin/env bash
# tests/test_docs.sh - the documentation stays true and self-contained.
#
# 1. Every `<!-- example -->` block of README.md and docs/*.md prints what it shows. A block is "$ COMMAND"
#    (continued on the next lines while a line ends with a backslash or a quote is open) and then the
#    expected output;
#    `...` in the expected output stands for text left out (any characters, across lines), everything else
#    must match byte for byte. `<!-- file: NAME -->` blocks are written to NAME first. Each document's
#    commands run in its own scratch directory, in order, with ./build/ pointing at this build and
#    localhost:8080 at a fresh test daemon of its own (so counters such as /metrics start at zero).
# 2. The README's dependency lists are scripts/install-deps.sh's, and `make run` installs no test tool.
# 3. Nothing tracked points outside the repository: no `../shared` or `shared/seeds` (the sources are cited
#    by title in docs/mathematics.md), and every relative link of a Markdown file names a tracked file
#    (web addresses of other projects are allowed).
source "$(dirname "$0")/lib/daemon.bash"

is() { [ "$1" = "$2" ] || { echo "    got '$1', expected '$2'"; return 1; }; }
is_empty() { [ -z "$1" ] || { printf '    %s\n' "$1" | head -20; return 1; }; }

# extract DOC DIR: writes DIR/cmdNN, DIR/wantNN, the file blocks, and DIR/count.
extract() {
    python3 - "$1" "$2" <<'PY'
import os, re, shlex, sys
text = open(sys.argv[1]).read()
out = sys.argv[2]
os.makedirs(out, exist_ok=True)
blocks = re.findall(r'<!-- (example|file: ([^ ]+)) -->\n```[a-z]*\n(.*?)```', text, re.S)
# The rendered page hides the markers: the prose just before each file block must name the file.
unnamed = [m.group(1) for m in re.finditer(r'<!-- file: ([^ ]+) -->', text)
           if '`' + m.group(1) + '`' not in text[max(0, m.start() - 400):m.start()]]
open(os.path.join(out, 'unnamed'), 'w').write(' '.join(unnamed))
n = 0
for kind, name, body in blocks:
    if kind.startswith('file'):
        open(os.path.join(out, name), 'w').write(body)
        continue
    lines = body.split('\n')
    assert lines[0].startswith('$ '), lines[0]
    cmd = [lines[0][2:]]
    def incomplete(text):  # a trailing backslash, or a quote still open
        try:
            shlex.split(text)
        except ValueError:
            return True
        return text.endswith('\\')
    while incomplete('\n'.join(cmd)):
        cmd.append(lines[len(cmd)])
    n += 1
    open(os.path.join(out, 'cmd%02d' % n), 'w').write('\n'.join(cmd) + '\n')
    open(os.path.join(out, 'want%02d' % n), 'w').write('\n'.join(lines[len(cmd):]))
print(n, file=open(os.path.join(out, 'count'), 'w'))
PY
}

# matches WANT GOT: GOT is WANT with each `...` standing for any text; else the difference, and status 1.
matches() {
    python3 - "$1" "$2" <<'PY' && return 0
import re, sys
want, got = open(sys.argv[1]).read(), open(sys.argv[2]).read()
pattern = '.*?'.join(re.escape(piece) for piece in want.split('...'))
sys.exit(0 if re.fullmatch(pattern, got, re.S) else 1)
PY
    diff "$1" "$2" | head -10 | cut -c1-300 | sed 's/^/    /'
    return 1
}

run_examples() { # run_examples DOC: every example of one document against its own daemon
    local doc=$1 name dir count i cmd
    name=$(basename "$doc" .md)
    name=${name//-/_} # a daemon's name is part of shell variable names
    dir=$SCRATCH/$name
    extract "$ROOT/$doc" "$dir"
    count=$(cat "$dir/count")
    check "$doc: the text before each file block says to save it under its name" is_empty "$(cat "$dir/unnamed")"
    [ "$count" -gt 0 ] || return 0
    start_daemon "$name" || return 1
    local port_var=PORT_$name
    mkdir -p "$dir/build"
    ln -s "$BUILD/dashpot" "$dir/build/dashpot"
    for i in $(seq -f %02g "$count"); do
        cmd=$(sed "s/localhost:8080/127.0.0.1:${!port_var}/g" "$dir/cmd$i")
        (cd "$dir" && timeout 60 bash -c "$cmd") >"$dir/got$i" 2>&1
        check "$doc example $i: $(head -1 "$dir/cmd$i" | head -c 70)" matches "$dir/want$i" "$dir/got$i"
    done
    stop_daemon "$name"
    EXAMPLES=$((EXAMPLES + count))
}

EXAMPLES=0
for doc in README.md docs/*.md; do
    run_examples "$doc"
done
check "the README and docs have examples ($EXAMPLES)" test "$EXAMPLES" -ge 20

# ---- the dependency lists: `make run` installs no test tool, and the README names what the script installs ----
run_deps=$(bash "$ROOT/scripts/install-deps.sh" --list --run)
test_deps=$(bash "$ROOT/scripts/install-deps.sh" --list)
check "make run installs only what builds and runs (no libcmocka-dev, curl, python3): $run_deps" \
    bash -c "! grep -qwE 'libcmocka-dev|curl|python3' <<<'$run_deps' && grep -qw libmicrohttpd-dev <<<'$run_deps'"
check "make run calls install-deps.sh --run" \
    bash -c "cd '$ROOT' && make -n run 2>/dev/null | grep -m1 install-deps | grep -qx 'bash scripts/install-deps.sh --run'"
readme_deps() { # the README's package list after "$1 needs"/"$1 adds", backquoted, on one line
    python3 - "$ROOT/README.md" "$1" <<'PY'
import re, sys
text = re.sub(r'\s+', ' ', open(sys.argv[1]).read())
m = re.search(re.escape(sys.argv[2]) + r' (?:needs|adds) `([^`]*)`', text)
print(m.group(1) if m else '')
PY
}
check "the README's make run list is the script's --run list" is "$(readme_deps '`make run`')" "$run_deps"
check "the README's make test list adds what the script adds" is "$run_deps $(readme_deps '`make test`')" "$test_deps"

# ---- self-contained ----
cd "$ROOT" || finish
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    # .ci/ belongs to the machinery around the repository; this file names the patterns it looks for.
    outside=$(git ls-files -z | grep -zv -e '^\.ci/' -e '^tests/test_docs\.sh$' |
              xargs -0 grep -lIE '\.\./shared|shared/seeds' 2>/dev/null)
    check "no tracked file points outside the repository (../shared, shared/seeds)" is_empty "$outside"
    broken=$(git ls-files '*.md' | python3 -c '
import os, re, subprocess, sys
tracked = set(subprocess.run(["git", "ls-files"], capture_output=True, text=True).stdout.split("\n"))
dirs = {os.path.dirname(p) for p in tracked} | {""}
for doc in sys.stdin.read().split():
    text = open(doc).read()
    for target in re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", text):
        if re.match(r"https?://", target):
            continue
        path = os.path.normpath(os.path.join(os.path.dirname(doc), target))
        if path.startswith("..") or (path not in tracked and path not in dirs):
            print(doc, "->", target)')
    check "every relative link in the Markdown files names a tracked file or directory" is_empty "$broken"
else
    echo "# not a git checkout: the self-containment checks are skipped"
fi
finish
