#!/bin/bash
# LUT4 / flip-flop / depth figure of the texture address unit rtl/fxr_texaddr.sv (docs/texaddr.md,
# "Cost"), with the generic flow of scripts/synth_cost.py:
#   yosys: read_verilog -sv PKG rtl/fxr_texaddr.sv rtl/fxr_texaddr_axis.sv [WRAPPER];
#          synth -flatten -top T; abc -lut 4; opt_clean; stat; ltp -noff
# Filter and wrap are input ports of the unit (texture state). Three tops:
#   both      fxr_texaddr itself (filter_i free: nearest and bilinear in one datapath)
#   nearest   a wrapper tying filter_i to tex_addr_filter_e nearest (Yosys removes the rest)
#   bilinear  a wrapper tying filter_i to bilinear
# Usage: [FAST=1] scripts/synth_texaddr.sh PKG OUTDIR [both|nearest|bilinear ...]
#   FAST=1: `abc -lut 4 -fast` (ABC's short script) instead of the full one; docs/texaddr.md gives
#   both figures where the full script finishes.
#   PKG: the generated package (build/gen/fxr_config_pkg.sv, or `fxraster config --emit-sv F`).
# Prints one line per top: "<top> lut4=N ff=N depth=N seconds=S". Runs under nice -n 19.
set -euo pipefail
pkg=$(realpath "$1"); out=$(realpath -m "$2"); shift 2
tops=("$@"); [ ${#tops[@]} -eq 0 ] && tops=(both nearest bilinear)
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
wrapper() {  # $1: module name, $2: the tex_addr_filter_e enumerator
  cat <<SV
module $1 #(
  parameter int SigBits  = fxr_config_pkg::TexAddrSigBits,
  parameter int ExpBits  = fxr_config_pkg::TexAddrExpBits,
  parameter int SizeBits = fxr_config_pkg::TexAddrSizeBits,
  parameter int FracBits = fxr_config_pkg::TexAddrWeightFracBits
) (
  input  logic clk_i, rst_ni, in_valid_i, out_ready_i,
  output logic in_ready_o, out_valid_o,
  input  logic [1:0] wrap_i,
  input  logic u_neg_i, input logic [ExpBits-1:0] u_exp_i, input logic [SigBits-1:0] u_sig_i,
  input  logic v_neg_i, input logic [ExpBits-1:0] v_exp_i, input logic [SigBits-1:0] v_sig_i,
  input  logic [SizeBits:0] width_i, height_i,
  output logic [SizeBits-1:0] s_i0_o, s_i1_o, t_i0_o, t_i1_o,
  output logic s_b0_o, s_b1_o, t_b0_o, t_b1_o,
  output logic [FracBits-1:0] s_w_o, t_w_o
);
  fxr_texaddr #(.SigBits(SigBits), .ExpBits(ExpBits), .SizeBits(SizeBits), .FracBits(FracBits)) u (
    .clk_i(clk_i), .rst_ni(rst_ni), .in_valid_i(in_valid_i), .in_ready_o(in_ready_o),
    .filter_i(1'(fxr_config_pkg::$2)), .wrap_i(wrap_i),
    .u_neg_i(u_neg_i), .u_exp_i(u_exp_i), .u_sig_i(u_sig_i),
    .v_neg_i(v_neg_i), .v_exp_i(v_exp_i), .v_sig_i(v_sig_i),
    .width_i(width_i), .height_i(height_i), .out_valid_o(out_valid_o), .out_ready_i(out_ready_i),
    .s_i0_o(s_i0_o), .s_i1_o(s_i1_o), .s_b0_o(s_b0_o), .s_b1_o(s_b1_o), .s_w_o(s_w_o),
    .t_i0_o(t_i0_o), .t_i1_o(t_i1_o), .t_b0_o(t_b0_o), .t_b1_o(t_b1_o), .t_w_o(t_w_o));
endmodule
SV
}
for which in "${tops[@]}"; do
  files="$root/rtl/fxr_texaddr.sv $root/rtl/fxr_texaddr_axis.sv"
  case $which in
    both) top=fxr_texaddr ;;
    nearest) top=fxr_texaddr_nearest; wrapper $top TexAddrFilterNearest > "$out/$top.sv"; files="$files $out/$top.sv" ;;
    bilinear) top=fxr_texaddr_bilinear; wrapper $top TexAddrFilterBilinear > "$out/$top.sv"; files="$files $out/$top.sv" ;;
    *) echo "synth_texaddr.sh: unknown top '$which' (both, nearest, bilinear)" >&2; exit 2 ;;
  esac
  log="$out/$which.log"
  t0=$(date +%s)
  nice -n 19 yosys -q -l "$log" -p "read_verilog -sv $pkg $files; synth -flatten -top $top; abc -lut 4 ${FAST:+-fast}; opt_clean; tee -o $out/$which.stat stat; tee -o $out/$which.ltp ltp -noff" > /dev/null
  t1=$(date +%s)
  lut=$(awk '$1 == "$lut" {print $2}' "$out/$which.stat" | tail -1)
  ff=$(awk '$1 ~ /^\$_.*DFF/ {s += $2} END {print s + 0}' "$out/$which.stat")
  depth=$(sed -n 's/.*Longest topological path in \S* (length=\([0-9]*\)).*/\1/p' "$out/$which.ltp" | tail -1)
  echo "$which${FAST:+ (abc -fast)} lut4=$lut ff=$ff depth=$depth seconds=$((t1 - t0))"
done
