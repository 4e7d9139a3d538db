#!/usr/bin/env bash
# scripts/install-deps.sh - installs the Debian 12 packages dashpot builds, tests and benchmarks with.
# Fast when everything is present (dpkg query only); installs the missing ones with apt-get as root,
# or prints the exact command when not root. Used by `make test` (no argument: build and test),
# `make run` (--run: only what building and running needs), the benchmarks and .ci/run.
# --list [--run|--bench|...] prints the packages instead of installing them (tests/test_docs.sh compares
# them with the README).
set -euo pipefail
list=0
[ "${1:-}" = "--list" ] && { list=1; shift; }
pkgs=(build-essential pkg-config libgsl-dev libcjson-dev libmicrohttpd-dev)   # build and run (the image's build stage)
test_pkgs=(python3 python3-yaml libcmocka-dev liblapack-dev curl               # the tests add these (LAPACK: test_modes.c's
           libsiconos-kernel-dev g++                                         # reference; Siconos: tests/test_siconos.sh;
           python3-numpy python3-requests python3-pytest python3-pandas      # the Python client and its notebook:
           python3-matplotlib python3-tqdm python3-nbclient python3-nbformat # tests/test_python.sh, which installs
           python3-ipykernel python3-setuptools python3-wheel python3-pip    # python/ offline into a venv)
           python3-venv python3-distributed)                                 # Dask: python/tests/test_sweep.py
[ "${1:-}" = "--run" ] || pkgs+=("${test_pkgs[@]}")
[ "${1:-}" = "--bench" ] && pkgs+=(wrk python3-numpy python3-scipy valgrind)
[ "${1:-}" = "--fuzz" ] && pkgs+=(clang libclang-rt-14-dev)
[ "${1:-}" = "--robustness" ] && pkgs+=(wrk valgrind)
[ "${1:-}" = "--siconos" ] && pkgs+=(libsiconos-kernel-dev g++)
[ "${1:-}" = "--image" ] && pkgs+=(podman debootstrap)
[ "${1:-}" = "--gallery" ] && pkgs+=(python3-matplotlib)                    # scripts/gallery.sh
[ $list = 1 ] && { echo "${pkgs[*]}"; exit 0; }
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
if [ "$(id -u)" -ne 0 ]; then
  echo "missing Debian packages: ${missing[*]}" >&2
  echo "install them with: sudo apt-get update && sudo apt-get install -y ${missing[*]}" >&2
  exit 1
fi
echo "installing: ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
