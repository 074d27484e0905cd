// Stages 5–10 on one snapped triangle (contracts in model/unit/backend.hpp and the stage headers).
#include "model/unit/backend.hpp"

#include <string>

#include "model/config/validate.hpp"
#include "model/stages/depth.hpp"
#include "model/stages/interp.hpp"
#include "model/stages/traverse.hpp"

namespace fxr {

void frame_begin(const Config& cfg, const DrawState& st, FrameOutput& f) {
  validate(cfg, "configuration");  // every range and cross-field rule (model/config/validate.hpp)
  if (st.num_varyings < 0 || st.num_varyings > kMaxVaryings)
    throw ConfigError("draw state: field 'num_varyings' = " + std::to_string(st.num_varyings) +
                      " is outside 0.." + std::to_string(kMaxVaryings));
  if (st.viewport_w < 1 || st.viewport_h < 1)
    throw ConfigError("draw state: viewport " + std::to_string(st.viewport_w) + "x" +
                      std::to_string(st.viewport_h) + " is empty");
  f.width = st.viewport_w;
  f.height = st.viewport_h;
  f.fragments.clear();
  f.depth.assign((size_t)f.width * f.height, depth_max_code(cfg.raster));
  f.stats = RasterStats{};
}

namespace {
struct VectorSink final : FragmentSink {
  std::vector<Fragment>& out;
  explicit VectorSink(std::vector<Fragment>& o) : out(o) {}
  void emit(const Fragment& f) override { out.push_back(f); }
};
}  // namespace

SetupOutcome raster_triangle(const Config& cfg, const DrawState& st, const SetupTriangle& tri, FrameOutput& f,
                             bool keep_fragments) {
  VectorSink vs(f.fragments);
  return raster_triangle_to(cfg, st, tri, f, keep_fragments ? &vs : nullptr);
}

SetupOutcome raster_triangle_to(const Config& cfg, const DrawState& st, const SetupTriangle& tri, FrameOutput& f,
                                FragmentSink* sink) {
  const bool keep_fragments = sink != nullptr;
  TriSetup t;
  const SetupOutcome o = setup_triangle(cfg, st, tri, t);
  if (o != SetupOutcome::Ok) return o;
  const DepthSetup ds = depth_setup(cfg, tri, t);
  InterpSetup is;
  const int nv = st.num_varyings;
  if (keep_fragments && nv > 0) interp_setup(cfg, st, tri, t, is);
  const DivConfig& dc = cfg.div;
  RasterStats& s = f.stats;
  uint32_t* const zbuf = f.depth.data();
  const int w = f.width;

  Fragment fr;  // reused: only the fields of this triangle's fragments are rewritten
  fr.prim = tri.prim;
  traverse(t, [&](int j, int xb, int xe) {
    s.fragments_generated += (uint64_t)(xe - xb + 1);
    DepthStepper dz(ds, xb, j);
    uint32_t* zrow = zbuf + (size_t)(j - st.viewport_y) * w - st.viewport_x;
    // Planes at the span start (direct evaluation), then stepped exactly along x.
    i128 D = 0, N[kMaxVaryings];
    if (keep_fragments && nv > 0) {
      D = is.den.at(xb, j);
      for (int m = 0; m < nv; ++m) N[m] = is.num[m].at(xb, j);
    }
    for (int i = xb; i <= xe; ++i) {
      const uint32_t code = dz.code();
      bool pass = true;
      if (st.depth_test) {
        pass = depth_compare(st.depth_func, code, zrow[i]);
        if (pass && st.depth_write) zrow[i] = code;
      }
      if (pass) {
        ++s.fragments_depth_pass;
        if (keep_fragments) {
          fr.x = i;
          fr.y = j;
          fr.depth = code;
          if (nv > 0) {
            const DenNorm dn = normalize_den(dc, D, is.den_exp);
            for (int m = 0; m < nv; ++m) fr.var[m] = divide_varying(dc, N[m], is.num_exp[m], dn);
          }
          sink->emit(fr);
        }
      } else {
        ++s.fragments_depth_fail;
      }
      dz.step_x();
      if (keep_fragments && nv > 0) {
        D += is.den.dx;
        for (int m = 0; m < nv; ++m) N[m] += is.num[m].dx;
      }
    }
  });
  return SetupOutcome::Ok;
}

}  // namespace fxr
