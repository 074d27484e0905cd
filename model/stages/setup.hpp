// model/stages/setup.hpp — stage 5 (triangle setup): exact integer edge functions, area, culling,
// the top-left fill rule and the bounding box. docs/pipeline.md, stage 5.
//
// Grid. Snapped vertices arrive with raster.subpixel_bits fraction bits. Setup works on the
// "sample grid", which has g = grid_bits(cfg) = max(subpixel_bits, 1) fraction bits so that the
// pixel centre (i + ½, j + ½) is an integer point: X = i·2^g + 2^(g−1). For subpixel_bits ≥ 1 the
// grid is the snap grid itself; for subpixel_bits = 0 vertices are doubled (exact).
//
// Edge functions (docs/references.md#seed-001-edge-function). For the directed edge a → b,
//     E(X, Y) = (y_a − y_b)·X + (x_b − x_a)·Y + (x_a·y_b − x_b·y_a)
// which is cross(b − a, p − a): positive to the left of a → b. Edge k is the edge opposite
// vertex k (from v_{k+1} to v_{k+2}), so E_k(v_k) = 2·area and E_0 + E_1 + E_2 = 2·area at
// every point (an exact integer invariant). After setup the triangle is normalised to
// counter-clockwise winding in y-up window space (all three functions negated for a clockwise
// triangle), so E_k ≥ 0 inside, and E_k / 2A is the barycentric weight of vertex k.
//
// Top-left rule (D3D11 definition, in y-up window coordinates). A pixel centre exactly on an
// edge is inside only if that edge is a top edge (exactly horizontal, with the triangle below
// it: the edge with the greater y) or a left edge (not horizontal, with the triangle to its
// right). On a counter-clockwise triangle with edge coefficients A = y_a − y_b, B = x_b − x_a
// (the gradient (A, B) points inside):  left ⇔ A > 0;  top ⇔ A = 0 and B < 0.
// It is applied as an exact bias on the edge constant: bias = 0 on top / left edges and −1 on
// the others, and a centre is covered iff E_k + bias_k ≥ 0 for k = 0, 1, 2 (E is an integer,
// so E > 0 ⇔ E − 1 ≥ 0). This is D3D's rule read in y-up coordinates; llvmpipe's rule in y-up
// coordinates makes left and bottom edges inclusive instead (docs/references.md#peer-fill-rule): mirror y to compare.
#pragma once

#include <atomic>
#include <cstdint>

#include "model/config/config.hpp"
#include "model/arith/fixed.hpp"
#include "model/arith/fxfloat.hpp"
#include "model/unit/io.hpp"
#include "model/unit/record.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

// ---- widths (derived; docs/pipeline.md stage 5 table) --------------------------------------

// Fraction bits of the sample grid: ≥ 1 so the pixel centre offset 2^(g−1) is an integer.
constexpr int grid_bits(const RasterConfig& c) { return c.subpixel_bits > 0 ? c.subpixel_bits : 1; }
// Signed bits of a vertex coordinate on the sample grid: window_int_bits integer bits (guard
// band included) + grid_bits fraction bits. Range [−2^(cb−1), 2^(cb−1)).
constexpr int coord_bits(const RasterConfig& c) { return c.window_int_bits + grid_bits(c); }
// Signed bits of an edge coefficient A or B: a difference of two coordinates, |A| < 2^cb.
constexpr int edge_coef_bits(const RasterConfig& c) { return coord_bits(c) + 1; }
// Signed bits of an edge value (and of 2·area) at any point p of the coordinate range:
// E = cross(b − a, p − a) with each component of magnitude < 2^cb, so |E| < 2·2^(2cb) and
// 2·cb + 2 signed bits hold it (50 bits at 16.8, docs/references.md#widths). Stepping adds no bits (every stepped
// value is the exact value at a sample point); the −1 top-left bias cannot overflow either.
constexpr int edge_value_bits(const RasterConfig& c) { return 2 * coord_bits(c) + 2; }
// Edge values are held in int64_t.
inline constexpr int kEdgeValueMaxBits = 63;

