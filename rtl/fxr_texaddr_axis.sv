// fxr_texaddr_axis: one axis of the texture address unit (combinational), instantiated twice
// by fxr_texaddr. Model: fxr::texaddr_axis (model/stages/texaddr.hpp); rules: docs/texaddr.md.
//
//   e   = min(exp_i, 1) + (bilinear ? FracBits : 0)   (huge exponents: exact, docs/texaddr.md)
//   sh  = clamp(e + Cap, 0, Cap + 1 + FracBits)        Cap = SigBits + SizeBits + 2 (tiny |u|)
//   Y   = (+-sig_i * size_i) * 2^sh - offset * 2^Cap   offset = bilinear ? 2^(FracBits-1) : 0
//   T   = floor(Y / 2^Cap) (nearest) or RNE(Y / 2^Cap) (bilinear): the one rounding
//   i0  = bilinear ? floor(T / 2^FracBits) : T;  w = bilinear ? T mod 2^FracBits : 0
// Wrap (i1 = i0 + 1): repeat / mirrored repeat reduce |i0| modulo M = W or 2W bit-serially
// (a restoring remainder over the IdxBits bits of |i0|), negate for i0 < 0, step to i1 by one;
// the clamps compare i0 and i0 + 1 with 0 and W.
module fxr_texaddr_axis #(
  parameter int SigBits  = fxr_config_pkg::TexAddrSigBits,
  parameter int ExpBits  = fxr_config_pkg::TexAddrExpBits,
  parameter int SizeBits = fxr_config_pkg::TexAddrSizeBits,
  parameter int FracBits = fxr_config_pkg::TexAddrWeightFracBits
) (
  input  logic                bilinear_i,
  input  logic [1:0]          wrap_i,     // fxr_config_pkg::tex_addr_wrap_e
  input  logic                neg_i,
  input  logic [ExpBits-1:0]  exp_i,      // signed exponent of the lsb of sig_i
  input  logic [SigBits-1:0]  sig_i,
  input  logic [SizeBits:0]   size_i,     // in [1, 2^SizeBits]
  output logic [SizeBits-1:0] i0_o,
  output logic [SizeBits-1:0] i1_o,
  output logic                b0_o,
  output logic                b1_o,
  output logic [FracBits-1:0] w_o
);
  localparam int ProdBits = SigBits + SizeBits + 1;     // sig * size (< 2^(SigBits+SizeBits))
  localparam int Cap      = SigBits + SizeBits + 2;     // right-shift cap (model kShiftCapMargin = 2)
  localparam int ShMax    = Cap + 1 + FracBits;         // largest left shift
  localparam int YBits    = 1 + ProdBits + ShMax + 1;   // signed Y
  localparam int QBits    = YBits - Cap;                // signed T
  localparam int IdxBits  = QBits;                      // signed i0
  localparam int EBits    = ExpBits + 8;                // signed e + Cap (Cap, FracBits < 2^7)
  localparam int RBits    = SizeBits + 2;               // remainder modulo M <= 2^(SizeBits+1)

  // wrap_i is compared with the enumerators of fxr_config_pkg::tex_addr_wrap_e (the port stays
  // a plain 2-bit vector: the vector field's width).
  logic [1:0] wrap;
  assign wrap = wrap_i;

  // ---- scale and round ----------------------------------------------------------------------
  logic signed [EBits-1:0] e_lim, sh_s;
  logic [$clog2(ShMax+1)-1:0] sh;
  logic [ProdBits-1:0] mag;
  logic signed [YBits-1:0] x, y;
  logic signed [QBits-1:0] q, t, i0;
  logic [Cap-1:0] rem;
  logic up;
  always_comb begin
    e_lim = EBits'($signed(exp_i));
    if (e_lim > EBits'(1)) e_lim = EBits'(1);
    sh_s = e_lim + EBits'(Cap) + (bilinear_i ? EBits'(FracBits) : EBits'(0));
    if (sh_s < 0) sh_s = '0;
    sh   = sh_s[$clog2(ShMax+1)-1:0];
    mag  = ProdBits'(sig_i) * ProdBits'(size_i);
    x    = neg_i ? -$signed(YBits'(mag)) : $signed(YBits'(mag));
    y    = (x <<< sh) - (bilinear_i ? (YBits'(1) << (Cap + FracBits - 1)) : YBits'(0));
    q    = y[YBits-1:Cap];
    rem  = y[Cap-1:0];
    // RNE for bilinear: up when the dropped part is above one half, or exactly one half and q odd.
    up   = bilinear_i & rem[Cap-1] & ((|rem[Cap-2:0]) | q[0]);
    t    = q + QBits'(up);
    i0   = bilinear_i ? (t >>> FracBits) : t;
    w_o  = bilinear_i ? t[FracBits-1:0] : '0;
  end

  // ---- wrap ---------------------------------------------------------------------------------
  logic [RBits-1:0] m, r, r0, r1, w_ext;
  logic [IdxBits-1:0] abs_i0;
  logic signed [IdxBits:0] i0x, i1x, w_s;
  logic lo0, hi0, lo1, hi1;
  always_comb begin
    w_ext  = RBits'(size_i);
    m      = (wrap == 2'(fxr_config_pkg::TexAddrWrapMirroredRepeat)) ? (w_ext << 1) : w_ext;
    abs_i0 = i0[IdxBits-1] ? IdxBits'(-i0) : IdxBits'(i0);
    r = '0;
    for (int b = IdxBits - 1; b >= 0; b--) begin
      r = {r[RBits-2:0], abs_i0[b]};
      if (r >= m) r = r - m;
    end
    r0 = (i0[IdxBits-1] && r != '0) ? m - r : r;    // mathematical modulo of i0
    r1 = (r0 + RBits'(1) == m) ? '0 : r0 + RBits'(1);
    i0x = (IdxBits+1)'(i0);
    i1x = i0x + (IdxBits+1)'(1);
    w_s = $signed((IdxBits+1)'(size_i));
    lo0 = i0x < 0;
    hi0 = i0x >= w_s;
    lo1 = i1x < 0;
    hi1 = i1x >= w_s;
    b0_o = 1'b0;
    b1_o = 1'b0;
    unique case (wrap)
      2'(fxr_config_pkg::TexAddrWrapRepeat): begin
        i0_o = SizeBits'(r0);
        i1_o = SizeBits'(r1);
      end
      2'(fxr_config_pkg::TexAddrWrapMirroredRepeat): begin
        i0_o = SizeBits'(r0 < w_ext ? r0 : m - RBits'(1) - r0);
        i1_o = SizeBits'(r1 < w_ext ? r1 : m - RBits'(1) - r1);
      end
      2'(fxr_config_pkg::TexAddrWrapClampToEdge), 2'(fxr_config_pkg::TexAddrWrapClampToBorder): begin
        i0_o = lo0 ? '0 : (hi0 ? SizeBits'(size_i - 1'b1) : SizeBits'(i0x));
        i1_o = lo1 ? '0 : (hi1 ? SizeBits'(size_i - 1'b1) : SizeBits'(i1x));
        b0_o = (wrap == 2'(fxr_config_pkg::TexAddrWrapClampToBorder)) & (lo0 | hi0);
        b1_o = (wrap == 2'(fxr_config_pkg::TexAddrWrapClampToBorder)) & (lo1 | hi1);
      end
      default: begin
        i0_o = '0;
        i1_o = '0;
      end
    endcase
    if (!bilinear_i) begin  // nearest: one texel
      i1_o = i0_o;
      b1_o = b0_o;
    end
  end
endmodule
