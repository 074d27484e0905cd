// model/stages/attr.hpp — attribute positions (issue 8): the depth and varying planes are set up
// from window positions of higher precision than the snapped coverage positions.
// docs/pipeline.md, "Attribute positions".
//
// Coverage keeps the snapped positions (raster.subpixel_bits, top-left rule, watertight). Depth
// and varyings are affine / rational functions of the window position, so a vertex shift of
// δ px moves them by their gradient times δ: on snapped positions (δ ≤ 2^−9 px) that is a
// bias of tens of D24 LSB on steep planes and thousands on slivers. With
// raster.attr_subpixel_bits = A > subpixel_bits:
//   per vertex   x_a = RNE(x_w·2^A), x_w = (x_c/w_c + 1)·W/2 + X0, from the EXACT quotient
//                (a correctly rounded division, not x_c·rcp(w_c)); likewise y; and
//                z = RNE(z_c/w_c·2^z_frac_bits), saturated to [0, 2^z_frac_bits];
//   per triangle relative coordinates: every vertex and every candidate pixel centre relative
//                to vertex 0, in raster.attr_coord_bits signed bits. When the triangle's extent
//                needs more, the positions drop s low bits (RNE) to F = A − s fraction bits
//                (F ≥ attr_coord_bits − window_int_bits − 1 for any triangle of the window range);
//   planes       P(i, j) = Σ_k E'_k(centre)·Q_k with the attribute edge functions E'_k: exact
//                i128 integers, anchored at the candidate rectangle's corner (so no evaluated
//                value leaves its derived width), evaluated exactly at every pixel centre.
// With A ≤ subpixel_bits this stage is not used (the planes take the coverage edge functions).
#pragma once

#include <cstdint>

#include "model/arith/fxfloat.hpp"
#include "model/config/config.hpp"
#include "model/stages/setup.hpp"

