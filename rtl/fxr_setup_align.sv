// fxr_setup_align: block alignment of three FxFloats onto one exponent (combinational),
// instantiated by fxr_setup for 1/w and for every v/w. Model: fxr::align_block
// (model/stages/setup.cpp); docs/pipeline.md, stage 7 "Block alignment".
//
// Inputs are normalised (significand msb set) or zero, so the lead exponent of value k is
// exp_k + SigBits - 1 and the largest lead is the largest exp among the non-zero values.
//   exp_o = max exp + SigBits - Bits        (the largest gets its msb at bit Bits - 1)
//   q_k   = ±RNE(sig_k * 2^L / 2^R_k)       L = max(0, Bits - SigBits) (exact),
//                                           R_k = (max exp - exp_k) + max(0, SigBits - Bits)
// A right shift of R_k >= W + 1 (W = SigBits + L bits of the shifted significand) gives 0, so
// R_k saturates there. All three zero: q = 0, exp_o = 0. |q_k| <= 2^Bits: QB = Bits + 2 signed bits.
module fxr_setup_align #(
  parameter int SigBits = fxr_config_pkg::RasterAttrSigBits,
  parameter int ExpBits = 12,                                 // signed exponent of the lsb
  parameter int Bits    = fxr_config_pkg::RasterInterpBlockBits,
  localparam int QB     = Bits + 2
) (
  input  logic                 en_i,   // low: q_o, exp_o = 0 (not read; the simulator skips the alignment)
  input  logic [2:0]           neg_i,
  input  logic [3*SigBits-1:0] sig_i,
  input  logic [3*ExpBits-1:0] exp_i,
  output logic [3*QB-1:0]      q_o,
  output logic [ExpBits-1:0]   exp_o
);
  localparam int L   = Bits > SigBits ? Bits - SigBits : 0;
  localparam int RX  = SigBits > Bits ? SigBits - Bits : 0;
  localparam int W   = SigBits + L;             // shifted significand
  localparam int Cap = W + 1;                   // saturated right shift (result 0)
  localparam int DB  = ExpBits + 2;             // signed exponent differences
  localparam int SB  = $clog2(Cap + 1);         // right shift amount

  logic [2:0]             nz;
  logic                   first;
  logic signed [DB-1:0]   e [3];
  logic signed [DB-1:0]   emax, d;
  logic [SB-1:0]          r;
  logic [W+Cap-1:0]       ext;
  logic [W-1:0]           m;
  logic                   rnd, sticky, up;
  logic [QB-1:0]          mag;
  always_comb begin
    nz = '0;
    first = 1'b0;
    for (int k = 0; k < 3; k++) e[k] = '0;
    emax = '0;
    d = '0;
    r = '0;
    ext = '0;
    m = '0;
    rnd = 1'b0;
    sticky = 1'b0;
    up = 1'b0;
    mag = '0;
    exp_o = '0;
    q_o = '0;
    if (en_i) begin
      for (int k = 0; k < 3; k++) begin
        nz[k] = |sig_i[k*SigBits +: SigBits];
        e[k]  = DB'($signed(exp_i[k*ExpBits +: ExpBits]));
      end
      emax  = '0;
      first = 1'b1;
      for (int k = 0; k < 3; k++) begin
        if (nz[k] && (first || e[k] > emax)) emax = e[k];
        if (nz[k]) first = 1'b0;
      end
      exp_o = |nz ? ExpBits'(emax + DB'(SigBits) - DB'(Bits)) : '0;
      for (int k = 0; k < 3; k++) begin
        d = emax - e[k] + DB'(RX);
        r = (d > DB'(Cap)) ? SB'(Cap) : SB'(d);
        ext = {W'(sig_i[k*SigBits +: SigBits]) << L, Cap'(0)} >> r;
        m = ext[Cap +: W];
        rnd = ext[Cap-1];
        sticky = |ext[Cap-2:0];
        up  = rnd & (sticky | m[0]);
        mag = QB'(m) + QB'(up);
        q_o[k*QB +: QB] = !nz[k] ? '0 : (neg_i[k] ? -mag : mag);
      end
    end
  end
endmodule
