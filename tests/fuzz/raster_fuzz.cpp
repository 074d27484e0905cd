// Fuzz harness: the raster unit (run_raster_unit) on random in-range configurations, draw states
// and extreme clip-space triangles. Invariants (docs/testing.md "Fuzzing"):
//   every input primitive is accounted for (drawn + culled + rejected = in),
//   every fragment lies inside the viewport ∩ scissor, its primitive index is an input's,
//   every depth code is within the depth format, and fragment counts add up;
//   and the same for 0..4 line segments drawn after the triangles (docs/lines.md): every segment
//   is accounted for in RasterStats::lines, its fragments inside viewport ∩ scissor.
// A configuration the rules reject (validate, check_attr_widths) is skipped: that path is the config
// harness's.
#include <cmath>
#include <cstring>
#include <vector>

#include "model/config/config.hpp"
#include "model/config/validate.hpp"
#include "model/stages/attr.hpp"
#include "model/stages/setup.hpp"
#include "model/unit/raster_unit.hpp"
#include "tests/fuzz/fuzz_common.hpp"

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
    // A moderate value in [−2, 2] with 16 bits of resolution (most triangles land on screen).
    const float f = ((float)b.below(1u << 16) / (float)(1u << 14)) - 2.0f;
    std::memcpy(&bits, &f, sizeof bits);
  }
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
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
  for (auto& t : tris)
    for (auto& v : t.v) {
      for (float& p : v.pos) p = extreme(b);
      if (b.below(2)) v.pos[3] = std::fabs(v.pos[3]);  // mostly in front of the eye
      for (int k = 0; k < st.num_varyings; ++k) v.var[k] = extreme(b);
    }
  std::vector<ClipLine> lines((size_t)b.in(0, 4));  // 0 once the input is used up: old inputs unchanged
  for (auto& l : lines)
    for (auto& v : l.v) {
      for (float& p : v.pos) p = extreme(b);
      if (b.below(2)) v.pos[3] = std::fabs(v.pos[3]);
      for (int k = 0; k < st.num_varyings; ++k) v.var[k] = extreme(b);
    }
  FrameOutput f;
  fuzz::run_expecting_config_errors([&] { f = run_raster_unit(cfg, st, tris, st, lines); });
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
  return 0;
}
