// model/unit/geometry.hpp — stages 1–4: input conversion, clipper, reciprocal unit + perspective
// divide, viewport transform + snap. From one clip-space triangle to zero or more snapped
// setup triangles.
#pragma once

#include <vector>

#include "model/config/config.hpp"
#include "model/stages/setup.hpp"
#include "model/unit/io.hpp"

namespace fxr {

// How one input primitive left the geometry stages.
enum class GeomOutcome : uint8_t {
  Emitted,        // ≥ 1 SetupTriangle appended to `out`
  CulledOutside,  // trivially rejected or clipped away entirely
  RejectedNaN,    // a NaN in a position (NaN / Inf varyings are replaced, not rejected)
  RejectedInf,    // an infinity in a position
  RejectedRange,  // finite but beyond a format's range
};

// Contract: appends the snapped triangles of `tri` to `out` (prim index stamped on each) and
// updates the geometry counters of `stats` (trivial accept, clipped, vertices created,
// triangles out, varyings non-finite). The caller counts prims_in and the final disposition. Pure function of its
// inputs: a shared edge of two input triangles is clipped identically in both. (Convenience
// entry point: it sets the stages up per call; GeometryChain in model/unit/chain.hpp sets them up
// once per frame.)
GeomOutcome geometry(const Config& cfg, const DrawState& st, const ClipTriangle& tri, uint32_t prim,
                     std::vector<SetupTriangle>& out, RasterStats& stats);

}  // namespace fxr
