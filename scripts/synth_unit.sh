#!/bin/bash
# LUT4 / flip-flop / logic-depth figures of the whole raster unit rtl/fxr_raster_unit.sv, as the sum
# of its parts, each part one Yosys run (docs/rtl.md, "fxr_raster_unit: area"):
#   yosys: read_verilog -sv PKG RECPKG rtl/<every module of the unit>; [chparam …]
#          synth -flatten -noabc -top PART; abc -lut 4 -fast; opt_clean; stat; ltp -noff
# The parts are the nine stages (each flattened, with the parameters the unit instantiates it
# with) and the two glue levels (fxr_raster_backend and fxr_raster_unit with their stages as black
# boxes: FIFOs, counters, the draw-state register block). One run of the whole unit, flattened or
# hierarchical, does not fit this machine: the hierarchical run was killed by the OOM killer at
# 20 GB after 61 min (fxr_setup's plane products alone hand about 700,000 gates to ABC); the sum
# loses only optimisation across stage boundaries (registered records).
# Usage: scripts/synth_unit.sh GEN_DIR OUTDIR [PART ...]
#   GEN_DIR: the folder of the generated packages (build/gen). PART: input clip recip viewport
#   setup traverse interp depth divide backend_glue unit_glue (default: all, small ones first).
#   CONFIG_PKG=F: another fxr_config_pkg.sv (a variant's or a plan's: `fxraster config --config F
#   --emit-sv DIR`); default GEN_DIR/fxr_config_pkg.sv. SYNTH_TIMEOUT=S per part (default 2400).
# Prints one line per part, "<part> lut4=N ff=N depth=N seconds=S", then "total lut4=N ff=N" when
# every part has a figure. Each part is cached in OUTDIR/cache/<part>-<key> (key: sha256 of the
# flow and the text of every package and source): a rerun on unchanged RTL prints at once.
set -euo pipefail
gen=$(realpath "$1"); out=$(realpath -m "$2"); shift 2
parts=("$@")
[ ${#parts[@]} -eq 0 ] && parts=(input unit_glue backend_glue depth traverse divide recip interp viewport clip setup)
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out/cache"
cfg_pkg=$(realpath "${CONFIG_PKG:-$gen/fxr_config_pkg.sv}")
srcs=""
for m in fxr_pipe fxr_round fxr_input fxr_clip_core fxr_clip fxr_seed_rom fxr_nr_step fxr_recip fxr_recip_stage \
         fxr_divide_norm fxr_norm_log fxr_viewport_lane fxr_viewport_snap fxr_viewport_core fxr_viewport \
         fxr_setup_align fxr_setup_edges fxr_setup_attr fxr_setup_plane fxr_setup_fields fxr_setup \
         fxr_traverse fxr_interp fxr_depth fxr_divide fxr_div fxr_div_align fxr_div_radix2 \
         fxr_div_radix2_pre fxr_div_radix2_post fxr_div_recip_mul fxr_div_shared_recip \
         fxr_raster_backend fxr_raster_unit; do
  srcs="$srcs $root/rtl/$m.sv"
done
# glue: TOP with its stage instances as black boxes (the pattern of scripts/synth_viewport.sh; the
# trailing * matches a parameterised instance, $paramod\fxr_viewport\Lanes=…)
glue() { echo "hierarchy -top $1; rename -top $1; blackbox $2; hierarchy -top $1;"; }
tot_lut=0; tot_ff=0; complete=1
for p in "${parts[@]}"; do
  flat=-flatten; set=""
  case $p in
    input) top=fxr_input ;;
    clip) top=fxr_clip ;;
    recip) top=fxr_recip_stage ;;
    viewport) top=fxr_viewport; set="chparam -set Lanes 3 fxr_viewport;" ;;  # the unit's ViewportLanes
    setup) top=fxr_setup ;;
    traverse) top=fxr_traverse ;;
    interp) top=fxr_interp; set="chparam -set DivStepsPerClock 4 fxr_interp;" ;;  # the back end's InterpDivSteps
    depth) top=fxr_depth; set="chparam -set WritePort 1 fxr_depth;" ;;            # the back end's DepthWritePort
    divide) top=fxr_divide ;;
    backend_glue) top=fxr_raster_backend; flat=""
      set="$(glue fxr_raster_backend '*fxr_setup* *fxr_traverse* *fxr_interp* *fxr_depth* *fxr_divide* *fxr_div_*')" ;;
    unit_glue) top=fxr_raster_unit; flat=""
      set="$(glue fxr_raster_unit '*fxr_input* *fxr_clip* *fxr_recip_stage* *fxr_viewport* *fxr_raster_backend*')" ;;
    *) echo "synth_unit.sh: unknown part '$p'" >&2; exit 2 ;;
  esac
  script="read_verilog -sv $cfg_pkg $gen/fxr_rec_pkg.sv $srcs; $set synth $flat -noabc -top $top; abc -lut 4 -fast; opt_clean; tee -q -o $out/$p.stat stat; tee -q -o $out/$p.ltp ltp -noff"
  key=$( { echo "$script" | sed "s|$root/||g; s|$gen/||g; s|$cfg_pkg||g; s|$out/||g"; cat "$cfg_pkg" "$gen/fxr_rec_pkg.sv" $srcs; } | sha256sum | cut -c1-16)
  if [ -s "$out/cache/$p-$key" ]; then
    line=$(cat "$out/cache/$p-$key"); echo "$line (cached)"
  else
    start=$(date +%s)
    if ! timeout "${SYNTH_TIMEOUT:-2400}" yosys -q -l "$out/$p.log" -p "$script" >/dev/null 2>&1; then
      echo "$p failed or timed out after $(( $(date +%s) - start )) s (log $out/$p.log)"; complete=0; continue
    fi
    secs=$(( $(date +%s) - start ))
    lut=$(grep -E '^\s+\$lut\s' "$out/$p.stat" | tail -1 | awk '{print $2}')
    ff=$(grep -E '^\s+\$_(S)?DFF' "$out/$p.stat" | awk '{s+=$2} END {print s+0}')
    depth=$(grep -Eo '\(length=[0-9]+\)' "$out/$p.ltp" | grep -Eo '[0-9]+' | sort -n | tail -1)
    line="$p lut4=${lut:-0} ff=$ff depth=${depth:-?} seconds=$secs"
    echo "$line" | tee "$out/cache/$p-$key"
  fi
  tot_lut=$(( tot_lut + $(echo "$line" | sed -n 's/.*lut4=\([0-9]*\).*/\1/p') ))
  tot_ff=$(( tot_ff + $(echo "$line" | sed -n 's/.*ff=\([0-9]*\).*/\1/p') ))
done
[ $complete -eq 1 ] && echo "total lut4=$tot_lut ff=$tot_ff (parts: ${parts[*]})"
exit 0
