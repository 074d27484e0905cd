// model/unit/threads.hpp — the raster unit on several threads, bit-identical to one thread
// (docs/speed.md, "Deterministic threads": the choice and its measured figures).
//
// Geometry and setup by primitive batches, the back end by interleaved bands of rows:
//   - the primitives are taken in batches of `batch_prims`; each thread runs stages 1–5 on its
//     contiguous share of a batch (a pure function of the primitive) and counts the primitive's
//     disposition; the batch's triangle equations, in primitive order, are the threads'
//     lists concatenated in thread order;
//   - the window rows are cut into bands of `band_rows` rows, band b (from the viewport's bottom)
//     belongs to thread b mod threads; every thread runs stages 6–10 of every triangle of the
//     batch on its own bands only, in triangle order. A depth-buffer word is touched by one
//     thread only, in the order of one thread: the depth buffer, every depth-test result and
//     every fragment are those of the sequential unit;
//   - a thread keeps its fragments as compact records with a run mark per (triangle, band); the
//     frame's fragment stream is the runs ordered by (triangle, band) — the sequential order,
//     rows bottom to top — and the statistics are sums of per-thread counters.
// The two phases are pipelined: in step k each thread rasterises batch k − 1 and sets up batch
// k (two equation buffers), one barrier per step.
#pragma once

#include <cstdint>
#include <vector>

#include "model/config/config.hpp"
#include "model/unit/backend.hpp"
#include "model/unit/io.hpp"
#include "model/unit/raster_unit.hpp"

namespace fxr {

// Rows per band: the bands go round-robin to the threads (docs/speed.md: measured choice).
inline constexpr int kThreadBandRows = 8;
// Primitives per batch between two barriers (docs/speed.md).
inline constexpr int kThreadBatchPrims = 2048;

struct ThreadOptions {
  int threads = 1;                    // ≥ 1; 1 runs the sequential chain (model/unit/chain.hpp)
  int band_rows = kThreadBandRows;    // ≥ 1
  int batch_prims = kThreadBatchPrims;  // ≥ 1
};

// Contract: run_raster_unit_to(cfg, st, tris, f, sink, NoTaps) on opts.threads threads, with
// the same result for every thread count (the fragment stream, the depth buffer, the
// statistics). The fragments go to `keep` (appended as records, nullptr: not kept) or to `sink`
// (emitted in order on the calling thread after the triangles are drawn; nullptr: none); with
// neither, no varyings are computed. Prepares `f` (frame_begin). Invalid options (threads,
// band_rows or batch_prims < 1): std::invalid_argument.
void run_raster_unit_threads(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                             FrameOutput& f, FragmentStore* keep, FragmentSink* sink, const ThreadOptions& opts);

// Contract: as run_raster_unit (model/unit/raster_unit.hpp) on opts.threads threads: the same
// FrameOutput for every thread count. The line segments are drawn after the triangles on the
// calling thread (one pass, docs/lines.md).
FrameOutput run_raster_unit(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                            const ThreadOptions& opts);
FrameOutput run_raster_unit(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                            const DrawState& line_st, const std::vector<ClipLine>& lines, const ThreadOptions& opts);

}  // namespace fxr
