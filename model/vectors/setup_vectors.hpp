// model/vectors/setup_vectors.hpp — golden vectors of stage 5, triangle setup
// (model/stages/setup.hpp ↔ rtl/fxr_setup.sv ↔ tb/setup_test.cpp ↔ vectors/setup/).
//
// Fields, generated from the records' visit() (never written by hand):
//   inputs   SetupTriangle::visit (prim, per vertex x, y, ax, ay, z, rw, vw0 … vw{n−1}), then the
//            draw state the stage reads (visit_setup_state: viewport, scissor, cull, front_ccw,
//            interp);
//   outputs  outcome (SetupOutcome, kSetupOutcomeBits), then TriangleEquations::visit (edges
//            e0..e2 a, b, c, bias, area2, front, the candidate rectangle x0..y1, the depth plane,
//            z_den, the 1/w plane, den_exp, the v/w planes and their exponents). An output whose
//            name is also an input's gets the prefix "out_" (prim → out_prim).
// A triangle that is not drawn (outcome ≠ ok) has every other output field 0.
// The number of varyings is fixed per vector unit (kSetupVecVaryings): the RTL's port list.
#pragma once

#include <memory>

#include "model/config/config.hpp"
#include "model/vectors/vectors.hpp"

namespace fxr {

// Varyings of the setup vector unit (and of rtl/fxr_setup.sv's ports): two, as a texture
// coordinate pair; more varyings are more instances of the same plane datapath.
inline constexpr int kSetupVecVaryings = 2;
// SetupOutcome (5 values) as an unsigned field.
inline constexpr int kSetupOutcomeBits = 3;

std::unique_ptr<VectorModel> make_setup_vectors(const Config& cfg);

}  // namespace fxr
