// model/unit/io.hpp — what enters and leaves the raster unit.
//
// Input: primitives as a vertex stage emits them (float32 clip-space positions and
// varyings), plus the draw state. Output: fragments with integer codes, and statistics that
// account for every input primitive. Internal stage records live in the stage headers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/arith/fxfloat.hpp"
#include "model/unit/record.hpp"

namespace fxr {

// Upper bound on varyings per vertex (0 … at least 16: docs/references.md#spec-raster-unit).
inline constexpr int kMaxVaryings = 16;
// The number of varyings of the generated record package when none is given (`fxraster layout
// --emit-records-sv`, build/gen/fxr_rec_pkg.sv): the default scene's and scenes/transactions.json's.
// The testbenches of record-port units are built for it (fxr_rec_pkg::NumVaryings), and the RTL
// stage costs that depend on it (ViewportStage::cost) default to it.
inline constexpr int kRecordPackageVaryings = 2;

// One vertex as the vertex stage emits it: raw float32 values (bit patterns are kept, so a
// user can feed exactly what their vertex stage produced, NaN payloads included).
struct ClipVertex {
  float pos[4] = {0, 0, 0, 1};      // x_c, y_c, z_c, w_c
  float var[kMaxVaryings] = {};     // varyings v_0 … v_{N−1}
};

struct ClipTriangle {
  ClipVertex v[3];
};

// A line segment (GL_LINES: independent pairs of vertices): v[0] is the first vertex (p_a of
// the diamond-exit rule). docs/lines.md.
struct ClipLine {
  ClipVertex v[2];
};

enum class CullMode : uint8_t { None, Back, Front };
enum class DepthFunc : uint8_t { Never, Less, Equal, LessEqual, Greater, NotEqual, GreaterEqual, Always };

// Contract: the depth comparison `incoming func stored` (GL / D3D semantics) on any ordered
// type: the model's unorm codes, the double reference's and the float rasterizer's depths. One
// table for all: it is the draw state's meaning, not arithmetic the references must check.
template <class T>
inline bool depth_compare(DepthFunc f, T incoming, T stored) {
  switch (f) {
    case DepthFunc::Never: return false;
    case DepthFunc::Less: return incoming < stored;
    case DepthFunc::Equal: return incoming == stored;
    case DepthFunc::LessEqual: return incoming <= stored;
    case DepthFunc::Greater: return incoming > stored;
    case DepthFunc::NotEqual: return incoming != stored;
    case DepthFunc::GreaterEqual: return incoming >= stored;
    case DepthFunc::Always: return true;
  }
  return false;
}
enum class InterpMode : uint8_t { Perspective, Affine };  // Affine: the wrong image of docs/references.md#seed-000-wrong-image

// The fields of one vertex as the vertex stage emits it (float32 bit patterns): <pre>x, y, z, w
// and <pre>var<k> for the active varyings. InputTriangle and InputLine list their vertices so.
template <class V>
void visit_input_vertex(V& v, const std::string& pre, ClipVertex& x, const RecordShape& s) {
  static const char* const kPos[4] = {"x", "y", "z", "w"};
  for (int c = 0; c < 4; ++c) v(pre + kPos[c], x.pos[c], kF32Bits, false);
  for (int k = 0; k < s.num_varyings; ++k) v(pre + "var" + std::to_string(k), x.var[k], kF32Bits, false);
}

// Draw state: everything besides the primitives that the unit needs. Window coordinates have
// y up (row 0 at the bottom), pixel centres at (x + ½, y + ½).
// Bits of a field holding the values 0 … n − 1 (enum choices) or 0 … n (counts: n + 1 values).
constexpr int bits_for_values(int n) {
  int b = 1;
  while ((1 << b) < n) ++b;
  return b;
}
inline constexpr int kCullModeBits = bits_for_values(3);      // CullMode: 3 choices
inline constexpr int kDepthFuncBits = bits_for_values(8);     // DepthFunc: 8 choices
inline constexpr int kInterpModeBits = bits_for_values(2);    // InterpMode: 2 choices
inline constexpr int kNumVaryingsBits = bits_for_values(kMaxVaryings + 1);  // 0 … kMaxVaryings

struct DrawState {
  int viewport_x = 0, viewport_y = 0, viewport_w = 256, viewport_h = 256;
  int scissor_x = 0, scissor_y = 0, scissor_w = -1, scissor_h = -1;  // −1: same as the viewport
  int num_varyings = 0;
  bool front_ccw = true;  // counter-clockwise (in y-up window space) is front-facing
  CullMode cull = CullMode::None;
  DepthFunc depth_func = DepthFunc::Less;
  bool depth_test = true;
  bool depth_write = true;
  InterpMode interp = InterpMode::Perspective;

