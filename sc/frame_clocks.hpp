// sc/frame_clocks.hpp — clocks per frame of the cycle model (sc/cycle_model.hpp) as one number,
// for callers that run many configurations in one process (`fxraster plan --cost cycles`,
// analysis/plan.hpp): each run happens in a forked child process, so the simulation contexts,
// modules and triangle copies that run_unit_cycles keeps allocated (SystemC 2.3 cannot tear a
// simulation down; about 100 MB per run of the default scene, docs/reports.md "Planner") end
// with the child, and calls from several threads at once are safe (each child has its own
// SystemC kernel). The result is run_unit_cycles(...).clocks exactly.
#pragma once

#include <cstdint>
#include <vector>

#include "model/config/arch_config.hpp"
#include "model/config/config.hpp"
#include "model/unit/io.hpp"

namespace fxr::cyc {

// Contract: run_unit_cycles(cfg, arch, st, prims, f, nullptr).clocks for a fresh FrameOutput,
// computed in a child process; std::runtime_error when the child fails (its message included).
uint64_t unit_frame_clocks(const Config& cfg, const ArchConfig& arch, const DrawState& st,
                           const std::vector<ClipTriangle>& prims);

}  // namespace fxr::cyc