// The rules that keep edge values in int64 and the interpolator / depth sums in i128 are
// checked by validate() (model/config/validate.hpp), which frame_begin calls.

// ---- stage 5 input: the record between the geometry stages (1–4) and the raster stages (5–10)
//
// A vertex after input conversion, clipping, the reciprocal unit, the perspective divide and
// viewport snapping. Formats (named in the configuration, see docs/pipeline.md):
//   x, y: window coordinates in subpixel units (raster.subpixel_bits fraction bits), snapped
//         with round-to-nearest-even; y up, pixel centres at (i + ½)·2^subpixel_bits.
//   z:    z_c / w_c ∈ [0, 1] as an unsigned fraction with raster.z_frac_bits bits.
//   rw:   1/w_c from the reciprocal unit, a normalised FxFloat (recip.out_sig_bits significand).
//   vw:   v_k · (1/w_c) per varying, a normalised FxFloat (raster.varying_sig_bits), or, in the
//         affine mode, v_k itself.
//
// With separate attribute positions (raster.attr_subpixel_bits > subpixel_bits; model/stages/attr.hpp):
//   ax, ay: window coordinates with attr_subpixel_bits fraction bits, RNE of the exact quotient;
//   z:      RNE of the exact z_c / w_c (not z_c·rcp(w_c));
//   rw, vw: RNE of the exact 1/w_c and v_k / w_c to raster.attr_sig_bits.
// Otherwise ax, ay equal x, y (and are not part of the record).
struct SetupVertex {
  int64_t x = 0, y = 0;
  int64_t ax = 0, ay = 0;
  uint64_t z = 0;
  FxFloat rw;
  FxFloat vw[kMaxVaryings];

  // Widths: x, y signed window_int_bits + subpixel_bits (the snap's range), z z_frac_bits + 1
  // (z = 1 is 2^z_frac_bits); ax, ay signed window_int_bits + attr_subpixel_bits.
  template <class V>
  void visit(V& v, const RecordShape& s, const std::string& pre) {
    const RasterConfig& r = s.cfg.raster;
    const bool attr = r.attr_subpixel_bits > r.subpixel_bits;
    v(pre + "x", x, r.window_int_bits + r.subpixel_bits, true);
    v(pre + "y", y, r.window_int_bits + r.subpixel_bits, true);
    if (attr) {
      v(pre + "ax", ax, r.window_int_bits + r.attr_subpixel_bits, true);
      v(pre + "ay", ay, r.window_int_bits + r.attr_subpixel_bits, true);
    }
    v(pre + "z", z, r.z_frac_bits + 1, false);
    visit_fx(v, pre + "rw", rw, attr ? r.attr_sig_bits : s.cfg.recip.out_sig_bits, s);
    for (int k = 0; k < s.num_varyings; ++k)
      visit_fx(v, pre + "vw" + std::to_string(k), vw[k], attr ? r.attr_sig_bits : r.varying_sig_bits, s);
  }
};

// Stage 4 output, stage 5 input.
struct SetupTriangle {
  SetupVertex v[3];
  uint32_t prim = 0;  // index of the input primitive it came from

  template <class V>
  void visit(V& v_, const RecordShape& s) {
    v_("prim", prim, kPrimIdBits, false);
    for (int i = 0; i < 3; ++i) v[i].visit(v_, s, field_prefix("v", i));
  }
};

// The draw state stage 5 reads, as per-draw inputs of the hardware (rtl/fxr_setup.sv; the setup
// vectors list these fields from here). Widths as the draw state's register block: origins
// signed window_int_bits pixel indices, sizes signed window_int_bits + 1 (a negative scissor
// size, −1 by default, means "no scissor"), cull 2 bits (CullMode), front_ccw 1 bit, interp
// 1 bit (InterpMode: 1 = affine).
template <class V>
void visit_setup_state(V& v, const RecordShape& s, DrawState& st) {
  st.visit_rects(v, s);  // the register block's fields (DrawState::visit), the subset setup reads
  v("cull", st.cull, kCullModeBits, false);
  v("front_ccw", st.front_ccw, 1, false);
  v("interp", st.interp, kInterpModeBits, false);
}