  // The draw state as the unit's register block (a record, model/unit/stage.hpp). Origins are
  // signed window_int_bits pixel indices; sizes window_int_bits + 1 bits signed (a size may
  // span the whole signed range, and the scissor's −1 means "the viewport").
  template <class V>
  void visit_rects(V& v, const RecordShape& s) {
    const int b = s.cfg.raster.window_int_bits;
    v("viewport_x", viewport_x, b, true);
    v("viewport_y", viewport_y, b, true);
    v("viewport_w", viewport_w, b + 1, true);
    v("viewport_h", viewport_h, b + 1, true);
    v("scissor_x", scissor_x, b, true);
    v("scissor_y", scissor_y, b, true);
    v("scissor_w", scissor_w, b + 1, true);
    v("scissor_h", scissor_h, b + 1, true);
  }
  template <class V>
  void visit(V& v, const RecordShape& s) {
    visit_rects(v, s);
    v("num_varyings", num_varyings, kNumVaryingsBits, false);
    v("front_ccw", front_ccw, 1, false);
    v("cull", cull, kCullModeBits, false);
    v("depth_func", depth_func, kDepthFuncBits, false);
    v("depth_test", depth_test, 1, false);
    v("depth_write", depth_write, 1, false);
    v("interp", interp, kInterpModeBits, false);
  }
};

}  // namespace fxr

namespace fxr {

// One fragment leaving the unit. depth is the D16 / D24 unorm code; var[k] is the
// perspective-correct varying as a normalised FxFloat (raster.varying_out_sig_bits).
// The fields every per-pixel record starts with. Widths: pixel indices are signed
// raster.window_int_bits, depth codes raster.depth_bits().
template <class V>
void visit_pixel_fields(V& v, const RecordShape& s, uint32_t& prim, int32_t& x, int32_t& y, uint32_t& depth) {
  const RasterConfig& r = s.cfg.raster;
  v("prim", prim, kPrimIdBits, false);
  v("x", x, r.window_int_bits, true);
  v("y", y, r.window_int_bits, true);
  v("depth", depth, r.depth_bits(), false);
}

struct Fragment {
  int32_t x = 0, y = 0;  // pixel (column, row), row 0 at the bottom
  uint32_t depth = 0;
  uint32_t prim = 0;
  FxFloat var[kMaxVaryings];

  template <class V>
  void visit(V& v, const RecordShape& s) {
    const RasterConfig& r = s.cfg.raster;
    visit_pixel_fields(v, s, prim, x, y, depth);
    for (int k = 0; k < s.num_varyings; ++k) visit_fx(v, "var" + std::to_string(k), var[k], r.varying_out_sig_bits, s);
  }
};

// Line segments (docs/lines.md, "The line path"): every input segment ends in exactly one of
// drawn, culled or rejected (in == drawn + culled + rejected is asserted by tests). Kept apart
// from the triangle counters so that a draw without lines reports exactly what it did before.
struct LineStats {
  uint64_t in = 0;
  uint64_t trivial_accept = 0;   // no clipping needed
  uint64_t clipped = 0;          // went through the segment clipper (then drawn or culled)
  uint64_t clip_vertices_created = 0;
  uint64_t drawn = 0;            // at least one pixel inside viewport ∩ scissor
  uint64_t culled_outside = 0;   // trivially rejected or clipped away entirely
  uint64_t culled_no_pixels = 0; // snapped segment covers no pixel of viewport ∩ scissor (zero length included)
  uint64_t rejected_nan = 0;     // a NaN in a position
  uint64_t rejected_inf = 0;     // an infinity in a position
  uint64_t rejected_range = 0;   // finite but beyond a format's range (documented)
  uint64_t fragments_generated = 0;  // covered pixels inside viewport ∩ scissor (also counted in RasterStats)
  uint64_t varying_nonfinite = 0;  // NaN / Inf varyings replaced (docs/pipeline.md stage 1); not a disposition

