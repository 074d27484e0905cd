// fxr_div_round: round to nearest even from an exact floor quotient and remainder
// (combinational), shared by every divider algorithm.
//
// Mirrors round_rne in model/arith/div.cpp. Inputs: q_i = floor(X) in [2^(QuotBits-1), 2^QuotBits);
// with r in [0, b) the exact remainder (X*b = q*b + r), the sign and zero flags of t = 2r - b
// (t_neg_i, t_zero_i; the caller forms t, for radix2 it is one more recurrence step); k_i = 1
// when the normalised numerator was below the divisor (exp_adj -1 before rounding).
// Rounding: up when 2r > b, or 2r == b and q is odd (ties to even) - the unit's only rounding.
// Carry out (q + 1 == 2^QuotBits) renormalises: sig = 2^(QuotBits-1), exp_adj + 1.
// exp_adj_o: two's complement, 2'b11 = -1, 2'b00 = 0, 2'b01 = +1.
module fxr_div_round #(
  parameter int QuotBits = 24
) (
  input  logic [QuotBits-1:0]  q_i,
  input  logic                 t_neg_i,
  input  logic                 t_zero_i,
  input  logic                 k_i,
  output logic [QuotBits-1:0]  sig_o,
  output logic [1:0]           exp_adj_o
);
  logic              up;
  logic [QuotBits:0] q_inc;

  assign up    = (!t_neg_i && !t_zero_i) || (t_zero_i && q_i[0]);
  assign q_inc = {1'b0, q_i} + {{QuotBits{1'b0}}, up};

  always_comb begin
    if (q_inc[QuotBits]) begin
      sig_o     = {1'b1, {(QuotBits - 1){1'b0}}};
      exp_adj_o = k_i ? 2'b00 : 2'b01;
    end else begin
      sig_o     = q_inc[QuotBits-1:0];
      exp_adj_o = k_i ? 2'b11 : 2'b00;
    end
  end
endmodule
