#!/usr/bin/env bash
# scripts/gallery.sh - redraws the README's gallery, docs/images/*.png, from the CLI's output.
# Usage: scripts/gallery.sh [DASHPOT_BINARY [OUT_DIR]] (default build/dashpot and docs/images; `make gallery`
# builds first). Installs python3-matplotlib if missing (scripts/install-deps.sh --gallery) and draws with
# Debian's /usr/bin/python3 (PYTHON=... to use another interpreter that has matplotlib). The pictures are
# reproducible: the documents are fixed in scripts/gallery.py, nothing is random, and the PNGs carry no time
# stamp or version string, so the same build and packages give the same bytes (`git diff --stat docs/images`
# after a run shows whether a change of the solvers moved a picture).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/dashpot}
out=${2:-$root/docs/images}
[ -x "$bin" ] || { echo "gallery.sh: no $bin: run make first (or make gallery)" >&2; exit 1; }
bash "$root/scripts/install-deps.sh" --gallery
"${PYTHON:-/usr/bin/python3}" "$root/scripts/gallery.py" "$bin" "$out"
