// Stage 7 (interpolators). Contracts in model/stages/interp.hpp; the planes are set up in
// model/stages/setup.cpp.
#include <string>

#include "model/stages/interp.hpp"

namespace fxr {

StageCost InterpStage::cost(const Config& cfg) {
  const RasterConfig& r = cfg.raster;
  StageCost c;
  c.latency = 1;  // one accumulator step per clock
  c.ii = 1;
  // Per varying and for 1/w: an interp_plane_bits accumulator; z: quotient + remainder DDA.
  c.adder_bits = (int64_t)(kMaxVaryings + 1) * interp_plane_bits(r) + 2 * depth_plane_bits(r);
  c.ff_bits = record_bits<PlaneSample>(cfg, kMaxVaryings);
  return c;
}

}  // namespace fxr
