#!/usr/bin/env bash
# The main job on the embedded defaults; writes into $1 (default out/), with $1/README.md the index
# a reader opens first: what each file is, which doc explains it, and the render's figures.
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-out}
mkdir -p "$OUT"
FXR=${FXR:-build/app/fxraster}  # FXR=path: another build's binary
"$FXR" config --emit-json "$OUT/config.json" --emit-md "$OUT/config.md"
# Every unit of the registries (model/vectors/vectors.cpp, app/cmd_sweep.cpp): adding a unit there
# adds it here.
VEC_UNITS=$("$FXR" vectors --list)
SWEEP_UNITS=$("$FXR" sweep --list)
for u in $VEC_UNITS; do "$FXR" vectors "$u" --seed 1 --count 100000 --out "$OUT/vectors/$u"; done
for u in $SWEEP_UNITS; do "$FXR" sweep "$u" --quick --out "$OUT/sweep/$u"; done  # error vs cost: report.md + plots
RENDER=$("$FXR" render --default --out "$OUT/render")  # image, depth, fragments, report.md
echo "$RENDER"

{
  echo "# fxraster: the main job's output"
  echo
  echo "Written by \`bash scripts/main_job.sh\` (README command 1, \`bash scripts/setup.sh\`), $("$FXR" --version)$(
    git rev-parse --short HEAD 2> /dev/null | sed 's/^/, commit /'). Every figure comes from the"
  echo "bit-accurate model at the default configuration; the docs named below explain each file."
  echo
  echo "| what | file | explained in |"
  echo "|---|---|---|"
  echo "| the default scene (a checkerboard face at an angle and the Stanford bunny) through the model and a double-precision reference: the shaded image, depth, the affine image (the wrong one), the texel-error heat map, and the error report | [render/report.md](render/report.md), [render/image.png](render/image.png) | docs/reports.md \"Render output\" |"
  echo "| the configuration: every number format and unit parameter (the RTL's \`fxr_config_pkg\` is generated from it) | [config.md](config.md), [config.json](config.json) | docs/number-formats.md, docs/config-table.md |"
  for u in $VEC_UNITS; do
    echo "| golden vectors of \`$u\`: directed corner cases then 100,000 random cases, one hex word per line for \`\$readmemh\`, fields named in the manifest | [vectors/$u/$u.hex](vectors/$u/$u.hex), [vectors/$u/$u.json](vectors/$u/$u.json) | docs/vectors.md |"
  done
  for u in $SWEEP_UNITS; do
    echo "| \`$u\`: error against cost (latency, table bits, multipliers) over its configuration sweep, Pareto fronts and plots | [sweep/$u/report.md](sweep/$u/report.md) | docs/reports.md |"
  done
  echo
  echo "## The render in figures"
  echo
  echo '```'
  echo "$RENDER"
  echo '```'
  echo
  echo "ulp: of the output format's significand; LSB: of the depth code; \"exact (snapped)\": exact arithmetic on the"
  echo "model's own snapped triangle (GMP), i.e. how well each rounding is done; \"double reference\": the unsnapped ideal."
  echo "The model's time is the model alone; the reference's is the double-precision renderer (same run)."
} > "$OUT/README.md"
echo "main job: wrote $OUT/ (index: $OUT/README.md)"
