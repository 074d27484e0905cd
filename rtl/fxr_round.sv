// fxr_round: round to nearest even and renormalise a significand (combinational); the one
// rounding module, shared by fxr_div_radix2_post, fxr_div_recip_mul and fxr_recip.
// Model: fxr::rne_round_up + fxr::round_increment (model/arith/round.hpp); docs/arith.md
// "# Shared arithmetic".
//
// Inputs: q_i in [2^(QuotBits-1), 2^QuotBits), the candidate significand; the three-way comparison
// of the value's fraction beyond q with 1/2 as two flags of t = 2r - b (t_neg_i: below 1/2,
// t_zero_i: exactly 1/2; neither: above). Dividers form t from the exact remainder r in [0, b);
// the reciprocal unit from its midpoint test (ties impossible, t_zero_i tied low) or, without
// the correction, from the rounding bit of y (t_zero_i tied low: a tie rounds up, half up).
// k_i = 1 when the value lies one binade below (exp_adj -1 before rounding).
// Rounding: up when t > 0, or t == 0 and q is odd (ties to even).
// Carry out (q + 1 == 2^QuotBits) renormalises: sig = 2^(QuotBits-1), exp_adj + 1.
// exp_adj_o: two's complement, 2'b11 = -1, 2'b00 = 0, 2'b01 = +1.
module fxr_round #(
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
