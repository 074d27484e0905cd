#!/bin/bash
# LUT4 / flip-flop / logic-depth figures of the whole raster unit rtl/fxr_raster_unit.sv and of
# every module under it, from ONE hierarchical Yosys run (docs/rtl.md, "fxr_raster_unit: area"):
#   yosys: read_verilog -sv PKG RECPKG rtl/<every module of the unit>;
#          synth -noabc -top fxr_raster_unit; abc -lut 4 -fast; opt_clean; stat; ltp -noff
# Hierarchical, not flattened: each module (each parameterisation) is mapped once and `stat`
# gives its own count and the design total (the sum over the instance tree). A flattened run of
# the whole unit hands well over a million gates to ABC (fxr_setup's plane products alone are about
# 700,000) and does not finish on the 2-core machine; the hierarchy loses only the optimisation
# across module boundaries (ports are registered or feed wide arithmetic, so little is lost; the
# flattened back end of a96d7a1 is within the sum of its parts, docs/rtl.md).
# Usage: scripts/synth_unit.sh GEN_DIR OUTDIR
#   GEN_DIR: the folder of the generated packages (build/gen).
#   CONFIG_PKG=F: another fxr_config_pkg.sv (for example a variant's or a plan's: the package
#   `fxraster config --config F --emit-sv DIR` writes); default GEN_DIR/fxr_config_pkg.sv.
#   NICE=N: run Yosys under nice -n N (default 0); SYNTH_TIMEOUT=S (default 7200 s).
# Writes OUTDIR/unit.log, OUTDIR/unit.stat (per-module and total statistics), OUTDIR/unit.ltp and
# prints "fxr_raster_unit lut4=N ff=N depth=N seconds=S". Cached in OUTDIR/cache/<key> (key: sha256
# of the flow and the text of every package and source): a rerun on unchanged RTL prints at once.
set -euo pipefail
gen=$(realpath "$1"); out=$(realpath -m "$2")
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out/cache"
cfg_pkg=$(realpath "${CONFIG_PKG:-$gen/fxr_config_pkg.sv}")
srcs=""
for m in fxr_pipe fxr_round fxr_input fxr_clip_core fxr_clip fxr_seed_rom fxr_nr_step fxr_recip fxr_recip_stage \
         fxr_divide_norm fxr_viewport_lane fxr_viewport_snap fxr_viewport_core fxr_viewport \
         fxr_setup_align fxr_setup_edges fxr_setup_attr fxr_setup_plane fxr_setup_fields fxr_setup \
         fxr_traverse fxr_interp fxr_depth fxr_divide fxr_div fxr_div_align fxr_div_radix2 \
         fxr_div_radix2_pre fxr_div_radix2_step fxr_div_radix2_post fxr_div_recip_mul fxr_div_shared_recip \
         fxr_raster_backend fxr_raster_unit; do
  srcs="$srcs $root/rtl/$m.sv"
done
top=fxr_raster_unit
script="read_verilog -sv $cfg_pkg $gen/fxr_rec_pkg.sv $srcs; synth -noabc -top $top; abc -lut 4 -fast; opt_clean; tee -q -o $out/unit.stat stat; tee -q -o $out/unit.ltp ltp -noff"
key=$( { echo "$script" | sed "s|$root/||g; s|$gen/||g; s|$cfg_pkg||g; s|$out/||g"; cat "$cfg_pkg" "$gen/fxr_rec_pkg.sv" $srcs; } | sha256sum | cut -c1-16)
if [ -s "$out/cache/$top-$key" ]; then
  echo "$(cat "$out/cache/$top-$key") (cached)"; exit 0
fi
start=$(date +%s)
if ! nice -n "${NICE:-0}" timeout "${SYNTH_TIMEOUT:-7200}" yosys -q -l "$out/unit.log" -p "$script" >/dev/null 2>&1; then
  echo "$top failed or timed out after $(( $(date +%s) - start )) s (log $out/unit.log)"; exit 1
fi
secs=$(( $(date +%s) - start ))
# the design total: the last "design hierarchy" block of stat (per-module blocks come first)
tot() { awk '/=== design hierarchy ===/ {h=1} h' "$out/unit.stat"; }
lut=$(tot | grep -E '^\s+\$lut\s' | tail -1 | awk '{print $2}')
ff=$(tot | grep -E '^\s+\$_(S)?DFF' | awk '{s+=$2} END {print s+0}')
depth=$(grep -Eo 'Longest topological path in .* \(length=[0-9]+\)' "$out/unit.ltp" | grep -Eo '[0-9]+\)$' | tr -d ')' | sort -n | tail -1)
cp "$out/unit.stat" "$out/cache/$top-$key.stat"
echo "$top lut4=${lut:-?} ff=$ff depth=${depth:-?} seconds=$secs" | tee "$out/cache/$top-$key"
