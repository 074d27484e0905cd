// Fuzz harness: the raster unit (run_raster_unit) on random in-range configurations, draw states
// and extreme clip-space triangles. Invariants (docs/testing.md "Fuzzing"):
//   every input primitive is accounted for (drawn + culled + rejected = in),
//   every fragment lies inside the viewport ∩ scissor, its primitive index is an input's,
//   every depth code is within the depth format, and fragment counts add up;
//   the same for 0..4 line segments drawn after the triangles (docs/lines.md): every segment
//   is accounted for in RasterStats::lines, its fragments inside viewport ∩ scissor;
//   the coverage of every small snapped triangle (bounding box ∩ draw rectangle at most
//   kSmallPixels pixel centres) equals the exact reference of tests/model/coverage_ref.hpp
//   (i128 orientation tests, the top-left rule from its D3D11 definition, culling by the sign of
//   the snapped area): every pixel of the box, covered or not;
//   a primitive with a NaN / Inf varying but finite positions is counted in
//   prims_varying_nonfinite.
// A configuration the rules reject (validate, check_attr_widths) is skipped: that path is the config
// harness's.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "model/config/config.hpp"
#include "model/config/validate.hpp"
#include "model/stages/attr.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/traverse.hpp"
#include "model/unit/geometry.hpp"
#include "model/unit/raster_unit.hpp"
#include "tests/fuzz/fuzz_common.hpp"
#include "tests/model/coverage_ref.hpp"

