// model/unit/threads.hpp — the raster unit on several threads, bit-identical to one thread
// (docs/speed.md, "Deterministic threads": the choice and its measured figures).
//
// Geometry and setup by primitive batches, the back end by interleaved bands of rows, in steps
// separated by one barrier each:
//   - the primitives are taken in batches of `batch_prims`, cut into chunks of
//     `setup_chunk_prims`; the threads claim the chunks one at a time as they come to them, half
//     of them from the batch's front, the others from its back (a thread with less raster work
//     in the step sets up more; a thread's chunks are mostly consecutive), run stages 1–5 on a
//     chunk's primitives (a pure function of the primitive), count each primitive's disposition
//     and route each set-up triangle to the threads owning one of its bands;
//   - the window rows are cut into bands (of `band_rows` rows, or fewer for a batch of tall
//     triangles: kThreadFineBandRows, chosen from a batch's triangles after its setup for the
//     next batch, whose triangles are routed in that band map only; the frame's first batch is
//     routed in both and takes its own choice), band b (from the viewport's bottom) belongs to
//     thread b mod threads: within a step a depth-buffer word is touched by one thread only, in the
//     sequential order (the barrier between two steps orders the rest), so the depth buffer,
//     every depth-test result and every fragment are those of the sequential unit;
//   - a batch is rasterised in steps of about `step_pixels` candidate pixels: the triangles'
//     bounding-box rows, in draw order, weighted by their width; a large triangle is cut into
//     row chunks (the grazing plane of bench/peer_bench is two triangles). Every thread derives
//     the same step boundaries from the same weights, so a step's fragments are a contiguous
//     part of the sequential stream;
//   - a thread keeps a step's fragments as compact records in its own buffer, one run per
//     (triangle, band rows); in the next step each thread copies its runs into the frame's
//     store at offsets ordered by (triangle, first row) — the sequential order — while the
//     records are still in its cache (a sink is fed the runs in that order by the calling
//     thread instead). The statistics are sums of per-thread counters;
//   - a step whose items all belong to one triangle (a large triangle cut into row chunks: the
//     grazing plane) is a *split step* when the fragments are kept: its rows are cut into
//     `threads` contiguous parts of about equal estimated coverage instead of bands, part w on
//     thread w (one triangle per step: every depth word still has one writer in triangle
//     order). Part 0 leads the step's records, so thread 0 writes them straight into the
//     frame's store at the step's first offset; part w ≥ 1 goes straight in too, after the
//     fragments the parts before it generate (its thread counts them by traversal; a gap left by
//     depth-test failures is closed between the steps), when the store has room for the whole
//     step's candidate pixels, else into its step store to be copied in the next step
//     (docs/speed.md "Session 10: threads", "Session 11: threads");
//   - a new depth buffer is filled by the calling thread in the first raster step (step 1),
//     min(band_rows, kThreadFineBandRows) rows at a time, while the others rasterise the rows
//     already filled (that step's rows of a split step are claimed in pieces of as many rows by
//     whichever thread is free).
// The setup of batch k + 1 runs in the first raster step of batch k (two equation buffers). The
// worker threads and their buffers persist between frames (one pool per calling thread).
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include "model/config/config.hpp"
#include "model/unit/backend.hpp"
#include "model/unit/io.hpp"
#include "model/unit/raster_unit.hpp"

