// model/unit/stage.hpp — what every stage of the raster unit has in common
// (docs/architecture.md has the stage table).
//
// A stage is a header in model/stages/ with: the part of the configuration it reads, its input
// and output records (each listing its fields once in visit()), a step function that emits
// 0..n output records per input record, and cost(config) returning the one StageCost shape
// below. The unit (model/unit/) chains the steps.
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
};

}  // namespace fxr
