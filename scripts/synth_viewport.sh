#!/bin/bash
# LUT4 / flip-flop / depth figures of stage 4, rtl/fxr_viewport.sv (docs/rtl.md "fxr_viewport"),
# with the flow of scripts/synth_divide.sh:
#   yosys: read_verilog -sv PKG RECPKG rtl/fxr_viewport*.sv rtl/fxr_divide_norm.sv rtl/fxr_norm_log.sv;
#          chparam -set Lanes L fxr_viewport; synth -flatten -top TOP; abc -lut 4 [-fast];
#          opt_clean; stat; ltp -noff
# Variants: l1 l3 l7 (fxr_viewport with Lanes 1, 3 (the default), 7, flattened), lane
#   (fxr_viewport_lane alone: one divider lane), snap (fxr_viewport_snap alone: one snap unit),
#   g1 g3 g7 (fxr_viewport_core with Lanes 1, 3, 7 and its lanes and snap units as black boxes:
#   the input register, job and slot multiplexers, FIFO and output register; the whole unit is
#   then g<L> + L·lane + SnapLanes·snap, SnapLanes = ceil(6 / ceil(3·(4 + NumVaryings) / L))).
# Usage: [FAST=1] scripts/synth_viewport.sh PKG RECPKG OUTDIR [variant ...]
#   PKG, RECPKG: build/gen/fxr_config_pkg.sv, build/gen/fxr_rec_pkg.sv. FAST=1: `abc -lut 4 -fast`.
# Prints one line per variant: "<variant> lut4=N ff=N depth=N seconds=S". Runs under nice -n 19.
set -euo pipefail
pkg=$(realpath "$1"); rec=$(realpath "$2"); out=$(realpath -m "$3"); shift 3
vars=("$@"); [ ${#vars[@]} -eq 0 ] && vars=(snap lane l1 l3)
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
files=""
for f in fxr_viewport fxr_viewport_core fxr_viewport_lane fxr_viewport_snap fxr_divide_norm fxr_norm_log; do
  files="$files $root/rtl/$f.sv"
done
for v in "${vars[@]}"; do
  case $v in
    l1) top=fxr_viewport; set="chparam -set Lanes 1 fxr_viewport;" ;;
    l3) top=fxr_viewport; set="chparam -set Lanes 3 fxr_viewport;" ;;
    l7) top=fxr_viewport; set="chparam -set Lanes 7 fxr_viewport;" ;;
    g1 | g3 | g7) top=fxr_viewport_core; set="chparam -set Lanes ${v#g} fxr_viewport_core; hierarchy -top fxr_viewport_core; rename -top fxr_viewport_core; blackbox *fxr_viewport_lane *fxr_viewport_snap; hierarchy -top fxr_viewport_core;" ;;
    lane) top=fxr_viewport_lane; set="" ;;
    snap) top=fxr_viewport_snap; set="" ;;
    *) echo "synth_viewport.sh: unknown variant '$v'" >&2; exit 2 ;;
  esac
  t0=$(date +%s)
  flat=-flatten; case $v in g*) flat="" ;; esac
  nice -n 19 yosys -q -l "$out/$v.log" -p "read_verilog -sv $pkg $rec $files; $set synth $flat -top $top; abc -lut 4 ${FAST:+-fast}; opt_clean; tee -o $out/$v.stat stat; tee -o $out/$v.ltp ltp -noff" > /dev/null
  t1=$(date +%s)
  lut=$(awk '$1 == "$lut" {print $2}' "$out/$v.stat" | tail -1)
  ff=$(awk '$1 ~ /^\$_.*DFF/ {s += $2} END {print s + 0}' "$out/$v.stat")
  depth=$(sed -n 's/.*Longest topological path in \S* (length=\([0-9]*\)).*/\1/p' "$out/$v.ltp" | tail -1)
  echo "$v${FAST:+ (abc -fast)} lut4=$lut ff=$ff depth=$depth seconds=$((t1 - t0))"
done