// ---- coverage: edge functions ------------------------------------------------------------------------

// One edge function on the sample grid: E(X, Y) = a·X + b·Y + c, and its top-left bias.
struct EdgeEq {
  int64_t a = 0, b = 0, c = 0;  // edge_coef_bits, edge_coef_bits, edge_value_bits (signed)
  int64_t bias = 0;             // 0 on a top or left edge, −1 otherwise
};

// Contract: E(X, Y) exactly, X, Y on the sample grid (no bias). |result| < 2^(edge_value_bits−1)
// for X, Y in the coordinate range.
inline int64_t edge_eval(const EdgeEq& e, int64_t X, int64_t Y) { return e.a * X + e.b * Y + e.c; }

// The sample grid coordinate of pixel centre i: i·2^g + 2^(g−1) (exact).
inline int64_t pixel_centre(int i, int g) { return (int64_t)i * ((int64_t)1 << g) + ((int64_t)1 << (g - 1)); }  // i may be < 0

// Setup of one triangle.
struct TriSetup {
  EdgeEq e[3];           // e[k] opposite vertex k, counter-clockwise normalised: E_k ≥ 0 inside
  int64_t area2 = 0;     // 2·area on the sample grid, > 0 (edge_value_bits)
  bool front = true;     // front-facing per DrawState.front_ccw
  int g = 1;             // grid_bits
  int x0 = 0, x1 = -1, y0 = 0, y1 = -1;  // candidate pixels, inclusive: bbox ∩ viewport ∩ scissor
};

enum class SetupOutcome : uint8_t { Ok, CulledZeroArea, CulledBackface, CulledNoSamples, RejectedRange };

// The pixel rectangle a draw may touch: viewport ∩ scissor, inclusive bounds (x1 < x0: empty).
struct PixelRect {
  int x0 = 0, x1 = -1, y0 = 0, y1 = -1;
};
PixelRect draw_rect(const DrawState& st);

// Contract: stage 5 on one snapped triangle.
//   Input: vertex x, y in subpixel units (raster.subpixel_bits fraction bits, signed, within
//   ±2^(window_int_bits−1) pixels); anything outside → RejectedRange (documented discard; the
//   geometry stage should never produce it); likewise z > 1 (more than 2^z_frac_bits).
//   Zero area (collinear or repeated vertices, after snapping) → CulledZeroArea.
//   Back faces per st.cull and st.front_ccw → CulledBackface (zero area is never "back").
//   No candidate pixel (bbox of the pixel centres inside the vertex bbox ∩ draw_rect) →
//   CulledNoSamples. Otherwise Ok and `out` filled. All arithmetic exact (int64).
SetupOutcome setup_triangle(const Config& cfg, const DrawState& st, const SetupTriangle& tri, TriSetup& out);

// The pixels any triangle of a draw may have as candidates: draw_rect(st) ∩ the window
// coordinate range ±2^(window_int_bits − 1) (a pixel outside it is never a candidate, which keeps
// every evaluated edge value within edge_value_bits). A function of the draw only.
PixelRect setup_rect(const Config& cfg, const DrawState& st);
// Contract: setup_triangle(cfg, st, tri, out) with rect = setup_rect(cfg, st) formed once per
// draw by the caller (SetupStage: it was formed per triangle, docs/speed.md "Session 11: per
// triangle").
SetupOutcome setup_triangle(const Config& cfg, const DrawState& st, const PixelRect& rect, const SetupTriangle& tri,
                            TriSetup& out);

// ---- plane equations for z, 1/w and v/w (docs/pipeline.md, stages 7 and 8) -----------------

