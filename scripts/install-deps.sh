#!/usr/bin/env bash
# scripts/install-deps.sh - installs the Debian 12 packages dashpot builds, tests and benchmarks with.
# Fast when everything is present (dpkg query only); installs the missing ones with apt-get as root,
# or prints the exact command when not root. Used by `make test`, `make run` and .ci/run.
set -euo pipefail
pkgs=(build-essential pkg-config python3 python3-yaml libgsl-dev liblapack-dev libcjson-dev libmicrohttpd-dev libcmocka-dev curl)
[ "${1:-}" = "--bench" ] && pkgs+=(wrk python3-numpy python3-scipy valgrind)
[ "${1:-}" = "--fuzz" ] && pkgs+=(clang libclang-rt-14-dev)
[ "${1:-}" = "--robustness" ] && pkgs+=(wrk valgrind)
[ "${1:-}" = "--siconos" ] && pkgs+=(libsiconos-kernel-dev g++)
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