  template <class V>
  void visit(V& v) {
#define FXR_STAT(n) v(#n, n)
    FXR_STAT(in); FXR_STAT(trivial_accept); FXR_STAT(clipped); FXR_STAT(clip_vertices_created);
    FXR_STAT(drawn); FXR_STAT(culled_outside); FXR_STAT(culled_no_pixels); FXR_STAT(rejected_nan);
    FXR_STAT(rejected_inf); FXR_STAT(rejected_range); FXR_STAT(fragments_generated);
    FXR_STAT(varying_nonfinite);
#undef FXR_STAT
  }
  uint64_t accounted() const {
    return drawn + culled_outside + culled_no_pixels + rejected_nan + rejected_inf + rejected_range;
  }
};

// Every input primitive ends in exactly one of: drawn, culled_* or rejected_*
// (prims_in == prims_drawn + Σ culled + Σ rejected is asserted by tests).
// The unit's counters past the clipper (rtl/fxr_raster_unit.sv stat_geom_rejected_range_o,
// stat_tri_*_o), counted per clipped piece and per setup triangle where RasterStats'
// dispositions are per primitive (docs/pipeline.md, "Statistics: primitives, pieces, setup
// triangles"). Not in RasterStats::visit(): the statistics JSON stays as it was.
struct TriStats {
  uint64_t geom_rejected_range = 0;  // primitives the clipper rejects for range (RejectedViewport,
                                     // RejectedOverflow) + clipped pieces dropped by stage 3 (a
                                     // reciprocal error) or stage 4 (a code out of range)
  uint64_t in = 0;                   // setup triangles (stage 5's inputs)
  uint64_t drawn = 0, zero_area = 0, backface = 0, no_samples = 0, range = 0;  // by setup outcome
};

struct RasterStats {
  uint64_t prims_in = 0;
  uint64_t prims_trivial_accept = 0;     // no clipping needed
  uint64_t prims_clipped = 0;            // went through the clipper (then drawn or culled)
  uint64_t clip_vertices_created = 0;
  uint64_t clip_triangles_out = 0;       // triangles emitted by the clipper
  uint64_t prims_drawn = 0;              // produced at least one setup triangle that was rasterised
  uint64_t prims_culled_outside = 0;     // trivially rejected or clipped away entirely
  uint64_t prims_culled_zero_area = 0;   // zero area after snapping (all pieces)
  uint64_t prims_culled_backface = 0;
  uint64_t prims_culled_no_samples = 0;  // bounding box ∩ scissor empty
  uint64_t prims_rejected_nan = 0;       // a NaN in a position
  uint64_t prims_rejected_inf = 0;       // an infinity in a position
  uint64_t prims_rejected_range = 0;     // finite but beyond a format's range (documented)
  uint64_t prims_varying_nonfinite = 0;  // finite positions, a NaN / Inf active varying replaced
                                         // (0 / ±FLT_MAX, docs/pipeline.md stage 1); not a
                                         // disposition: the primitive also counts as one of the above
  uint64_t fragments_generated = 0;      // covered samples
  uint64_t fragments_depth_pass = 0;
  uint64_t fragments_depth_fail = 0;
  // Line segments (their own accounting; their fragments also count in fragments_* above).
  // Not in visit(): the JSON of a draw without lines stays as it was; stats_json adds "lines"
  // when lines.in > 0.
  LineStats lines;
  // Per piece and per setup triangle (triangles of UnitChain only; not in visit()).
  TriStats tris;

  template <class V>
  void visit(V& v) {
#define FXR_STAT(n) v(#n, n)
    FXR_STAT(prims_in); FXR_STAT(prims_trivial_accept); FXR_STAT(prims_clipped);
    FXR_STAT(clip_vertices_created); FXR_STAT(clip_triangles_out); FXR_STAT(prims_drawn);
    FXR_STAT(prims_culled_outside); FXR_STAT(prims_culled_zero_area); FXR_STAT(prims_culled_backface);
    FXR_STAT(prims_culled_no_samples); FXR_STAT(prims_rejected_nan); FXR_STAT(prims_rejected_inf);
    FXR_STAT(prims_rejected_range); FXR_STAT(prims_varying_nonfinite); FXR_STAT(fragments_generated); FXR_STAT(fragments_depth_pass);
    FXR_STAT(fragments_depth_fail);
#undef FXR_STAT
  }
};

}  // namespace fxr