// P(i, j) = c + i·dx + j·dy over pixel indices (exact; widths checked by validate(), model/config/validate.hpp).
struct Plane {
  i128 c = 0, dx = 0, dy = 0;
  int i0 = 0, j0 = 0;  // anchor: c is the value at pixel (i0, j0) (attribute planes; 0 otherwise)
  i128 at(int i, int j) const { return c + (i128)(i - i0) * dx + (i128)(j - j0) * dy; }
};

// Contract: the plane Σ_k E_k(centre(i, j))·q[k] of a set-up triangle; exact.
//   |q[k]| < 2^qbits gives |P| < 2^(edge_value_bits + qbits + 1) inside the window range.
Plane make_plane(const TriSetup& t, const int64_t q[3]);
// The same written into `out` (no Plane returned through the stack).
void make_plane_to(const TriSetup& t, const int64_t q[3], Plane& out);

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
// The i128 reference of align_block (which takes int64 words where they suffice; tests/model/
// attr_fast64_test.cpp runs both).
Block3 align_block_wide(const FxFloat v[3], int bits);

// Per-triangle interpolation setup: the denominator plane and one numerator plane per varying.
struct InterpSetup {
  Plane den;                 // D = Σ E_k·R_k (> 0 inside), value D·2^den_exp
  int den_exp = 0;
  Plane num[kMaxVaryings];   // N_m = Σ E_k·V_{m,k}, value N_m·2^num_exp[m]
  int num_exp[kMaxVaryings] = {};
  int n = 0;                 // number of varyings
};

// The planes of stage 7 from per-vertex block values: D from the block-aligned 1/w (affine:
// R_k = 1, D = 2A), N_m from the block-aligned v_m/w; `plane(q, p)` writes Σ E_k·q[k] with the
// edge functions of the caller's triangle (coverage or attribute positions) into p (a Plane
// returned and copied stalled on store forwarding, docs/speed.md "Session 12: per triangle").
template <class MakePlane>
void build_interp_planes(const Config& cfg, const DrawState& st, const SetupTriangle& tri, InterpSetup& out,
                         MakePlane&& plane) {
  const int bits = cfg.raster.interp_block_bits;
  out.n = st.num_varyings;
  if (st.interp == InterpMode::Affine) {
    const int64_t one[3] = {1, 1, 1};
    plane(one, out.den);
    out.den_exp = 0;
  } else {
    const FxFloat rw[3] = {tri.v[0].rw, tri.v[1].rw, tri.v[2].rw};
    const Block3 r = align_block(rw, bits);
    plane(r.q, out.den);
    out.den_exp = r.exp;
  }
  for (int m = 0; m < out.n; ++m) {
    const FxFloat vw[3] = {tri.v[0].vw[m], tri.v[1].vw[m], tri.v[2].vw[m]};
    const Block3 b = align_block(vw, bits);
    plane(b.q, out.num[m]);
    out.num_exp[m] = b.exp;
  }
}

// Contract: builds the planes of stage 7 for `tri` (perspective: D from rw; affine: D = 2A,
// i.e. R_k = 1). Uses raster.interp_block_bits. Exact apart from align_block's rounding.
void interp_setup(const Config& cfg, const DrawState& st, const SetupTriangle& tri, const TriSetup& t,
                  InterpSetup& out);

// The maximum depth code (buffer clear value): 2^depth_bits − 1.
inline uint32_t depth_max_code(const RasterConfig& c) { return (uint32_t)((1u << c.depth_bits()) - 1); }

struct DepthSetup {
  Plane z;     // Σ E_k·z_k·(2^depth_bits − 1)
  i128 den = 0;  // 2A · 2^z_frac_bits (> 0)
  // Codes are clamped to [0, max_code]: on the snapped triangle z is a convex combination and
  // the clamp never acts; attribute planes extrapolate slightly at covered pixel centres outside
  // the attribute triangle (model/stages/attr.hpp).
  i128 max_code = ((i128)1 << 32) - 1;
};
// Contract: exact; needs z_k ≤ 2^z_frac_bits (setup rejects larger as RejectedRange).
DepthSetup depth_setup(const Config& cfg, const SetupTriangle& tri, const TriSetup& t);

