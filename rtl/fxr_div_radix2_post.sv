// fxr_div_radix2_post: end of the radix-2 divider (combinational). Mirrors the end of
// fxr::div_sig_radix2_steps:
//   signed digits to binary: Q = 2P + 1 - 2^QuotBits = {P[QuotBits-2:0], 1} (P's msb is digit 0,
//   always 1, so no adder); a negative remainder is corrected (Q - 1 clears the odd lsb, r + b);
//   then Q = floor(X), r in [0, b) exact, and fxr_round rounds to nearest even on the sign
//   of t = 2r - b. The corrected r is never formed: t = 2(r_i + b) - b = 2r_i + b when r_i < 0,
//   else 2r_i - b, i.e. one more recurrence step (one carry chain, then the increment).
// Special cases: dbz_i -> sig all ones, exp_adj 0, dbz_o = 1; else nz_i -> sig 0, exp_adj 0.
module fxr_div_radix2_post #(
  parameter int AlignBits = 32,
  parameter int RemBits   = AlignBits + 2,
  parameter int QuotBits  = 24
) (
  input  logic [RemBits-1:0]         r_i,  // two's complement, in [-b, b)
  input  logic [QuotBits-1:0]        p_i,
  input  logic [AlignBits-1:0]       b_i,
  input  logic                       k_i,
  input  logic                       dbz_i,
  input  logic                       nz_i,
  output logic [QuotBits-1:0]        sig_o,
  output logic [1:0]                 exp_adj_o,
  output logic                       dbz_o
);
  logic                      neg;
  logic [RemBits:0]          two_r;
  logic [RemBits:0]          t;  // 2r - b after the correction, in [-b, b)
  logic [QuotBits-1:0]       q;
  logic [QuotBits-1:0]       sig_rnd;
  logic [1:0]                exp_rnd;

  assign neg   = r_i[RemBits-1];
  assign two_r = {r_i, 1'b0};
  // 2r + b (r < 0) or 2r - b as one adder, the operand selected: 2r + (b XOR ~neg) + ~neg (the
  // form of fxr_div_radix2's steps: no data-dependent branch in a simulator).
  assign t     = two_r + ({3'b000, b_i} ^ {(RemBits + 1){~neg}}) + {{RemBits{1'b0}}, ~neg};
  assign q     = {p_i[QuotBits-2:0], ~neg};

  fxr_round #(
    .QuotBits(QuotBits)
  ) u_round (
    .q_i      (q),
    .t_neg_i  (t[RemBits]),
    .t_zero_i (t == '0),
    .k_i      (k_i),
    .sig_o    (sig_rnd),
    .exp_adj_o(exp_rnd)
  );

  always_comb begin
    dbz_o = dbz_i;
    if (dbz_i) begin
      sig_o     = '1;
      exp_adj_o = 2'b00;
    end else if (nz_i) begin
      sig_o     = '0;
      exp_adj_o = 2'b00;
    end else begin
      sig_o     = sig_rnd;
      exp_adj_o = exp_rnd;
    end
  end

  // p_i's msb is digit 0, always 1 (the 2^QuotBits the digit conversion subtracts).
  logic unused_p_msb;
  assign unused_p_msb = p_i[QuotBits-1];
endmodule
