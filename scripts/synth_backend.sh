#!/bin/bash
# LUT4 / flip-flop / logic-depth figure of the raster back end rtl/fxr_raster_backend.sv and of
# its stages (docs/rtl.md, "fxr_raster_backend"):
#   yosys: read_verilog -sv build/gen/fxr_config_pkg.sv build/gen/fxr_rec_pkg.sv rtl/<the modules>;
#          synth -flatten -noabc -top TOP; abc -lut 4 -fast; opt_clean; stat; ltp -noff
# `abc -lut 4 -fast` (ABC's short script, as scripts/synth_texaddr.sh FAST=1) and no ABC run inside
# synth: the full script does not finish on the wide datapaths (fxr_setup's plane products: about
# 700,000 gates) within the time the shared machine gives.
# Usage: scripts/synth_backend.sh GEN_DIR OUTDIR [TOP ...]   (default TOP: fxr_raster_backend)
#   GEN_DIR: the folder of the generated packages (build/gen).
#   CONFIG_PKG=F: another fxr_config_pkg.sv (e.g. build/gen/variants/div_shared_recip/fxr_config_pkg.sv:
#   the back end with fxr_divide's shared_recip algorithm); default GEN_DIR/fxr_config_pkg.sv.
# Prints one line per top: "<top> lut4=N ff=N depth=N seconds=S". Runs under nice -n 19; each top
# is bounded by `timeout ${SYNTH_TIMEOUT:-1200}` seconds. Results are cached in OUTDIR/cache/<key>
# (key: sha256 of the flow, the top and the text of every package and source), so a rerun on
# unchanged RTL prints the stored line at once ("cached").
set -euo pipefail
gen=$(realpath "$1"); out=$(realpath -m "$2"); shift 2
tops=("$@"); [ ${#tops[@]} -eq 0 ] && tops=(fxr_raster_backend)
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
srcs=""
cfg_pkg=$(realpath "${CONFIG_PKG:-$gen/fxr_config_pkg.sv}")
for m in fxr_pipe fxr_setup_align fxr_setup_edges fxr_setup_attr fxr_setup_plane fxr_setup_fields fxr_setup \
         fxr_traverse fxr_interp fxr_depth fxr_divide fxr_divide_norm fxr_norm_log fxr_div fxr_div_align fxr_div_radix2 \
         fxr_div_radix2_pre fxr_div_radix2_post fxr_div_recip_mul fxr_div_shared_recip \
         fxr_seed_rom fxr_nr_step fxr_round fxr_raster_backend; do
  srcs="$srcs $root/rtl/$m.sv"
done
mkdir -p "$out/cache"
for top in "${tops[@]}"; do
  script="read_verilog -sv $cfg_pkg $gen/fxr_rec_pkg.sv $srcs; synth -flatten -noabc -top $top; abc -lut 4 -fast; opt_clean; stat; ltp -noff"
  key=$( { echo "$script" | sed "s|$root/||g; s|$gen/||g; s|$cfg_pkg||g"; cat "$cfg_pkg" "$gen/fxr_rec_pkg.sv" $srcs; } | sha256sum | cut -c1-16)
  if [ -s "$out/cache/$top-$key" ]; then
    echo "$(cat "$out/cache/$top-$key") (cached)"
    continue
  fi
  log="$out/$top.log"
  start=$(date +%s)
  if ! nice -n 19 timeout "${SYNTH_TIMEOUT:-1200}" yosys -q -l "$log" -p "$script" >/dev/null 2>&1; then
    echo "$top failed or timed out after $(( $(date +%s) - start )) s (log $log)"
    continue
  fi
  secs=$(( $(date +%s) - start ))
  # the last statistics (synth prints its own before abc): LUTs and every flip-flop cell type
  last() { awk '/Printing statistics/ {buf=""} {buf=buf $0 "\n"} END {printf "%s", buf}' "$log"; }
  lut=$(last | grep -E '^\s+\$lut\s' | tail -1 | awk '{print $2}')
  ff=$(last | grep -E '^\s+\$_(S)?DFF' | awk '{s+=$2} END {print s+0}')
  depth=$(grep -Eo 'Longest topological path in .* \(length=[0-9]+\)' "$log" | grep -Eo '[0-9]+\)$' | tr -d ')')
  echo "$top lut4=${lut:-?} ff=$ff depth=${depth:-?} seconds=$secs" | tee "$out/cache/$top-$key"
done
