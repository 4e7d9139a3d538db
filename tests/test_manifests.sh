#!/usr/bin/env bash
# tests/test_manifests.sh - the container and Kubernetes files checked without a container engine or a cluster
# (hadolint and kubeconform are in neither Debian nor npm): the manifests parse and agree with each other and
# with the daemon (probe paths and ports, DASHPOT_* variables that src/http/config.c reads, values the daemon
# accepts), resources, the hardening of every pod, the HPA's target, the Service's selector, the shutdown
# timeline, the sweep Job's size; the Dockerfile's stages, user, HEALTHCHECK and runtime packages (against the
# shared libraries the binaries need); and the image's build stage, run from exactly the .dockerignore'd
# context. Prints "N passed, M failed"; the scratch tree is removed on any exit; every command is bounded.
cd "$(dirname "$0")/.." || exit 1
exec python3 tests/lib/check_manifests.py "${BUILD:-build}"
