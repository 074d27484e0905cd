// fxr_divide_norm: normalisation of a non-negative integer to an OutBits significand with its msb
// set, rounded to nearest even (combinational); stage 9's operand normalisation (fxr_divide).
// Model: fxr::normalize(x, OutBits, Round::HalfEven) (model/arith/fixed.hpp) as normalize_den /
// divide_varying call it (model/stages/divide.hpp).
//
//   x_i > 0: m = index of the leading one; sig_o = x * 2^(OutBits-1-m) when m < OutBits (exact),
//   else RNE(x / 2^(m-OutBits+1)); a carry out of the rounding renormalises (sig_o = 2^(OutBits-1),
//   m + 1). msb_o = m (+1 on the carry). x_i = 0: sig_o = 0, msb_o = 0.
module fxr_divide_norm #(
  parameter int InBits  = 93,
  parameter int OutBits = 32,
  parameter int MsbBits = 8
) (
  input  logic [InBits-1:0]  x_i,
  output logic [OutBits-1:0] sig_o,
  output logic [MsbBits-1:0] msb_o
);
  // Leading one (priority encoder) and the left shift that puts it at bit InBits-1.
  logic [MsbBits-1:0] m;
  always_comb begin
    m = '0;
    for (int i = 0; i < InBits; i++) begin
      if (x_i[i]) m = MsbBits'(i);
    end
  end
  logic [InBits-1:0] xn;
  assign xn = x_i << (MsbBits'(InBits - 1) - m);

  if (InBits > OutBits) begin : gen_round
    logic [OutBits-1:0] top;
    logic               rb, st, up;
    logic [OutBits:0]   inc;
    assign top = xn[InBits-1 -: OutBits];
    assign rb  = xn[InBits-OutBits-1];
    if (InBits - OutBits >= 2) begin : gen_sticky
      assign st = |xn[InBits-OutBits-2:0];
    end else begin : gen_no_sticky
      assign st = 1'b0;
    end
    assign up  = rb & (st | top[0]);
    assign inc = {1'b0, top} + {{OutBits{1'b0}}, up};
    always_comb begin
      if (inc[OutBits]) begin  // 1.11..1 rounded up: renormalise
        sig_o = {1'b1, {(OutBits - 1){1'b0}}};
        msb_o = m + 1'b1;
      end else begin
        sig_o = inc[OutBits-1:0];
        msb_o = m;
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