namespace fxr {

// Rows per band: the bands go round-robin to the threads. A batch is rasterised in bands of
// band_rows (coarse: few triangles straddle two threads' bands) when the triangles of the batch
// before it (the frame's first batch: its own) are on average shorter than a fine band, else in
// bands of min(band_rows, kThreadFineBandRows) (fine: a step of a few tall triangles is shared
// evenly). docs/speed.md "Session 12: threads" (measured choice), "Session 13: threads".
inline constexpr int kThreadBandRows = 32;
// The fine bands' rows; also the rows of a new depth buffer filled and published at a time in the
// first raster step (and of a piece of a split step's rows claimed in that step).
inline constexpr int kThreadFineBandRows = 8;
// Primitives per batch (docs/speed.md).
inline constexpr int kThreadBatchPrims = 2048;
// Candidate pixels (bounding-box rows × width) per raster step (docs/speed.md: a step's records
// stay in the threads' caches until they are copied).
inline constexpr int kThreadStepPixels = 65536;
// Primitives per setup chunk, the unit the threads claim (docs/speed.md "Session 9: threads").
inline constexpr int kThreadSetupChunkPrims = 64;

// A thread waiting for another (a barrier between two steps, the pool's start and end, a new
// depth buffer's rows) polls before it rests — sleeps, or yields its core: on an idle machine the
// others arrive within microseconds, while a sleeping thread takes tens of microseconds to wake
// (and its waker pays for the wake-up). How long it polls adapts per thread and waiting place,
// between these bounds (docs/speed.md "Deterministic threads", "Session 13: threads").
inline constexpr std::chrono::nanoseconds kThreadPollMax{100000}, kThreadPollMin{1000};
// Waits after a raise of the polling time that did not help during which it is not raised again.
inline constexpr int kThreadPollCooldown = 16;
// A waiting place's polling state, per thread: how long it polls; whether the last wait there
// rested and raised that time; waits left before it may be raised again.
struct PollState {
  std::chrono::nanoseconds poll = kThreadPollMax;
  bool raised = false;
  int cooldown = 0;
};
// Contract: the state after a wait that began in state `s`, needed `needed` (from its start to the
// moment the state waited for was published: a wake-up's latency is not part of it) and ended
// while polling (rested = false: the time doubles, the cooldown ends) or after resting. A rest
// that polling up to kThreadPollMax would have ended raises the time to twice max(poll, needed),
// unless the time is cooling down; a rest right after a raise (raising did not help: the thread
// waited for is being descheduled, a loaded machine) halves it and starts kThreadPollCooldown
// waits of cooldown; any other rest halves it (and counts one down); within [kThreadPollMin,
// kThreadPollMax]. (Halving after every rest drove the barriers' polling to kThreadPollMin for
// good once a few waits outlasted it: every barrier then slept; raising after every short rest
// kept polling up on a loaded machine: threads_test took 3–6 times its CPU.) No effect on any
// output.
PollState next_poll_state(PollState s, std::chrono::nanoseconds needed, bool rested);

// The phases a thread of run_raster_unit_threads goes through, reported to a ThreadObserver
// (a bench times them; the model never reads a clock).
enum class ThreadPhase : uint8_t {
  Frame,   // the calling thread prepares the frame (validation, buffers)
  Setup,   // stages 1–5 on this thread's share of a batch
  Raster,  // stages 6–10 on this thread's bands of a step
  Output,  // copying the previous step's records into the frame (or feeding the sink)
  Wait,    // waiting at the barrier between two steps
  Serial,  // the last thread at a barrier decides the next step (the others wait)
  Direct,  // stages 6–10 on thread 0's rows of a split step, written straight into the frame
  Clear,   // thread 0 fills a new depth buffer within the first raster step
  Compact, // the last thread at a barrier closes a gap between a split step's parts (within Serial)
  Done,    // the frame is finished for this thread
};
class ThreadObserver {
 public:
  virtual ~ThreadObserver() = default;
  // Called by thread `thread` (0: the calling thread) when it enters phase `p`.
  virtual void phase(int thread, ThreadPhase p) = 0;
  // Called once per batch (in draw order, numbered from 0) before its raster: the height of the
  // bands it is rasterised in.
  virtual void batch_bands(int64_t /*batch*/, int /*band_rows*/) {}
};

struct ThreadOptions {
  int threads = 1;                      // ≥ 1; 1 runs the sequential chain (model/unit/chain.hpp)
  int band_rows = kThreadBandRows;      // ≥ 1
  int batch_prims = kThreadBatchPrims;  // ≥ 1
  int step_pixels = kThreadStepPixels;  // ≥ 1
  int setup_chunk_prims = kThreadSetupChunkPrims;  // ≥ 1
  ThreadObserver* observer = nullptr;   // phases of every thread (threads ≥ 2), or none
};

// Contract: run_raster_unit_to(cfg, st, tris, f, sink, NoTaps) on opts.threads threads, with
// the same result for every thread count (the fragment stream, the depth buffer, the
// statistics). The fragments go to `keep` (emptied, then filled with the frame's records;
// nullptr: not kept) or to `sink` (emitted in order on the calling thread while the triangles
// are drawn; nullptr: none); with neither, no varyings are computed. Prepares `f`
// (frame_begin). Invalid options (threads, band_rows, batch_prims, step_pixels or
// setup_chunk_prims < 1):
// std::invalid_argument. A call made from inside a sink's emit runs on threads of its own.
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