namespace {

using namespace fxr;

// Reads bytes from the input, zeros once it is used up (deterministic for a given input).
struct Bytes {
  const uint8_t* p;
  size_t n;
  uint32_t u32() {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | (n ? (--n, *p++) : 0u);
    return v;
  }
  uint32_t below(uint32_t k) { return k ? u32() % k : 0; }
  int in(int lo, int hi) { return lo + (int)below((uint32_t)(hi - lo + 1)); }
};

// Sets every parameter of a unit from the input, within its declared range.
struct RandomParams {
  Bytes& b;
  void integer(const char*, int& v, int lo, int hi, const char*) {
    if (b.below(4) == 0) v = b.in(lo, hi);  // mostly defaults: keeps the configurations valid
  }
  template <class E>
  void choice(const char*, E& v, std::initializer_list<const char*> names, const char*) {
    if (b.below(4) == 0) v = static_cast<E>(b.below((uint32_t)names.size()));
  }
};

// A value in [−2, 2) with 16 bits of resolution.
float moderate(Bytes& b) { return ((float)b.below(1u << 16) / (float)(1u << 14)) - 2.0f; }

// Extreme float32 values: the classes the input conversion distinguishes, plus raw bits.
float extreme(Bytes& b) {
  static const uint32_t kBits[] = {0x00000000u, 0x80000000u, 0x7f800000u, 0xff800000u, 0x7fc00000u,
                                   0x00000001u, 0x807fffffu, 0x7f7fffffu, 0xff7fffffu, 0x3f800000u,
                                   0xbf800000u, 0x33800000u, 0x4b800000u, 0x5f000000u, 0x3effffffu};
  const uint32_t kind = b.below(4);
  uint32_t bits;
  if (kind == 0) bits = kBits[b.below(sizeof kBits / sizeof kBits[0])];
  else if (kind == 1) bits = b.u32();
  else {
    const float f = moderate(b);
    std::memcpy(&bits, &f, sizeof bits);
  }
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// Pixel centres of a triangle's box (∩ the draw rectangle) up to which coverage is checked against
// the exact reference: the 48² viewports of this harness make a full-viewport box 2304 centres;
// the bound keeps the check to about a third of the harness's time.
constexpr int64_t kSmallPixels = 1024;

int64_t floor_shift(int64_t v, int s) { return v >= 0 ? v >> s : -((-v + ((int64_t)1 << s) - 1) >> s); }

// Coverage of one snapped triangle (stages 5–6 of the model: setup + traversal) against the exact
// reference, at every pixel centre of its box ∩ draw_rect. Returns whether it was small enough.
bool check_coverage(const Config& cfg, const DrawState& st, const SetupTriangle& t) {
  const int s = cfg.raster.subpixel_bits;
  const PixelRect r = draw_rect(st);
  int64_t bx0 = t.v[0].x, bx1 = t.v[0].x, by0 = t.v[0].y, by1 = t.v[0].y;
  for (const auto& v : t.v) bx0 = std::min(bx0, v.x), bx1 = std::max(bx1, v.x), by0 = std::min(by0, v.y), by1 = std::max(by1, v.y);
  // Pixels whose centre can lie in the box: floor(min) − 1 … floor(max), clamped to the draw rectangle.
  const int64_t x0 = std::max<int64_t>(r.x0, floor_shift(bx0, s) - 1), x1 = std::min<int64_t>(r.x1, floor_shift(bx1, s));
  const int64_t y0 = std::max<int64_t>(r.y0, floor_shift(by0, s) - 1), y1 = std::min<int64_t>(r.y1, floor_shift(by1, s));
  if (x1 < x0 || y1 < y0) return true;
  const int64_t W = x1 - x0 + 1, H = y1 - y0 + 1;
  if (W * H > kSmallPixels) return false;
  TriSetup ts;
  const SetupOutcome o = setup_triangle(cfg, st, t, ts);
  if (o == SetupOutcome::RejectedRange) return true;  // documented discard (counted by the unit)
  std::vector<uint8_t> model((size_t)(W * H), 0);
  if (o == SetupOutcome::Ok)
    traverse(ts, [&](int j, int xb, int xe) {
      for (int i = xb; i <= xe; ++i) {
        fuzz::check(i >= x0 && i <= x1 && j >= y0 && j <= y1, "covered pixel outside the triangle's box");
        uint8_t& m = model[(size_t)((j - y0) * W + (i - x0))];
        fuzz::check(m == 0, "pixel covered twice by one triangle");
        m = 1;
      }
    });
  const covref::P v[3] = {{t.v[0].x, t.v[0].y}, {t.v[1].x, t.v[1].y}, {t.v[2].x, t.v[2].y}};
  const covref::i128 area = covref::orient(v[0].x, v[0].y, v[1].x, v[1].y, v[2].x, v[2].y);
  const bool front = (area > 0) == st.front_ccw;
  const bool culled = (st.cull == CullMode::Back && !front) || (st.cull == CullMode::Front && front);
  for (int64_t j = y0; j <= y1; ++j)
    for (int64_t i = x0; i <= x1; ++i) {
      const bool ref = !culled && covref::ref_covered(v, s, (int)i, (int)j);
      fuzz::check(ref == (model[(size_t)((j - y0) * W + (i - x0))] != 0),
                  "coverage differs from the exact reference at pixel (" + std::to_string(i) + ", " +
                      std::to_string(j) + ")");
    }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Bytes b{data, size};
  Config cfg;
  RandomParams rp{b};
  cfg.for_each_unit([&](const char*, auto& u) { u.visit(rp); });
  derive_widths(cfg);
  try {
    validate(cfg, "fuzz");
    check_attr_widths(cfg);  // frame_begin's other configuration rule (model/stages/attr.hpp)
  } catch (const ConfigError&) {
    return 0;
  }
  DrawState st;
  st.viewport_x = b.in(-8, 8), st.viewport_y = b.in(-8, 8);
  st.viewport_w = b.in(1, 48), st.viewport_h = b.in(1, 48);
  if (b.below(2)) st.scissor_x = b.in(-8, 40), st.scissor_y = b.in(-8, 40), st.scissor_w = b.in(0, 48), st.scissor_h = b.in(0, 48);
  st.num_varyings = b.in(0, 3);
  st.front_ccw = b.below(2);
  st.cull = static_cast<CullMode>(b.below(3));
  st.depth_func = static_cast<DepthFunc>(b.below(8));
  st.depth_test = b.below(2), st.depth_write = b.below(2);
  st.interp = static_cast<InterpMode>(b.below(2));
  std::vector<ClipTriangle> tris((size_t)b.in(1, 6));
  for (auto& t : tris) {
    // Half the triangles are small and on screen (NDC centre in [−1, 1]², extent 2^−6 … 1, w in
    // (0, 4], z in [0, w]), so that the coverage check sees covered pixels; the others have
    // extreme values in every component.
    const bool tame = b.below(2);
    const float cx = moderate(b) * 0.5f, cy = moderate(b) * 0.5f, ext = std::ldexp(1.0f, -b.in(0, 6));
    for (auto& v : t.v) {
      if (tame) {
        const float w = std::fabs(moderate(b)) * 2.0f + 1.0f / 1024;
        v.pos[0] = (cx + ext * moderate(b) * 0.5f) * w;
        v.pos[1] = (cy + ext * moderate(b) * 0.5f) * w;
        v.pos[2] = std::fabs(moderate(b)) * 0.5f * w;
        v.pos[3] = w;
      } else {
        for (float& p : v.pos) p = extreme(b);
        if (b.below(2)) v.pos[3] = std::fabs(v.pos[3]);  // mostly in front of the eye
      }
      for (int k = 0; k < st.num_varyings; ++k) v.var[k] = extreme(b);
    }
  }
  std::vector<ClipLine> lines((size_t)b.in(0, 4));  // 0 once the input is used up
  for (auto& l : lines)
    for (auto& v : l.v) {
      for (float& p : v.pos) p = extreme(b);
      if (b.below(2)) v.pos[3] = std::fabs(v.pos[3]);
      for (int k = 0; k < st.num_varyings; ++k) v.var[k] = extreme(b);
    }
  FrameOutput f;
  if (!fuzz::run_expecting_config_errors([&] { f = run_raster_unit(cfg, st, tris, st, lines); })) return 0;
  fuzz::check(f.stats.lines.in == lines.size(), "lines.in differs from the input count");
  fuzz::check(f.stats.lines.accounted() == f.stats.lines.in, "a line segment is not accounted for");
  const RasterStats& s = f.stats;
  fuzz::check(s.prims_in == tris.size(), "prims_in differs from the input count");
  const uint64_t accounted = s.prims_drawn + s.prims_culled_outside + s.prims_culled_zero_area +
                             s.prims_culled_backface + s.prims_culled_no_samples + s.prims_rejected_nan +
                             s.prims_rejected_inf + s.prims_rejected_range;
  fuzz::check(accounted == s.prims_in, "a primitive is not accounted for");
  fuzz::check(s.fragments_depth_pass + s.fragments_depth_fail == s.fragments_generated, "fragment counts differ");
  const PixelRect r = draw_rect(st);
  const uint64_t max_code = (1ull << cfg.raster.depth_bits()) - 1;
  for (const Fragment& fr : f.fragments) {
    fuzz::check(fr.x >= r.x0 && fr.x <= r.x1 && fr.y >= r.y0 && fr.y <= r.y1, "fragment outside viewport ∩ scissor");
    fuzz::check(fr.depth <= max_code, "depth code beyond the format");
    fuzz::check(fr.prim < tris.size() + lines.size(), "fragment of no input primitive");
  }
  fuzz::check(f.fragments.size() <= s.fragments_depth_pass, "more fragments kept than passed the depth test");
  // Non-finite varyings: counted once per primitive with finite positions, never rejected.
  uint64_t nonfinite = 0;
  for (const auto& t : tris) {
    bool pos = true, var = false;
    for (const auto& v : t.v) {
      for (float p : v.pos) pos &= std::isfinite(p);
      for (int k = 0; k < st.num_varyings; ++k) var |= !std::isfinite(v.var[k]);
    }
    nonfinite += pos && var;
  }
  fuzz::check(s.prims_varying_nonfinite == nonfinite, "prims_varying_nonfinite differs from the input's count");
  // Coverage of the small snapped triangles against the exact reference.
  for (size_t p = 0; p < tris.size(); ++p) {
    std::vector<SetupTriangle> pieces;
    RasterStats gs;
    geometry(cfg, st, tris[p], (uint32_t)p, pieces, gs);
    for (const SetupTriangle& t : pieces) check_coverage(cfg, st, t);
  }
  return 0;
}
