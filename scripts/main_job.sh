#!/usr/bin/env bash
# The main job on the embedded defaults; writes into $1 (default out/).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-out}
mkdir -p "$OUT"
FXR=build/app/fxraster
"$FXR" config --emit-json "$OUT/config.json" --emit-md "$OUT/config.md"
# Every unit of the registries (model/vectors/vectors.cpp, app/cmd_sweep.cpp): adding a unit there
# adds it here.
for u in $("$FXR" vectors --list); do "$FXR" vectors "$u" --seed 1 --count 100000 --out "$OUT/vectors/$u"; done
for u in $("$FXR" sweep --list); do "$FXR" sweep "$u" --quick --out "$OUT/sweep/$u"; done  # error vs cost: report.md + plots
"$FXR" render --default --quiet --out "$OUT/render"  # image, depth, fragments, report.md
echo "main job: wrote $OUT/"
