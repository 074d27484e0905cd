// Stages 1–4 of the raster unit: input conversion, clipper, reciprocal + perspective divide,
// viewport + snap, as the GeometryChain of model/unit/chain.hpp. Contract in
// model/unit/geometry.hpp; formats and derivations in docs/pipeline.md.
#include "model/unit/geometry.hpp"

#include "model/unit/chain.hpp"

namespace fxr {

GeomOutcome geometry(const Config& cfg, const DrawState& st, const ClipTriangle& tri, uint32_t prim,
                     std::vector<SetupTriangle>& out, RasterStats& stats) {
  NoTaps taps;
  GeometryChain<NoTaps> chain(cfg, st, taps);
  InputTriangle in;
  in.prim = prim;
  in.tri = tri;
  return chain.run(in, out, stats);
}

}  // namespace fxr
