// Stages 5–10 on one snapped triangle: the FragmentChain of model/unit/chain.hpp (contracts in
// model/unit/backend.hpp and the stage headers).
#include "model/unit/backend.hpp"

#include "model/stages/attr.hpp"

#include <string>

#include "model/config/validate.hpp"
#include "model/stages/depth.hpp"
#include "model/stages/interp.hpp"
#include "model/unit/chain.hpp"

namespace fxr {

void frame_check(const Config& cfg, const DrawState& st) {
  validate(cfg, "configuration");  // every range and cross-field rule (model/config/validate.hpp)
  check_attr_widths(cfg);           // attribute-plane widths (model/stages/attr.hpp)
  if (st.num_varyings < 0 || st.num_varyings > kMaxVaryings)
    throw ConfigError("draw state: field 'num_varyings' = " + std::to_string(st.num_varyings) +
                      " is outside 0.." + std::to_string(kMaxVaryings));
  if (st.viewport_w < 1 || st.viewport_h < 1)
    throw ConfigError("draw state: viewport " + std::to_string(st.viewport_w) + "x" +
                      std::to_string(st.viewport_h) + " is empty");
}

void frame_begin(const Config& cfg, const DrawState& st, FrameOutput& f) {
  frame_check(cfg, st);
  f.width = st.viewport_w;
  f.height = st.viewport_h;
  f.fragments.shape(st.num_varyings);
  f.depth.assign((size_t)f.width * f.height, depth_max_code(cfg.raster));
  f.stats = RasterStats{};
}

SetupOutcome raster_triangle(const Config& cfg, const DrawState& st, const SetupTriangle& tri, FrameOutput& f,
                             bool keep_fragments) {
  KeepFragments keep(f.fragments);
  return raster_triangle_to(cfg, st, tri, f, keep_fragments ? &keep : nullptr);
}

SetupOutcome raster_triangle_to(const Config& cfg, const DrawState& st, const SetupTriangle& tri, FrameOutput& f,
                                FragmentSink* sink) {
  NoTaps taps;
  FragmentChain<NoTaps> chain(cfg, st, f, sink, taps);
  return chain.run(tri);
}

}  // namespace fxr
