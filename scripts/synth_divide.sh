#!/bin/bash
# LUT4 / flip-flop / depth figures of stage 9, rtl/fxr_divide.sv, for both interpolation
# algorithms and lane counts (docs/rtl.md "fxr_divide", docs/arith.md), with the generic flow of
# scripts/synth_cost.py:
#   yosys: read_verilog -sv PKG RECPKG rtl/fxr_divide*.sv rtl/fxr_div*.sv (+ the shared pieces);
#          chparam -set Algorithm A -set Lanes L fxr_divide; synth -flatten -top fxr_divide;
#          abc -lut 4 [-fast]; opt_clean; stat; ltp -noff
# Variants: radix2_l2 radix2_l1 shared_l2 shared_l1 (algorithm, lanes; NumVaryings = RECPKG's),
#   div_radix2 div_shared (fxr_div alone, one lane: the per-lane figure).
# Usage: [FAST=1] scripts/synth_divide.sh PKG RECPKG OUTDIR [variant ...]
#   PKG, RECPKG: build/gen/fxr_config_pkg.sv, build/gen/fxr_rec_pkg.sv (the defaults; the
#   algorithm and lanes are set by chparam). FAST=1: `abc -lut 4 -fast`.
# Prints one line per variant: "<variant> lut4=N ff=N depth=N seconds=S". Runs under nice -n 19.
set -euo pipefail
pkg=$(realpath "$1"); rec=$(realpath "$2"); out=$(realpath -m "$3"); shift 3
vars=("$@"); [ ${#vars[@]} -eq 0 ] && vars=(radix2_l2 radix2_l1 shared_l2 shared_l1)
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
files=""
for f in fxr_divide fxr_divide_norm fxr_norm_log fxr_div fxr_div_align fxr_div_radix2 fxr_div_radix2_pre \
         fxr_div_radix2_post fxr_div_recip_mul fxr_div_shared_recip fxr_seed_rom \
         fxr_nr_step fxr_round; do
  files="$files $root/rtl/$f.sv"
done
for v in "${vars[@]}"; do
  case $v in
    radix2_l2) top=fxr_divide; set="-set Algorithm 1" ;;
    radix2_l1) top=fxr_divide; set="-set Algorithm 1 -set Lanes 1" ;;
    shared_l2) top=fxr_divide; set="-set Algorithm 2" ;;
    shared_l1) top=fxr_divide; set="-set Algorithm 2 -set Lanes 1" ;;
    div_radix2) top=fxr_div; set="-set Algorithm 1" ;;
    div_shared) top=fxr_div; set="-set Algorithm 2" ;;
    *) echo "synth_divide.sh: unknown variant '$v'" >&2; exit 2 ;;
  esac
  t0=$(date +%s)
  nice -n 19 yosys -q -l "$out/$v.log" -p "read_verilog -sv $pkg $rec $files; chparam $set $top; synth -flatten -top $top; abc -lut 4 ${FAST:+-fast}; opt_clean; tee -o $out/$v.stat stat; tee -o $out/$v.ltp ltp -noff" > /dev/null
  t1=$(date +%s)
  lut=$(awk '$1 == "$lut" {print $2}' "$out/$v.stat" | tail -1)
  ff=$(awk '$1 ~ /^\$_.*DFF/ {s += $2} END {print s + 0}' "$out/$v.stat")
  depth=$(sed -n 's/.*Longest topological path in \S* (length=\([0-9]*\)).*/\1/p' "$out/$v.ltp" | tail -1)
  echo "$v${FAST:+ (abc -fast)} lut4=$lut ff=$ff depth=$depth seconds=$((t1 - t0))"
done
