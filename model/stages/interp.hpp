// model/stages/interp.hpp — stage 7 (interpolators) and stage 9 (per-pixel divide) of the raster unit.
// docs/pipeline.md, stages 7 and 9.
//
// Everything the unit interpolates is an affine function of the pixel (i, j) with exact
// integer coefficients: for per-vertex integers Q_k,
//     P(i, j) = Σ_k E_k(centre(i, j)) · Q_k = c + i·dx + j·dy           (a "plane", i128)
// where E_k are the unbiased edge functions of setup (E_k / 2A is the barycentric weight of
// vertex k). The perspective-correct varying is (seed 000, 004; the 2A cancels)
//     v = Σ E_k·vw_k / Σ E_k·rw_k = N / D,
// with vw_k = v_k/w_k and rw_k = 1/w_k. N and D are exact integer planes once the three vw_k
// (and the three rw_k) are put on one block exponent: the only roundings are
//   (1) block alignment (align_block): RNE to raster.interp_block_bits, exact while the lead
//       exponents of the three values differ by ≤ interp_block_bits − significand bits;
//   (2) normalising |N| and D to the divider's num_bits / den_bits significands (RNE);
//   (3) the divider itself (model/arith/div.hpp: RNE of its quotient to quot_bits).
// Affine mode (InterpMode::Affine, seed 000's wrong image): vw_k holds v_k itself and D = 2A.
#pragma once

#include <cstdint>

#include "model/config/config.hpp"
#include "model/arith/div.hpp"
#include "model/arith/fxfloat.hpp"
#include "model/stages/setup.hpp"

namespace fxr {

// P(i, j) = c + i·dx + j·dy over pixel indices (exact; widths checked by validate(), model/config/validate.hpp).
struct Plane {
  i128 c = 0, dx = 0, dy = 0;
  i128 at(int i, int j) const { return c + (i128)i * dx + (i128)j * dy; }
};

// Contract: the plane Σ_k E_k(centre(i, j))·q[k] of a set-up triangle; exact.
//   |q[k]| < 2^qbits gives |P| < 2^(edge_value_bits + qbits + 1) inside the window range.
Plane make_plane(const TriSetup& t, const int64_t q[3]);

// Three values on one block exponent: value_k = q[k] · 2^exp.
struct Block3 {
  int64_t q[3] = {0, 0, 0};
  int exp = 0;
};

// Contract: aligns three FxFloats to the block exponent of the largest magnitude, which gets
// its msb at bit `bits` − 1 (bits ≤ 62); the others are shifted right by their lead-exponent
// difference and rounded to nearest even — PRECISION IS LOST HERE when that difference
// exceeds bits − (significand bits); a value below half a block ulp becomes 0. Signs kept
// (two's complement). All three zero: q = 0, exp = 0. Rounding never overflows (a carry of
// the largest to 2^bits still fits int64).
Block3 align_block(const FxFloat v[3], int bits);

// Per-triangle interpolation setup: the denominator plane and one numerator plane per varying.
struct InterpSetup {
  Plane den;                 // D = Σ E_k·R_k (> 0 inside), value D·2^den_exp
  int den_exp = 0;
  Plane num[kMaxVaryings];   // N_m = Σ E_k·V_{m,k}, value N_m·2^num_exp[m]
  int num_exp[kMaxVaryings] = {};
  int n = 0;                 // number of varyings
};

// Contract: builds the planes of stage 7 for `tri` (perspective: D from rw; affine: D = 2A,
// i.e. R_k = 1). Uses raster.interp_block_bits. Exact apart from align_block's rounding.
void interp_setup(const Config& cfg, const DrawState& st, const SetupTriangle& tri, const TriSetup& t,
                  InterpSetup& out);

// Contract (stage 9): the varying N·2^en / (D·2^ed) as a normalised FxFloat with
// div.quot_bits (= raster.varying_out_sig_bits) significand bits.
//   D > 0 (always inside a triangle with all rw_k > 0); D ≤ 0 or N == 0 → zero (sig 0).
//   |N| is rounded (RNE) to div.num_bits and D to div.den_bits significant bits — PRECISION
//   IS LOST HERE when they have more bits — then div_sig rounds the quotient (RNE).
//   Sign-magnitude: the divider sees magnitudes, the sign of N is the result's sign.
struct DenNorm {
  uint64_t d = 0;  // D's significand, msb at den_bits − 1
  int e = 0;       // msb index of D (after rounding carry) + ed
};
inline DenNorm normalize_den(const DivConfig& dc, i128 D, int ed) {
  DenNorm r;
  if (D <= 0) return r;
  const Normalized nd = normalize((u128)D, dc.den_bits, Round::HalfEven);
  r.d = nd.sig;
  r.e = nd.exp + ed;
  return r;
}
inline FxFloat divide_varying(const DivConfig& dc, i128 N, int en, const DenNorm& dn) {
  FxFloat out;
  if (N == 0 || dn.d == 0) return out;
  out.neg = N < 0;
  const u128 mag = N < 0 ? (u128)0 - (u128)N : (u128)N;
  const Normalized nn = normalize(mag, dc.num_bits, Round::HalfEven);
  const DivSig q = div_sig(dc, nn.sig, dn.d);
  // value = sig·2^−(qb−1)·2^exp_adj · 2^(msb N + en) / 2^(msb D + ed)
  out.sig = q.sig;
  out.exp = q.exp_adj + (nn.exp + en) - dn.e - (dc.quot_bits - 1);
  return out;
}

// div.quot_bits is derived from raster.varying_out_sig_bits (model/config/validate.hpp:
// derive_widths; validate() rejects a configuration where they differ).

}  // namespace fxr
