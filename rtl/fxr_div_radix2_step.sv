// fxr_div_radix2_step: one radix-2 non-restoring recurrence step (combinational).
//
// Mirrors the loop body of fxr::div_sig_radix2_steps (model/arith/div.cpp):
//   r >= 0: r' = 2r - b, digit +1 (p' = {p, 1});   r < 0: r' = 2r + b, digit -1 (p' = {p, 0}).
// Invariant a'*2^i = Q_i*b + r_i with r_i in [-b, b): r' stays in RemBits signed bits (the
// intermediate 2r fits as |r| < b < 2^AlignBits). en_i = 0 passes r and p through unchanged
// (the unused steps of a partly filled stage). No rounding here; exact.
//
// Ports:
//   en_i   step enable
//   r_i    partial remainder, two's complement, RemBits    r_o  next partial remainder
//   p_i    quotient digit bits (1 = +1), QuotBits bits     p_o  shifted, new digit appended
//   b_i    aligned divisor, AlignBits bits, msb set
module fxr_div_radix2_step #(
  parameter int AlignBits = 32,
  parameter int RemBits   = AlignBits + 2,
  parameter int QuotBits  = 24
) (
  input  logic                       en_i,
  input  logic [RemBits-1:0]         r_i,
  input  logic        [QuotBits-1:0] p_i,
  input  logic        [AlignBits-1:0] b_i,
  output logic [RemBits-1:0]         r_o,
  output logic        [QuotBits-1:0] p_o
);
  logic signed [RemBits-1:0] b_ext;
  logic signed [RemBits-1:0] r2;
  logic                      pos;

  assign b_ext = $signed({{(RemBits - AlignBits){1'b0}}, b_i});
  assign r2    = $signed({r_i[RemBits-2:0], 1'b0});
  assign pos   = ~r_i[RemBits-1];

  always_comb begin
    if (!en_i) begin
      r_o = r_i;
      p_o = p_i;
    end else begin
      r_o = pos ? (r2 - b_ext) : (r2 + b_ext);
      p_o = {p_i[QuotBits-2:0], pos};
    end
  end
endmodule
