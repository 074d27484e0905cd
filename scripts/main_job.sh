#!/usr/bin/env bash
# The main job on the embedded defaults; writes into $1 (default out/).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-out}
mkdir -p "$OUT"
FXR=build/app/fxraster
"$FXR" config --emit-json "$OUT/config.json" --emit-md "$OUT/config.md"
echo "main job: wrote $OUT/"
