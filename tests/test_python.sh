#!/usr/bin/env bash
# tests/test_python.sh - the Python client (python/) and the notebook (notebooks/first-day.ipynb) against a
# live daemon of this build ($BUILD/dashpotd):
#
# 1. The package installs offline with Debian 12's own packages, as python/README.md says: a venv made with
#    --system-site-packages (numpy, requests, setuptools, pip from Debian), then
#    `pip install --no-index --no-build-isolation` of a copy of python/ (a copy, so the install's build/ and
#    egg-info never land in the checkout). Everything below runs that installed copy, not the source tree.
# 2. pytest python/tests: numbers against closed forms and numpy references, errors, streams, the daemon's
#    life cycle, plots (python/tests/*.py say what each asserts). Passes only with exit status 0, at least
#    MIN_TESTS tests run and none skipped (pytest exits 5 when it collects nothing; a skip would hide a
#    missing optional package).
# 3. The notebook, committed without outputs, executed headlessly by nbclient in a kernel of that venv; every
#    computing cell asserts its numbers, so a wrong number fails a cell and the check.
# 4. No dashpotd started here is left running.
#
# Env BUILD (default build); DASHPOT_PYTHON: the interpreter with Debian's packages (default /usr/bin/python3:
# a python3 earlier on PATH, e.g. pyenv's, does not see them). Prints "N passed, M failed"; exit 1 on failure.
source "$(dirname "$0")/lib/daemon.bash"

MIN_TESTS=30
PY=${DASHPOT_PYTHON:-/usr/bin/python3}
[ -x "$PY" ] || PY=$(command -v python3)
VENV=$SCRATCH/venv
export PYTHONDONTWRITEBYTECODE=1   # no __pycache__ in python/tests or the notebook's imports
export MPLBACKEND=Agg
export PYDEVD_DISABLE_FILE_VALIDATION=1  # quiets ipykernel's debugger warning about frozen modules
export DASHPOT_DAEMON=$DAEMON      # dashpot.Client() starts this build's daemon

# The dashpotd processes of this build that are running now, one pid a line (to find leftovers at the end):
# pgrep lists every dashpotd by name (other checkouts' too), the executable's path picks this build's.
DAEMON_REAL=$(readlink -f "$DAEMON")
our_daemons() {
    local p
    for p in $(pgrep -x dashpotd); do
        [ "$(readlink "/proc/$p/exe" 2>/dev/null)" = "$DAEMON_REAL" ] && echo "$p"
    done | sort
}
before=$(our_daemons)

[ -x "$DAEMON" ] || { echo "not ok - $DAEMON not built"; exit 1; }
missing=$("$PY" -c '
import importlib.util
need = "numpy requests setuptools pip pytest pandas matplotlib tqdm nbclient nbformat ipykernel".split()
print(" ".join(m for m in need if importlib.util.find_spec(m) is None))')
check "$PY has Debian's packages the client and its tests need (missing: ${missing:-none})" test -z "$missing"
[ -z "$missing" ] || finish

# ---- 1. install offline ----
cp -r "$ROOT/python" "$SCRATCH/src"
rm -rf "$SCRATCH/src/build" "$SCRATCH/src/"*.egg-info
"$PY" -m venv --without-pip --system-site-packages "$VENV" >"$SCRATCH/venv.log" 2>&1 &&
    "$VENV/bin/python" -m pip install --no-index --no-build-isolation --disable-pip-version-check --quiet \
        "$SCRATCH/src" >>"$SCRATCH/venv.log" 2>&1
rc=$?
check "pip install --no-index --no-build-isolation ./python into a venv with Debian's site packages" test $rc = 0
[ $rc = 0 ] || { sed 's/^/    /' "$SCRATCH/venv.log" | tail -20; finish; }
installed=$(cd "$SCRATCH" && "$VENV/bin/python" -c 'import dashpot; print(dashpot.__file__)')
check "the venv imports the installed copy ($installed)" \
    bash -c "[[ '$installed' == '$VENV'/lib/*/site-packages/dashpot/__init__.py ]]"

# ---- 2. pytest ----
(cd "$SCRATCH" && "$VENV/bin/python" -m pytest -p no:cacheprovider -q -rs --junitxml="$SCRATCH/junit.xml" \
    "$ROOT/python/tests") >"$SCRATCH/pytest.log" 2>&1
rc=$?
sed 's/^/    /' "$SCRATCH/pytest.log" | grep -v '^    $' | tail -40
counts=$("$PY" -c '
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
suite = root if root.tag == "testsuite" else root.find("testsuite")
print(*(int(suite.get(k, 0)) for k in ("tests", "failures", "errors", "skipped")))' "$SCRATCH/junit.xml" 2>/dev/null)
read -r n_tests n_failed n_errors n_skipped <<<"${counts:-0 0 0 0}"
summary=$(grep -E '^[0-9]+ (passed|failed)|passed|failed|error' "$SCRATCH/pytest.log" | tail -1)
check "pytest exit status 0 (got $rc)" test "$rc" = 0
check "pytest ran at least $MIN_TESTS tests, none failed or skipped ($n_tests run, $n_failed failed, $n_errors errors, $n_skipped skipped)" \
    test "$n_tests" -ge $MIN_TESTS -a "$n_failed" = 0 -a "$n_errors" = 0 -a "$n_skipped" = 0

# ---- 3. the notebook ----
"$VENV/bin/python" -m ipykernel install --prefix "$VENV" --name dashpot-test >/dev/null 2>&1
start=$(date +%s)
(cd "$SCRATCH" && "$VENV/bin/python" - "$ROOT/notebooks/first-day.ipynb" <<'PY') >"$SCRATCH/notebook.log" 2>&1
import os, sys
import nbclient, nbformat
path = sys.argv[1]
nb = nbformat.read(path, as_version=4)
nbformat.validate(nb)
code = [c for c in nb.cells if c.cell_type == "code"]
dirty = [i for i, c in enumerate(code) if c.outputs or c.execution_count is not None]
assert not dirty, "code cells committed with outputs: %s" % dirty
asserting = sum("assert " in c.source for c in code)
print("%d code cells, %d of them assert" % (len(code), asserting))
assert asserting >= 5, "the notebook's computing cells should assert their numbers"
client = nbclient.NotebookClient(nb, kernel_name="dashpot-test", timeout=120, allow_errors=False,
                                 resources={"metadata": {"path": os.path.dirname(path)}})
try:
    client.execute()
except nbclient.exceptions.CellExecutionError as e:
    print(e)
    sys.exit(1)
print("every cell ran")
PY
rc=$?
sed 's/^/    /' "$SCRATCH/notebook.log" | tail -30
check "notebooks/first-day.ipynb: no outputs committed, every cell runs and its asserts hold ($(( $(date +%s) - start )) s)" test $rc = 0

# ---- 4. nothing left running ----
leftover=$(comm -13 <(echo "$before") <(our_daemons) | grep .)
check "no dashpotd started by the client or the notebook is left running${leftover:+ (pids: $leftover)}" test -z "$leftover"
for p in $leftover; do kill -TERM "$p" 2>/dev/null; done

echo "pytest: ${summary:-no summary line}"
finish