namespace fxr {

// True when the planes are set up from separate attribute positions (A > subpixel_bits).
inline bool attr_separate(const RasterConfig& c) { return attr_planes(c); }

// ---- widths (derived; docs/pipeline.md "Attribute positions") ------------------------------
// Signed bits of an attribute edge value and of 2·area' (relative coordinates < 2^(acb−1), so
// each cross-product component is < 2^acb): 2·acb + 2.
constexpr int attr_edge_value_bits(const RasterConfig& c) { return 2 * c.attr_coord_bits + 2; }
// Signed bits of the per-vertex attribute position: window_int_bits integer bits + A fraction bits.
constexpr int attr_position_bits(const RasterConfig& c) { return c.window_int_bits + c.attr_subpixel_bits; }

// Contract (only when attr_separate): ConfigError naming the field unless positions fit
// int64 (attr_position_bits ≤ 62), attr_coord_bits ≥ window_int_bits + 2 (so F ≥ 1 for every
// triangle) and the depth / interpolator sums fit i128 (see attr_edge_value_bits).
void check_attr_widths(const Config& cfg);

// Contract: RNE(((c/w) + 1)·size/2·2^A + origin·2^A), the exact quotient c/w (w > 0) rounded
// ONCE; A ≥ 1. *range is set when the result leaves a signed attr_position_bits code.
int64_t attr_window(const FxFloat& c, const FxFloat& w, int64_t size, int64_t origin, const RasterConfig& rc,
                    bool* range);

// Contract: RNE(z/w · 2^z_frac_bits) from the exact quotient (w > 0), saturated to
// [0, 2^z_frac_bits] (z < 0 → 0, z > w → 2^z_frac_bits).
uint64_t attr_depth(const FxFloat& z, const FxFloat& w, const RasterConfig& rc);

// Contract: RNE(n / w) to a normalised `bits`-bit significand FxFloat (w > 0; n = 0 gives 0), from
// the exact quotient: one rounding. bits ≤ 62.
FxFloat attr_quotient(const FxFloat& n, const FxFloat& w, int bits);

// The i128 references of the three above: attr_window, attr_depth and attr_quotient take a
// 64-bit path when its range test passes and these otherwise (docs/speed.md "Session 9: per
// triangle"; tests/model/attr_fast64_test.cpp runs both).
int64_t attr_window_wide(const FxFloat& c, const FxFloat& w, int64_t size, int64_t origin, const RasterConfig& rc,
                         bool* range);
uint64_t attr_depth_wide(const FxFloat& z, const FxFloat& w, const RasterConfig& rc);
FxFloat attr_quotient_wide(const FxFloat& n, const FxFloat& w, int bits);

// Contract: RNE(C + (−1)^neg · N·2^k / D), exact (D > 0; N, D below 2^100 as attr_window,
// attr_depth pass them). *overflow when N·2^k cannot be formed (then the quotient is far beyond
// every window / depth range and the caller saturates or rejects). The i128 reference of
// rne_quotient_plus64.
i128 rne_quotient_plus(bool neg, u128 N, int k, u128 D, i128 C, bool* overflow);

// The 64-bit paths' bound: shifted operands and offsets below 2^kAttrFast64Bits.
inline constexpr int kAttrFast64Bits = 61;
// Contract: true when N·2^k and D (k ≥ 0) or N and D·2^−k (k < 0), and |C|, are below
// 2^kAttrFast64Bits and D > 0; *out is then RNE(C + (−1)^neg·N·2^k/D), exact. false: out of range, nothing written.
bool rne_quotient_plus64(bool neg, uint64_t N, int k, uint64_t D, int64_t C, int64_t* out);
// Contract: true when bits ≤ kAttrFast64Bits, w > 0 and attr_quotient's shifted operand is below
// 2^63; *out is then attr_quotient(n, w, bits). false: nothing written.
bool attr_quotient64(const FxFloat& n, const FxFloat& w, int bits, FxFloat* out);

// The attribute triangle of one set-up triangle: relative integer coordinates at F fraction bits.
struct AttrSetup {
  int F = 0;                 // fraction bits used for this triangle (≤ attr_subpixel_bits)
  int64_t ox = 0, oy = 0;    // origin: vertex 0 at F bits (absolute window position · 2^F)
  int64_t x[3], y[3];        // vertices relative to the origin (x[0] = y[0] = 0)
  i128 a[3], b[3], c[3];     // E'_k(X, Y) = a·X + b·Y + c in relative coordinates, CCW-normalised
  i128 area2 = 0;            // 2·area' (> 0), attr_edge_value_bits
  int i0 = 0, j0 = 0;        // plane anchor: the candidate rectangle's corner
  bool ok = false;           // false: 2·area' = 0 (then the planes fall back to the coverage triangle)
};

// Contract: the attribute triangle of `tri` (SetupVertex.ax, ay at attr_subpixel_bits) for the
// candidate rectangle of `t`. Exact apart from the documented drop to F bits. Orientation is
// normalised by the sign of 2·area' itself (it may differ from the snapped triangle's on
// near-degenerate triangles; barycentrics E'_k / 2A' do not depend on it).
AttrSetup attr_setup(const Config& cfg, const SetupTriangle& tri, const TriSetup& t);

// Contract: the plane Σ_k E'_k(centre(i, j))·q[k] anchored at (a.i0, a.j0); exact. (The
// reference: setup takes attr_plane below, the same values.)
Plane make_attr_plane(const AttrSetup& a, const int64_t q[3]);

// The attribute edge functions of one triangle at its plane anchor, shared by all its planes
// (docs/speed.md "Shortcuts"): per edge k the steps one pixel right / up, a_k·2^F and b_k·2^F,
// and the value E'_k(centre(i0, j0)); fits64 when all nine fit int64_t (then also in the *64
// members). A triangle of a few pixels at F = 24 needs ≈ 2^53.
struct AttrEdgeTerms {
  i128 dx[3], dy[3], e0[3];
  int64_t dx64[3], dy64[3], e064[3];
  bool fits64;
  int i0, j0;
  AttrEdgeTerms() : dx{}, dy{}, e0{}, dx64{}, dy64{}, e064{}, fits64(false), i0(0), j0(0) {}
  // Members left unset, for a caller that writes every one before reading (attr_plane_setup:
  // the 240-byte zero fill was a third of its samples, docs/speed.md "Session 9: per triangle").
  struct Unset {};
  explicit AttrEdgeTerms(Unset) {}
};
AttrEdgeTerms attr_edge_terms(const AttrSetup& a);

// The same terms straight from the vertices in 64-bit words (docs/speed.md "Session 8: the
// bunny's per-triangle cost"): attr_setup(cfg, tri, t) then attr_edge_terms, every
// intermediate value (the magnitude M, the dropped positions, the coefficients, the cross
// products, the edge values at the anchor) formed in int64_t with an overflow check. Done:
// `out` equals attr_edge_terms(attr_setup(cfg, tri, t)) member for member (fits64 set) and
// *area2 its area2; ZeroArea: attr_setup's ok = false (2·area' = 0); Wide: some value did not
// fit int64_t — nothing is decided, the caller takes attr_setup / attr_edge_terms. Needs
// attr_separate and check_attr_widths. Tests: AttrTerms64.* (tests/model/attr_plane_test.cpp),
// 10^8 random in attr_plane_slow_test.cpp.
enum class AttrTerms64 : uint8_t { Done, ZeroArea, Wide };
AttrTerms64 attr_edge_terms64(const Config& cfg, const SetupTriangle& tri, const TriSetup& t, AttrEdgeTerms& out,
                              i128* area2);

// Contract: make_attr_plane(a, q) for t = attr_edge_terms(a), bit for bit: Σ_k term_k·q[k] with
// the terms formed once per triangle; each product int64_t × int64_t → i128 (one widening
// multiply) when t.fits64, else i128 × i128. Tests: AttrPlane.* (tests/model/attr_test.cpp),
// 10^8 random in attr_slow_test.cpp.
Plane attr_plane(const AttrEdgeTerms& t, const int64_t q[3]);
// The same written into `out` (no Plane returned through the stack).
void attr_plane_to(const AttrEdgeTerms& t, const int64_t q[3], Plane& out);

// Contract: the depth plane's vertex value of a vertex with depth z (z_frac_bits):
// RNE(z·(2^db − 1) / 2^db), i.e. z·(2^db − 1) with z_frac_bits − db fraction bits of an LSB.
// In int64 words when the product and the rounding sum fit (three per triangle, docs/speed.md
// "Session 12: per triangle"), else in i128. The int64 rounding has no branch: with
// p = q·2^db + r (0 ≤ r < 2^db, p ≥ 0), (p + 2^(db−1) − 1 + (q & 1)) >> db is q + 1 exactly when
// r > 2^(db−1), or r = 2^(db−1) and q is odd — round half to even (shift_round_right's branches
// on the remainder mispredicted on the bunny's depths).
inline int64_t attr_depth_q(const RasterConfig& rc, uint64_t z) {
  const int db = rc.depth_bits();
  const int64_t M = (int64_t)((1u << db) - 1);
  int64_t p;
  if (db >= 1 && db <= kInt64ShiftMax && z <= (uint64_t)INT64_MAX && !__builtin_mul_overflow((int64_t)z, M, &p) &&
      p <= INT64_MAX - ((int64_t)1 << db))
    return (p + ((int64_t)1 << (db - 1)) - 1 + ((p >> db) & 1)) >> db;
  return (int64_t)shift_round((i128)z * M, db, Round::HalfEven);  // product < 2^64 · 2^db
}

// Contract: depth_setup (depth.hpp) on the attribute triangle: Z = Σ E'_k·z_k·(2^db − 1),
// den = 2A'·2^z_frac_bits. Pixel centres slightly outside the attribute triangle extrapolate:
// DepthStepper clamps the code to [0, 2^db − 1].
DepthSetup attr_depth_setup(const Config& cfg, const SetupTriangle& tri, const AttrSetup& a);

// Contract: interp_setup (interp.hpp) on the attribute triangle (same block alignment).
void attr_interp_setup(const Config& cfg, const DrawState& st, const SetupTriangle& tri, const AttrSetup& a,
                       InterpSetup& out);

}  // namespace fxr
