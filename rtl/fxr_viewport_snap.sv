// fxr_viewport_snap: the snap of one window coordinate (combinational), part of stage 4
// (fxr_viewport). Model: fxr::snap_window (model/stages/viewport.cpp) on the exact product
// n = c·r of a clip coordinate and the reciprocal unit's 1/w:
//
//   code = RNE(((n + 1)·size/2 + origin)·2^S) = RNE((M·2^E + C) / 2),
//   M = c_sig·r_sig·size (exact), E = c_exp + r_exp + S, C = (size + 2·origin)·2^S,
//
// one rounding. M·2^E is aligned to two fraction bits with the bits below jammed into the lowest
// (V4 = jam(M·2^(E+2)): the ½ bit and a sticky bit, which round like the exact value at any
// coarser step, docs/rtl.md "fxr_viewport"), then code = RNE((4C ± V4) / 8).
// Range (range_o): code outside a signed CodeBits = WindowIntBits + S code. When
// M·2^E ≥ 2^(CodeBits+3) the code is out of range whatever C is (|C| < 2^(CodeBits+1)), so V4 keeps
// CodeBits + 5 bits and anything above is the range flag: the model's own limit (2^120) lies
// beyond and flags range too.
// sizes are the draw state's viewport_w / _h (≥ 1, checked by the model's draw-state reader),
// origins viewport_x / _y (signed).
module fxr_viewport_snap #(
  parameter int SigBits = fxr_rec_pkg::ClipVertexSigBits,
  parameter int RecipBits = fxr_config_pkg::RecipOutSigBits,
  parameter int ExpBits = fxr_rec_pkg::FxExpBits,
  parameter int WindowIntBits = fxr_config_pkg::RasterWindowIntBits,
  parameter int SubBits = fxr_config_pkg::RasterSubpixelBits
) (
  input  logic                                    c_neg_i,
  input  logic [SigBits-1:0]                      c_sig_i,
  input  logic signed [ExpBits-1:0]               c_exp_i,
  input  logic                                    r_neg_i,
  input  logic [RecipBits-1:0]                    r_sig_i,
  input  logic signed [ExpBits-1:0]               r_exp_i,
  input  logic [WindowIntBits:0]                  size_i,    // viewport size (signed, ≥ 1)
  input  logic signed [WindowIntBits-1:0]         origin_i,  // viewport origin
  output logic signed [WindowIntBits+SubBits-1:0] code_o,
  output logic                                    range_o
);
  localparam int CodeBits = WindowIntBits + SubBits;
  localparam int MBits = SigBits + RecipBits + WindowIntBits + 1;  // c_sig·r_sig·size
  localparam int VBits = CodeBits + 5;                              // V4 = jam(M·2^(E+2))
  localparam int WideBits = MBits + VBits;
  localparam int ShBits = $clog2(WideBits + 1) + 1;                 // a shift of [0, WideBits]
  localparam int EBits = ExpBits + 2;                               // E + 2 and the shifts
  localparam int XBits = CodeBits + 8;                              // 4C ± V4 (signed)

  logic [MBits-1:0] m;
  assign m = MBits'(c_sig_i) * MBits'(r_sig_i) * MBits'(size_i);

  // t = VBits − (E + 2): the right shift of M·2^VBits that leaves M·2^(E+2).
  logic signed [EBits+1:0] t;
  assign t = (EBits + 2)'(VBits) - ((EBits + 2)'(c_exp_i) + (EBits + 2)'(r_exp_i) + (EBits + 2)'(SubBits + 2));

  logic [WideBits-1:0] wide, shifted, mask;
  logic [ShBits-1:0]   sh;
  logic                all_out, sticky, ovf;
  logic [VBits-1:0]    v4;
  assign wide = {m, {VBits{1'b0}}};
  assign all_out = t >= (EBits + 2)'(WideBits);
  assign sh = all_out ? ShBits'(WideBits) : (t < 0 ? '0 : ShBits'(t));
  assign shifted = all_out ? '0 : wide >> sh;
  assign mask = all_out ? '1 : ~({WideBits{1'b1}} << sh);
  assign sticky = |(wide & mask);
  // t < 0: M·2^(E+2) ≥ 2^VBits unless M = 0.
  assign ovf = (t < 0) ? (|m) : (|shifted[WideBits-1:VBits]);
  assign v4 = shifted[VBits-1:0] | VBits'(sticky);

  logic signed [XBits-1:0] c4, x4, code;
  logic                    up;
  assign c4 = (XBits'($signed(size_i)) + (XBits'(origin_i) <<< 1)) <<< (SubBits + 2);
  assign x4 = (c_neg_i ^ r_neg_i) ? c4 - XBits'(v4) : c4 + XBits'(v4);
  // RNE(x4 / 8): guard x4[2], sticky x4[1:0].
  assign up = x4[2] & ((|x4[1:0]) | x4[3]);
  assign code = (x4 >>> 3) + $signed(XBits'(up));
  assign range_o = ovf || (code < -(XBits'(1) <<< (CodeBits - 1))) || (code >= (XBits'(1) <<< (CodeBits - 1)));
  assign code_o = code[CodeBits-1:0];
endmodule