// Field widths of the planes (the bounds validate() checks against i128):
// Σ E_k·Q_k over three vertices with |E_k| < 2^(edge_value_bits−1), |Q_k| < 2^(qbits−1), plus 2
// bits for the three-term sum.
// With separate attribute positions the planes use the attribute edge functions
// (2·attr_coord_bits + 2 bits) and the depth vertex values z_k·(2^db − 1) at z_frac_bits − db
// fraction bits (z_frac_bits + 1 bits; model/stages/attr.hpp).
inline bool attr_planes(const RasterConfig& r) { return r.attr_subpixel_bits > r.subpixel_bits; }
inline int plane_edge_bits(const RasterConfig& r) {
  return attr_planes(r) ? 2 * r.attr_coord_bits + 2 : edge_value_bits(r);
}
inline int interp_plane_bits(const RasterConfig& r) { return plane_edge_bits(r) + r.interp_block_bits + 1 + 2; }
inline int depth_plane_bits(const RasterConfig& r) {
  return plane_edge_bits(r) + r.z_frac_bits + 1 + (attr_planes(r) ? 0 : r.depth_bits()) + 2;
}
// 2A·2^z_frac_bits (attribute planes: 2A'·2^(z_frac_bits − db)): unsigned, 2A < 2^(edge bits − 1).
inline int depth_den_bits(const RasterConfig& r) {
  return plane_edge_bits(r) - 1 + r.z_frac_bits - (attr_planes(r) ? r.depth_bits() : 0);
}

template <class V>
void visit_plane(V& v, const std::string& name, Plane& p, int bits, const RasterConfig& r) {
  v(name + "_c", p.c, bits, true);
  v(name + "_dx", p.dx, bits, true);
  v(name + "_dy", p.dy, bits, true);
  if (attr_planes(r)) {  // anchored attribute planes: c is the value at pixel (i0, j0)
    v(name + "_i0", p.i0, r.window_int_bits, true);
    v(name + "_j0", p.j0, r.window_int_bits, true);
  }
}

// ---- the stage ------------------------------------------------------------------------------

// Stage 5 output: everything the later stages need of one triangle — the edge equations and
// candidate rectangle (traversal), the z plane (depth), the 1/w and v/w planes (interpolators).
// The planes are built from the same snapped positions as the edges today; they are separate
// members so that they can get their own (higher-precision) positions without touching coverage.
struct TriangleEquations {
  uint32_t prim = 0;
  TriSetup edges;
  DepthSetup depth;
  InterpSetup interp;  // interp.n = 0 when the chain computes no varyings
  // Not a field of the record (not visited, no hardware bits): SetupStage numbers each triangle
  // it emits, unique in the process (0: built by hand), so that a consumer keeping per-triangle
  // state (FusedSpan's span-start cursor, model/stages/interp_span.hpp) tells a rewritten
  // record from the triangle it began.
  uint64_t serial = 0;

