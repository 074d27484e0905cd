// fxr_div_radix2_pre: operand alignment and quotient digit 0 of the radix-2 divider
// (combinational). Mirrors align() and the start of fxr::div_sig_radix2_steps:
//   a = num << (AlignBits - NumBits), b = den << (AlignBits - DenBits)   (exact, no bits lost)
//   k = (a < b);  a' = a << k in [b, 2b);  r0 = a' - b in [0, b);  digit 0 = +1 (p0 = 1).
// a - b and 2a - b are formed in parallel and k is the sign of a - b: one carry chain deep.
// dbz_o = (den == 0), nz_o = (num == 0): special cases, resolved in fxr_div_radix2_post.
module fxr_div_radix2_pre #(
  parameter int NumBits   = 32,
  parameter int DenBits   = 32,
  parameter int QuotBits  = 24,
  parameter int AlignBits = (NumBits > DenBits) ? NumBits : DenBits,
  parameter int RemBits   = AlignBits + 2
) (
  input  logic [NumBits-1:0]         num_i,
  input  logic [DenBits-1:0]         den_i,
  output logic [RemBits-1:0]         r_o,  // two's complement (value in [0, b) here)
  output logic [QuotBits-1:0]        p_o,
  output logic [AlignBits-1:0]       b_o,
  output logic                       k_o,
  output logic                       dbz_o,
  output logic                       nz_o
);
  logic [AlignBits-1:0] a;
  logic [RemBits-1:0]   d1;  // a - b, two's complement
  logic [RemBits-1:0]   d2;  // 2a - b

  fxr_div_align #(
    .NumBits(NumBits),
    .DenBits(DenBits)
  ) u_align (
    .num_i(num_i),
    .den_i(den_i),
    .a_o  (a),
    .b_o  (b_o)
  );

  assign d1    = {2'b00, a} - {2'b00, b_o};
  assign d2    = {1'b0, a, 1'b0} - {2'b00, b_o};
  assign k_o   = d1[RemBits-1];
  assign r_o   = k_o ? d2 : d1;
  assign p_o   = {{(QuotBits - 1){1'b0}}, 1'b1};
  assign dbz_o = den_i == '0;
  assign nz_o  = num_i == '0;
endmodule
