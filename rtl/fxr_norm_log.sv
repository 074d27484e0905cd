// fxr_norm_log: the leading one of a non-negative integer and the left shift that puts it at the
// top, as one log-step normaliser (combinational). Shared by fxr_divide_norm (stage 9's and the
// viewport's operand normalisation), fxr_clip_core (|d_s - d_e| and the numerator before the
// restoring division) and fxr_recip_stage (w before fxr_recip); docs/rtl.md, "fxr_norm_log".
// Model: the leading-one index of model/arith/fixed.hpp (msb_index) and the left shift of
// fxr::normalize before its rounding.
//
//   x_i > 0: msb_o = m, the index of the leading one; norm_o = x_i * 2^(Width-1-m) (bit Width-1 set).
//   x_i = 0: msb_o = 0, norm_o = 0.
//   en_i low: msb_o = 0, norm_o = 0 whatever x_i (the caller reads the outputs only with en_i high;
//   the simulator then skips the normaliser: docs/rtl.md, "Co-simulation speed", session 8). Tie
//   it high where the outputs are always read.
//
// The method: shifted up by 2^l wherever its top 2^l bits are zero (l = L-1 down to 0,
// L = ceil(log2(Width)), so 2^(L-1) < Width); the shifts' sum is the count of leading zeros
// lz = Width - 1 - m, taken greedily bit by bit from the top (lz < 2^L). L levels of 2:1
// multiplexers and a zero test each, not a priority loop over the Width bits and a barrel shift by
// Width - 1 - m: Verilator runs that loop bit by bit in every evaluation (125 iterations for the
// back end's denominator; docs/rtl.md, "Co-simulation speed", session 8), and in fxr_divide the
// priority chain was the longest path (60 levels against 32). The shifts work on norm_o itself:
// no wider padded word, so a disabled normaliser clears Width bits and nothing else in each
// evaluation (a simulator runs the block on every clock of its clock domain).
module fxr_norm_log #(
  parameter int Width   = 32,               // operand bits (>= 2)
  parameter int MsbBits = $clog2(Width)     // msb_o bits: holds Width - 1
) (
  input  logic               en_i,
  input  logic [Width-1:0]   x_i,
  output logic [Width-1:0]   norm_o,
  output logic [MsbBits-1:0] msb_o
);
  localparam int LzBits = $clog2(Width);

  if (Width < 2) begin : g_check
    $error("fxr_norm_log: Width %0d < 2", Width);
  end
  if (MsbBits < LzBits) begin : g_check_msb
    $error("fxr_norm_log: MsbBits %0d cannot hold Width - 1 = %0d", MsbBits, Width - 1);
  end

  logic [LzBits-1:0] lz;
  always_comb begin
    lz     = '0;
    norm_o = '0;
    msb_o  = '0;
    if (en_i) begin
      norm_o = x_i;
      for (int l = LzBits - 1; l >= 0; l--) begin
        if ((norm_o >> (Width - (1 << l))) == '0) begin
          lz     = lz | (LzBits'(1) << l);
          norm_o = norm_o << (1 << l);
        end
      end
      // the leading one is at the top after the shifts unless x is 0
      msb_o = norm_o[Width-1] ? MsbBits'(Width - 1) - MsbBits'(lz) : '0;
    end
  end
endmodule
