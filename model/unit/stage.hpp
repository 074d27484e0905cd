// model/unit/stage.hpp — what every stage of the raster unit has in common
// (docs/architecture.md has the stage table, docs/pipeline.md the stages).
//
// The stage interface. A stage is a header in model/stages/ declaring a class `<Name>Stage` with
//   static constexpr const char* kName;      the one name of the stage: model, RTL, tb, vectors
//   using In = <record>; using Out = <record>;
//   <Name>Stage(const Config&, const DrawState&[, state])   reads only its part of the
//                                             configuration (kept in members, computed once)
//   template <class Emit> Outcome step(const In&, Emit&& emit)
//                                             calls emit(const Out&) 0..n times, in order, and
//                                             returns why it emitted nothing (an enum whose
//                                             first value means "emitted")
//   static StageCost cost(const Config&);     the hardware cost of the stage (below)
// A stage that works inside one triangle after setup (interpolators) also takes the triangle's
// setup record as a per-triangle context: step(const Context&, const In&, emit) — what the
// hardware latches once per triangle. A stage with state (the depth buffer) gets it by
// reference at construction; nothing else is remembered between steps: a step is a pure
// function of (configuration, draw state, context, input[, state]). Out records may be scratch
// members of the stage object: emit's argument is valid only during the call.
//
// Records. Every record passed between stages lists its fields once in
//   template <class V> void visit(V& v, const RecordShape& s)
// calling v(name, field, bits, is_signed) per scalar field (bool, integers, i128), with the
// width derived from the configuration (s.cfg) and the number of active varyings (helpers in
// model/unit/record.hpp). Vector field layouts (model/vectors/scene_dump.hpp) are generated
// from it, never written by hand.
//
// The unit (model/unit/chain.hpp) chains the steps and calls a tap at every boundary.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace fxr {

// Hardware cost of one stage at one configuration: the formulas the RTL is built from, so the
// cycle model, the sweeps and the planner read cycles and area from one place.
struct StageCost {
  int latency = 0;          // clocks from the input handshake to the first output valid
  int ii = 1;               // initiation interval: clocks between accepted inputs (1 = pipelined)
  int64_t table_bits = 0;   // ROM bits
  std::vector<std::pair<int, int>> multipliers;  // operand widths (a, b) of every multiplier
  int64_t mult_bits = 0;    // Σ a·b over the multipliers (partial-product bits)
  int64_t adder_bits = 0;   // adder / subtractor / comparator bits, summed
  int64_t ff_bits = 0;      // pipeline register bits (estimate of the RTL's registers)
  // table_bits + mult_bits + adder_bits: a ranking proxy only (Yosys gives real LUT counts).
  int64_t area_proxy() const { return table_bits + mult_bits + adder_bits; }

  void add_mult(int a, int b) {
    multipliers.emplace_back(a, b);
    mult_bits += (int64_t)a * b;
  }
};

}  // namespace fxr
