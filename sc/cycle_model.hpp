// sc/cycle_model.hpp — the cycle-approximate SystemC model of the raster unit (issue 12,
// docs/cycles.md). One SC_MODULE per stage wraps that stage's step() of the bit-accurate model
// (model/stages/*), so every transaction carries the model's exact values and the fragment
// stream is the model's bit for bit; stages are joined by sc_fifo links. Timing comes from one
// place: the stages' cost() and their data-dependent timing (TraverseStage::timing,
// InterpStage::span_front_clocks, DepthStage::head_clocks, divide_cost) and the knobs of
// ArchConfig (model/config/arch_config.hpp), the parameters rtl/fxr_raster_backend.sv is built
// from.
//
// This header has no SystemC in it: callers (fxraster cycles, the tests) link fxr_sc.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "model/config/arch_config.hpp"
#include "model/config/config.hpp"
#include "model/unit/io.hpp"
#include "model/unit/backend.hpp"
#include "model/unit/raster_unit.hpp"
#include "model/stages/viewport.hpp"

namespace fxr::cyc {

// The modules whose clocks are counted. Stages 1–4 (kInput … kViewport) only in run_unit_cycles.
enum Stage : int { kInput, kClip, kRecip, kViewport, kSetup, kTraverse, kInterpFront, kInterpBack, kDepth, kDivide, kNumStages };
const char* stage_name(int s);

// Clocks of one stage over the frame [first input, last output]:
//   busy     the stage works on a transaction (its own clocks, from cost() / timing(); the
//            depth stage: one clock per sample on its memory port)
//   stalled  it holds a finished result its successor does not take (blocked on the link)
//   starved  neither: waiting for input (window − busy − stalled)
//   occupied clocks with a transaction inside the stage (what the RTL's state registers show:
//            busy + stalled, and for the depth stage every clock a sample is in its queue)
struct StageClocks {
  uint64_t in = 0, out = 0;  // transactions accepted / emitted
  uint64_t busy = 0, stalled = 0, starved = 0, occupied = 0;
};

struct CycleOptions {
  bool timeline = false;     // keep every stage's busy intervals (for the occupancy plot)
  bool span_clocks = false;  // keep the clock every span is taken by the interpolators
  bool traverse_clocks = false;  // keep every triangle's [accept, ready for the next) in traversal
};

struct CycleRun {
  uint64_t first_in = 0, last_out = 0;  // clocks of the first input transfer, the last fragment out
  uint64_t clocks = 0;                  // last_out − first_in + 1 (0 when nothing came out)
  uint64_t primitives = 0;              // run_unit_cycles: input primitives
  uint64_t triangles = 0;               // setup inputs
  uint64_t drawn = 0;                   // setup outputs
  uint64_t spans = 0, samples = 0, passed = 0;
  uint64_t sim_events = 0;              // SystemC delta cycles (a measure of the model's work)
  double seconds = 0;                   // wall clock of the simulation
  std::array<StageClocks, kNumStages> stage{};
  std::array<std::vector<std::pair<uint64_t, uint64_t>>, kNumStages> busy;  // [begin, end) when timeline
  std::vector<uint64_t> span_taken;  // when span_clocks: the clock each span entered the interpolators
  std::vector<std::pair<uint64_t, uint64_t>> traverse_tri;  // when traverse_clocks: per triangle, in order

  // The stage with the most busy clocks (the one every other waits for).
  int bottleneck() const;
};

// Stages 5–9 (fxr_raster_backend) on setup's input stream, one triangle offered per clock. `f`
// must be prepared (frame_begin, the depth buffer as the draw starts); its depth buffer is
// tested and written, its statistics are not touched. Every passing fragment goes to `sink`
// (nullptr: counted only), in the model's order.
CycleRun run_backend_cycles(const Config& cfg, const ArchConfig& arch, const DrawState& st,
                            const std::vector<SetupTriangle>& tris, FrameOutput& f, FragmentSink* sink,
                            const CycleOptions& opt = {});

// The whole unit (rtl/fxr_raster_unit.sv): stages 1–4 (fxr_input, fxr_clip, fxr_recip_stage,
// fxr_viewport; the values from fxr::GeometryChain, each primitive to 0..n snapped triangles) in
// front of the back end. Prepares `f` (frame_begin).
CycleRun run_unit_cycles(const Config& cfg, const ArchConfig& arch, const DrawState& st,
                         const std::vector<ClipTriangle>& prims, FrameOutput& f, FragmentSink* sink,
                         const CycleOptions& opt = {});

// A fresh SystemC simulation context: SystemC 2.3 cannot elaborate again after sc_start, so every
// simulation in a process (each run above, the mixed simulation of tb/backend/mixed_test.cpp)
// starts with one. Modules of an earlier simulation must stay allocated (never destroyed under
// their processes).
void fresh_sc_kernel();

// The setup inputs of a draw as the model's chain produces them (stages 1–4 of every primitive).
std::vector<SetupTriangle> setup_inputs(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& prims);

}  // namespace fxr::cyc
