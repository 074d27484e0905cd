// fxr_clip_side: the exact sign of one clip-plane distance of one vertex (combinational), the
// model's plane_side() (model/stages/clip.cpp; docs/pipeline.md, stage 2 "Trivial accept /
// reject"; docs/rtl.md, "fxr_clip"). Used by fxr_clip 21 times for the trivial accept / reject of
// an input triangle (3 vertices x 7 planes) and once by its iterative clipper.
//
//   d = a*c + b*w            (wmin_i = 0; a, b sign and magnitude, c and w (neg, sig, exp) values)
//   d = w - 2^ClipWMinExp    (wmin_i = 1: the w_min plane)
//
// Each product is a term +-|k|*sig * 2^exp. If the two terms' leading ones differ, the larger term
// decides the sign; if they are equal the terms overlap within CoefBits + SigBits bits of the
// common leading one, so aligning the one with the larger exponent onto the other and adding in
// CoefBits + SigBits + 2 bits is exact. No rounding anywhere.
module fxr_clip_side #(
  parameter int CoefBits = 17,  // |a|, |b| < 2^CoefBits
  parameter int SigBits = 32,   // value significands
  parameter int ExpBits = 12,   // value exponents (signed, exponent of the lsb)
  parameter int WMinExp = -160  // the w_min plane's exponent
) (
  input  logic                a_neg_i,
  input  logic [CoefBits-1:0] a_mag_i,
  input  logic                b_neg_i,
  input  logic [CoefBits-1:0] b_mag_i,
  input  logic                wmin_i,
  input  logic                c_neg_i,
  input  logic [SigBits-1:0]  c_sig_i,
  input  logic [ExpBits-1:0]  c_exp_i,
  input  logic                w_neg_i,
  input  logic [SigBits-1:0]  w_sig_i,
  input  logic [ExpBits-1:0]  w_exp_i,
  output logic                neg_o,   // d < 0: strictly outside
  output logic                zero_o   // d = 0: on the plane (inside)
);
  localparam int TB = CoefBits + SigBits;        // term magnitude bits
  localparam int LB = ExpBits + 2;               // leading-one exponents: exp + msb, signed
  localparam int SumBits = TB + 2;               // aligned sum of two terms, signed

  function automatic logic [LB-1:0] msb_of(input logic [TB-1:0] x);
    msb_of = '0;
    for (int k = 0; k < TB; k++)
      if (x[k]) msb_of = LB'(k);
  endfunction
  function automatic logic [LB-1:0] msb_w(input logic [SigBits-1:0] x);
    msb_w = '0;
    for (int k = 0; k < SigBits; k++)
      if (x[k]) msb_w = LB'(k);
  endfunction

  logic [TB-1:0] m1, m2;
  logic n1, n2, z1, z2;
  logic signed [LB-1:0] e1, e2, l1, l2, wl, dexp;
  logic [TB-1:0] m1a, m2a;
  logic signed [SumBits-1:0] s1, s2, sum;
  logic tn, tz, wn, wz;

  assign m1 = TB'(a_mag_i) * TB'(c_sig_i);
  assign m2 = TB'(b_mag_i) * TB'(w_sig_i);
  assign n1 = a_neg_i ^ c_neg_i;
  assign n2 = b_neg_i ^ w_neg_i;
  assign z1 = ~|m1;
  assign z2 = ~|m2;
  assign e1 = LB'($signed(c_exp_i));
  assign e2 = LB'($signed(w_exp_i));
  assign l1 = e1 + $signed(msb_of(m1));
  assign l2 = e2 + $signed(msb_of(m2));

  // Equal leading ones: shift the term with the larger exponent left by the difference (< TB).
  localparam int ShBits = $clog2(TB) + 1;
  logic [ShBits-1:0] sh;
  assign dexp = e1 - e2;
  assign sh = (dexp > 0) ? ShBits'(dexp) : ShBits'(-dexp);  // used only when < TB
  always_comb begin
    m1a = m1;
    m2a = m2;
    if (dexp > 0) m1a = m1 << sh;
    else m2a = m2 << sh;
  end
  assign s1 = n1 ? -$signed(SumBits'(m1a)) : $signed(SumBits'(m1a));
  assign s2 = n2 ? -$signed(SumBits'(m2a)) : $signed(SumBits'(m2a));
  assign sum = s1 + s2;

  always_comb begin
    if (z1 && z2) begin
      tn = 1'b0;
      tz = 1'b1;
    end else if (z1) begin
      tn = n2;
      tz = 1'b0;
    end else if (z2) begin
      tn = n1;
      tz = 1'b0;
    end else if (l1 != l2) begin
      tn = (l1 > l2) ? n1 : n2;
      tz = 1'b0;
    end else begin
      tn = sum[SumBits-1];
      tz = ~|sum;
    end
  end

  // w - 2^WMinExp: negative for w <= 0 or a leading one below; zero iff w is that power of two.
  assign wl = e2 + $signed(msb_w(w_sig_i));
  always_comb begin
    if (~|w_sig_i || w_neg_i || wl < LB'(WMinExp)) begin
      wn = 1'b1;
      wz = 1'b0;
    end else if (wl == LB'(WMinExp)) begin
      wn = 1'b0;
      wz = ((w_sig_i & (w_sig_i - 1'b1)) == '0);
    end else begin
      wn = 1'b0;
      wz = 1'b0;
    end
  end

  assign neg_o = wmin_i ? wn : tn;
  assign zero_o = wmin_i ? wz : tz;
endmodule