  template <class V>
  void visit(V& v, const RecordShape& s) {
    const RasterConfig& r = s.cfg.raster;
    v("prim", prim, kPrimIdBits, false);
    for (int k = 0; k < 3; ++k) {
      const std::string p = field_prefix("e", k);
      v(p + "a", edges.e[k].a, edge_coef_bits(r), true);
      v(p + "b", edges.e[k].b, edge_coef_bits(r), true);
      v(p + "c", edges.e[k].c, edge_value_bits(r), true);
      v(p + "bias", edges.e[k].bias, 1, true);  // 0 or −1
    }
    v("area2", edges.area2, edge_value_bits(r), true);
    v("front", edges.front, 1, false);
    v("x0", edges.x0, r.window_int_bits, true);
    v("x1", edges.x1, r.window_int_bits, true);
    v("y0", edges.y0, r.window_int_bits, true);
    v("y1", edges.y1, r.window_int_bits, true);
    visit_plane(v, "z", depth.z, depth_plane_bits(r), r);
    v("z_den", depth.den, depth_den_bits(r), false);
    visit_plane(v, "den", interp.den, interp_plane_bits(r), r);
    v("den_exp", interp.den_exp, fx_exp_field_bits(s.cfg), true);
    for (int m = 0; m < s.num_varyings; ++m) {
      const std::string p = "num" + std::to_string(m);
      visit_plane(v, p, interp.num[m], interp_plane_bits(r), r);
      v(p + "_exp", interp.num_exp[m], fx_exp_field_bits(s.cfg), true);
    }
  }
  // The members that are configuration constants, not wires (model/vectors/record_vectors.hpp).
  void restore(const RecordShape& s) {
    edges.g = grid_bits(s.cfg.raster);
    depth.max_code = depth_max_code(s.cfg.raster);
    interp.n = s.num_varyings;
  }
};

// Contract (model/stages/attr.cpp): the depth and varying planes of `eq` from the attribute
// positions of `tri` (eq.edges set up). false when the attribute triangle has zero area (the
// caller then uses the coverage triangle's planes).
bool attr_plane_setup(const Config& cfg, const DrawState& st, const SetupTriangle& tri, bool varyings,
                      TriangleEquations& eq);

// Register stages of rtl/fxr_setup.sv. Coverage (fxr_setup_edges): coordinate products | edge
// constants, 2A, candidate rectangle | outcome, winding, top-left bias. The planes' edge
// functions (fxr_setup_attr): fraction bits kept | positions, relative | coefficients, 2A', anchor
// | orientation, edge values at the anchor. Planes (fxr_setup_plane): products | sums.
inline constexpr int kSetupEdgeStages = 3;
inline constexpr int kSetupAttrStages = 4;
inline constexpr int kSetupPlaneStages = 2;

// The first serial of a SetupStage's block of 2^40 (TriangleEquations::serial), minus one.
inline uint64_t setup_serial_block() {
  static std::atomic<uint64_t> next{0};
  return (next.fetch_add(1, std::memory_order_relaxed) + 1) << 40;
}

class SetupStage {
 public:
  static constexpr const char* kName = "setup";
  using In = SetupTriangle;
  using Out = TriangleEquations;

  // with_varyings false: the 1/w and v/w planes are not built (nothing downstream divides).
  SetupStage(const Config& cfg, const DrawState& st, bool with_varyings = true)
      : cfg_(cfg), st_(st), varyings_(with_varyings && st.num_varyings > 0), rect_(setup_rect(cfg, st)) {}

  // 1 → 0..1: the triangle's equations, or why it is not drawn.
  template <class Emit>
  SetupOutcome step(const In& in, Emit&& emit) {
    const SetupOutcome o = setup_triangle(cfg_, st_, rect_, in, out_.edges);
    if (o != SetupOutcome::Ok) return o;
    out_.prim = in.prim;
    out_.serial = ++serial_;
    if (!attr_planes(cfg_.raster) || !attr_plane_setup(cfg_, st_, in, varyings_, out_)) {
      out_.depth = depth_setup(cfg_, in, out_.edges);
      if (varyings_) interp_setup(cfg_, st_, in, out_.edges, out_.interp);
      else out_.interp.n = 0;
    }
    emit(static_cast<const Out&>(out_));
    return o;
  }

  // rtl/fxr_setup.sv: latency and II of the RTL; area: its products and adders.
  static StageCost cost(const Config& cfg);

 private:
  const Config& cfg_;
  const DrawState& st_;
  bool varyings_;
  PixelRect rect_;  // setup_rect(cfg_, st_): per draw
  TriangleEquations out_;
  uint64_t serial_ = setup_serial_block();  // the last serial emitted
};

}  // namespace fxr
