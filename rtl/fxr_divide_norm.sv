// fxr_divide_norm: normalisation of a non-negative integer to an OutBits significand with its msb
// set, rounded to nearest even (combinational); stage 9's operand normalisation (fxr_divide).
// Model: fxr::normalize(x, OutBits, Round::HalfEven) (model/arith/fixed.hpp) as normalize_den /
// divide_varying call it (model/stages/divide.hpp).
//
//   x_i > 0: m = index of the leading one; sig_o = x * 2^(OutBits-1-m) when m < OutBits (exact),
//   else RNE(x / 2^(m-OutBits+1)); a carry out of the rounding renormalises (sig_o = 2^(OutBits-1),
//   m + 1). msb_o = m (+1 on the carry). x_i = 0: sig_o = 0, msb_o = 0.
//   en_i low: sig_o = 0, msb_o = 0 whatever x_i (the caller reads the outputs only with en_i high;
//   the simulator then skips the normaliser: docs/rtl.md, "Co-simulation speed"). Tie it high
//   where the outputs are always read.
module fxr_divide_norm #(
  parameter int InBits  = 93,
  parameter int OutBits = 32,
  parameter int MsbBits = 8
) (
  input  logic               en_i,
  input  logic [InBits-1:0]  x_i,
  output logic [OutBits-1:0] sig_o,
  output logic [MsbBits-1:0] msb_o
);
  // The leading one m and x shifted up to it (xn, msb at bit InBits-1): the shared log-step
  // normaliser (rtl/fxr_norm_log.sv), gated by en_i as the rounding below.
  logic [MsbBits-1:0] m;
  logic [InBits-1:0]  xn;
  fxr_norm_log #(
    .Width  (InBits),
    .MsbBits(MsbBits)
  ) u_norm (
    .en_i  (en_i),
    .x_i   (x_i),
    .norm_o(xn),
    .msb_o (m)
  );

  if (InBits > OutBits) begin : gen_round
    // the bits below the rounding bit (none when InBits = OutBits + 1)
    localparam logic [InBits-1:0] StickyMask = (InBits'(1) << (InBits - OutBits - 1)) - InBits'(1);
    logic [OutBits-1:0] top;
    logic               rb, st, up;
    logic [OutBits:0]   inc;
    always_comb begin
      top   = '0;
      rb    = 1'b0;
      st    = 1'b0;
      up    = 1'b0;
      inc   = '0;
      sig_o = '0;
      msb_o = '0;
      if (en_i) begin
        top = xn[InBits-1 -: OutBits];
        rb  = xn[InBits-OutBits-1];
        st  = |(xn & StickyMask);
        up  = rb & (st | top[0]);
        inc = {1'b0, top} + {{OutBits{1'b0}}, up};
        if (inc[OutBits]) begin  // 1.11..1 rounded up: renormalise
          sig_o = {1'b1, {(OutBits - 1){1'b0}}};
          msb_o = m + 1'b1;
        end else begin
          sig_o = inc[OutBits-1:0];
          msb_o = m;
        end
      end
    end
  end else if (InBits == OutBits) begin : gen_same
    assign sig_o = xn;
    assign msb_o = m;
  end else begin : gen_exact
    assign sig_o = {xn, {(OutBits - InBits){1'b0}}};
    assign msb_o = m;
  end
endmodule
