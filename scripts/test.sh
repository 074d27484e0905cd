#!/usr/bin/env bash
# README command 2: install what is missing, build everything, and run every test
# (labels: model, sc, rtl, peer, slow, tools).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake --preset default
cmake --build --preset default
ctest --preset default "$@"
