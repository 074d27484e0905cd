// The raster unit on several threads (contract and scheme in model/unit/threads.hpp; the choice
// and its figures in docs/speed.md, "Deterministic threads").
#include "model/unit/threads.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include <sched.h>

#include "model/unit/chain.hpp"
#include "model/unit/line_chain.hpp"

namespace fxr {

namespace {

// The x86-64 cache line: per-thread state is aligned to it (no false sharing), prefetches step by it.
constexpr size_t kCacheLineBytes = 64;

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

// A waiting thread polls before it rests (sleeps or yields) for a time adapted per thread and
// waiting place: next_poll_state (model/unit/threads.hpp; docs/speed.md "Session 13: threads").
// Polls between two reads of the steady clock (the deadline check) while polling.
constexpr unsigned kPollsPerClockRead = 64;

using WaitClock = std::chrono::steady_clock;
// A moment on WaitClock as one word (published beside a state for its waiters).
inline int64_t wait_clock_now() { return (int64_t)WaitClock::now().time_since_epoch().count(); }

// Whether a thread of a group of `threads` polls while it waits: not when the group has more
// threads than the cores the process may run on — a poller may then hold the core the thread it
// waits for needs, and the wait grows with the polling (docs/speed.md "Session 13: threads").
bool polling_pays(int threads) {
  static const int cores = [] {  // the cores this process may run on (0: unknown)
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof(set), &set) == 0) return CPU_COUNT(&set);
    return (int)std::thread::hardware_concurrency();
  }();
  return cores == 0 || threads <= cores;
}

// The one waiting mechanism of the threads (the barriers, the pool's start and end, the rows of
// a new depth buffer): returns once ready() holds. Polls for the thread's adaptive time (none
// when !poll: polling_pays), then calls rest(), which returns once ready() holds without
// spinning the CPU (sleeps or yields);
// published() (read once ready() holds) is the wait_clock_now() at which the state waited for
// was published, or 0 where the waiter's own clock stands in for it (the wake-up latency then
// counts as part of the wait).
template <class Ready, class Rest, class Published>
void poll_then(bool poll, Ready&& ready, Rest&& rest, Published&& published) {
  if (ready()) return;
  if (!poll) {
    rest();
    return;
  }
  thread_local PollState state;
  const int64_t start = wait_clock_now();
  const auto until = WaitClock::time_point(WaitClock::duration(start)) + state.poll;
  for (unsigned i = 1;; ++i) {
    cpu_relax();
    if (ready()) {
      state = next_poll_state(state, std::chrono::nanoseconds{0}, false);  // it needed less than state.poll
      return;
    }
    if (i % kPollsPerClockRead == 0 && WaitClock::now() > until) break;
  }
  rest();
  const int64_t at = published();
  state = next_poll_state(state, WaitClock::duration((at != 0 ? at : wait_clock_now()) - start), true);
}

// A long wait (a barrier, the pool): polls, then sleeps on `cv` (whoever makes ready() true does
// so holding `m`, then notifies `cv`).
template <class Ready, class Published>
void spin_then_wait(bool poll, std::mutex& m, std::condition_variable& cv, Ready&& ready, Published&& published) {
  poll_then(
      poll, ready,
      [&] {
        std::unique_lock<std::mutex> lock(m);
        cv.wait(lock, ready);
      },
      published);
}

// A short wait on a state published without a lock, P_ rows at a time (a new depth buffer's rows:
// a sleeping waiter would need the filling thread to take the lock and notify at every band):
// polls, then yields the core until ready() holds (more threads than cores: the thread waited
// for gets to run; the waiter's clock stands in for the publication time).
template <class Ready>
void spin_then_yield(bool poll, Ready&& ready) {
  poll_then(
      poll, ready, [&] { while (!ready()) std::this_thread::yield(); }, [] { return int64_t{0}; });
}

// All threads wait until the last one arrives; the last one runs `last` before releasing them.
class Barrier {
 public:
  explicit Barrier(int n) : n_(n), poll_(polling_pays(n)) {}
  template <class Last>
  void wait(Last&& last) {
    const uint64_t gen = gen_.load(std::memory_order_acquire);
    if (count_.fetch_add(1, std::memory_order_acq_rel) + 1 == n_) {
      count_.store(0, std::memory_order_relaxed);
      last();
      released_.store(wait_clock_now(), std::memory_order_relaxed);  // ordered by gen_'s release
      {
        std::lock_guard<std::mutex> lock(m_);
        gen_.store(gen + 1, std::memory_order_release);
      }
      cv_.notify_all();
      return;
    }
    spin_then_wait(poll_, m_, cv_, [&] { return gen_.load(std::memory_order_acquire) != gen; },
                   [&] { return released_.load(std::memory_order_relaxed); });
  }

 private:
  const int n_;
  const bool poll_;  // polling_pays(n_)
  alignas(kCacheLineBytes) std::atomic<int> count_{0};
  alignas(kCacheLineBytes) std::atomic<uint64_t> gen_{0};
  std::atomic<int64_t> released_{0};  // when the last opening happened (wait_clock_now; poll_then)
  std::mutex m_;
  std::condition_variable cv_;
};

// Candidate-pixel weights (model/unit/threads.hpp: the raster steps) saturate at kWeightCap:
// the sum is then the same whatever the order of the additions, so every thread finds the same
// step boundaries; past the cap the rest of a batch is one step. One triangle weighs less than
// 2^62 (its rows and width are within the viewport, each below 2^31).
constexpr uint64_t kWeightCap = uint64_t{1} << 62;
constexpr uint64_t kNoStart = ~uint64_t{0};
uint64_t add_weight(uint64_t a, uint64_t b) { return std::min(a + b, kWeightCap); }  // a, b ≤ kWeightCap

// The step that fills a new depth buffer covers this many steps' worth of items when they make a
// split step written in place (FrameRun::decide; docs/speed.md "Session 12: threads").
constexpr uint64_t kThreadFillStepFactor = 4;

// Rows sampled for a split step's estimated coverage (plan_split: the parts' boundaries fall on
// a sample; the grazing plane's steps are 64–130 rows, sampled every row or two).
constexpr int64_t kSplitSamples = 64;

// The members of a set-up triangle's TriangleEquations that stages 6–10 read, packed: a batch
// buffer holds these, its varying planes in arrays beside them (Batch), and a thread unpacks a
// triangle into a TriangleEquations of its own before rasterising it. A TriangleEquations holds
// kMaxVaryings planes (1,440 bytes, of which the bunny's raster read 6 lines at 0 varyings, 9 at
// 2, spread over the record): the batch buffers took 2.9 MB per batch of 2,048 and their lines
// were cold when rasterised (docs/speed.md "Session 12: threads").
struct PackedEq {
  TriSetup edges;
  DepthSetup depth;
  Plane den;
  uint32_t prim = 0;
  int den_exp = 0;
  int n = 0;
};

// A set-up triangle in a batch buffer, beside its equations.
struct EqMeta {
  uint64_t start = 0;            // weight of the chunk's earlier triangles
  int64_t b0[2] = {}, b1[2] = {};  // bands of its rows y0 and y1, fine and coarse (FrameRun::map_)
  int64_t chunk = 0;       // rows per raster item (all its rows when it weighs ≤ step_pixels) …
  int64_t items = 0;       // … and the number of items
};

// Triangles set up from one chunk of a batch (setup_chunk_prims primitives, claimed by whichever
// thread comes first; on cache lines of its own: the other parity's chunks are being filled
// while the threads read this one's).
struct alignas(kCacheLineBytes) Batch {
  std::vector<PackedEq> eqs;  // grown, never shrunk: a frame reuses the last one's
  std::vector<Plane> num;     // eqs[i]'s varying planes num[i · nv + m] …
  std::vector<int> num_exp;   // … and their exponents
  std::vector<EqMeta> meta;
  size_t n = 0;
  uint64_t weight = 0;
  uint64_t rows = 0;  // the candidate rows of its triangles, summed (the batch's band map)
  // route[g][c]: the triangles with a band of thread c in band map g (0 fine, 1 coarse).
  std::vector<std::vector<size_t>> route[2];
};

// Fragments of one thread in a raster step: `count` records of triangle `tri` (sequence number
// in the batch) from row `row` (from the viewport's bottom) up, within one band.
struct Run {
  unsigned __int128 key;  // tri · 2^64 + row: the sequential order
  size_t first, count;    // its records in the thread's step store (the runs tile the store in order)
};
unsigned __int128 run_key(uint64_t tri, int64_t row) { return (unsigned __int128)tri << 64 | (uint64_t)row; }
bool run_before(const Run& a, const Run& b) { return a.key < b.key; }
// Appends a run, its fields stored in place: a Run built on the stack and copied (push_back of a
// braced Run) wrote the key as two 8-byte halves and read it back as one 16-byte word, a
// store-forwarding stall per run (7.7 % of thread_body's samples on the bunny v0: docs/speed.md
// "Session 13: threads").
void add_run(std::vector<Run>& runs, uint64_t tri, int64_t row, size_t first, size_t count) {
  Run& r = runs.emplace_back();
  r.key = run_key(tri, row);
  r.first = first;
  r.count = count;
}

// Packs `a` (its first nv planes) as triangle i of batch b (room made by the caller).
void pack_used(const TriangleEquations& a, int nv, Batch& b, size_t i) {
  PackedEq& p = b.eqs[i];
  p.prim = a.prim;
  p.edges = a.edges;
  p.depth = a.depth;
  p.den = a.interp.den;
  p.den_exp = a.interp.den_exp;
  p.n = a.interp.n;
  for (int m = 0; m < nv; ++m) {
    b.num[i * (size_t)nv + (size_t)m] = a.interp.num[m];
    b.num_exp[i * (size_t)nv + (size_t)m] = a.interp.num_exp[m];
  }
}

// Triangle i of batch b into `t` (the members pack_used kept; the others are not read by stages
// 6–10). t.serial stays 0: FragmentChain::rows begins the fused span per call (a record edited by
// hand, model/stages/interp_span.hpp).
void unpack_used(const Batch& b, size_t i, int nv, TriangleEquations& t) {
  const PackedEq& p = b.eqs[i];
  t.prim = p.prim;
  t.edges = p.edges;
  t.depth = p.depth;
  t.interp.den = p.den;
  t.interp.den_exp = p.den_exp;
  t.interp.n = p.n;
  for (int m = 0; m < nv; ++m) {
    t.interp.num[m] = b.num[i * (size_t)nv + (size_t)m];
    t.interp.num_exp[m] = b.num_exp[i * (size_t)nv + (size_t)m];
  }
  t.serial = 0;
}

// Thread 0's sink in a split step: records written straight into the frame's store, in its
// layout, at most `cap` of them (its rows' candidate pixels) from `p` on.
class WindowSink final : public FragmentSink {
 public:
  WindowSink() { offer_span_space(); }  // span_space is asked only of a sink offering it
  void reset(uint8_t* p, size_t cap, int nv) {
    p_ = p, cap_ = cap, n_ = 0, nv_ = nv, stride_ = fragment_record_bytes(nv);
  }
  size_t count() const { return n_; }
  void emit(const Fragment& f) override {
    uint8_t* r = room(1);
    put_fragment_header(r, f.prim, f.x, f.y, f.depth);
    for (int k = 0; k < nv_; ++k) {
      const FxFloat& v = f.var[k];
      if (!fragment_var_storable(v.sig, v.exp)) throw std::logic_error("threads: a varying the compact record cannot hold");
      put_fragment_var(r, k, v.sig, v.exp, v.neg);
    }
    ++n_;
  }
  void emit_span(const FragmentRecords& b) override {
    if (b.num_varyings != nv_) throw std::logic_error("threads: a span of another record shape");
    if (b.count) std::memcpy(room(b.count), b.data, b.count * stride_);
    n_ += b.count;
  }
  uint8_t* span_space(size_t max_records, int num_varyings) override {
    return num_varyings == nv_ ? room(max_records) : nullptr;
  }
  void span_done(size_t count) override { n_ += count; }

 private:
  uint8_t* room(size_t k) {
    if (n_ + k > cap_) throw std::logic_error("threads: a split step's rows gave more records than candidate pixels");
    return p_ + n_ * stride_;
  }
  uint8_t* p_ = nullptr;
  size_t cap_ = 0, n_ = 0, stride_ = 0;
  int nv_ = 0;
};

int64_t floor_div(int64_t n, int64_t d) { return n >= 0 ? n / d : -((-n + d - 1) / d); }  // d > 0
int64_t ceil_div(int64_t n, int64_t d) { return -floor_div(-n, d); }                     // d > 0

// About how many pixels of row j the triangle covers: the pixel centres where no edge function
// is negative (the top-left bias ignored), within the candidate columns. A split step's
// scheduling weight only (model/unit/threads.hpp); never an output.
int64_t row_coverage(const TriSetup& t, int64_t j) {
  const int64_t one = int64_t{1} << t.g, half = one >> 1;
  const int64_t Y = j * one + half;
  int64_t lo = t.x0, hi = t.x1;
  for (const EdgeEq& e : t.e) {
    const int64_t v = e.b * Y + e.c;  // E = a·X + v at X = i·one + half
    if (e.a > 0) lo = std::max(lo, ceil_div(-v - e.a * half, e.a * one));
    else if (e.a < 0) hi = std::min(hi, floor_div(v + e.a * half, -e.a * one));
    else if (v < 0) return 0;
  }
  return std::max<int64_t>(0, hi - lo + 1);
}

// A thread's records of one raster step and their runs (cache lines of their own: the thread
// appends to one parity's, a record at a time, while the others read the other parity's).
struct alignas(kCacheLineBytes) StepRecords {
  FragmentStore store;
  std::vector<Run> runs;
};

// One thread's state; kept by the pool from frame to frame (buffers keep their capacity). What
// the other threads read during a step (a batch, a step's records) never shares a cache line
// with what this thread writes during it (its counters, its cursor, the other parities): on
// two cores running at once such a line would move between them at every write
// (docs/speed.md "Session 8: threads").
struct alignas(kCacheLineBytes) Worker {
  RasterStats stats;
  StepRecords step[2];   // by step parity
  // Raster cursor in the current batch: chunk, index in its route list, item of the triangle.
  size_t cur_p = 0;
  size_t cur_r = 0;
  uint64_t cur_k = 0;
  uint64_t next_start = kNoStart;  // weight where this thread's next item starts (after a step)
  size_t direct = 0;               // records written straight into the frame (a split step) …
  size_t placed = 0;               // … from this record on (thread 0: the step's first)
  std::exception_ptr error;
};

// Worker threads that persist between frames: run(fn) calls fn(w) on threads 0 … n − 1 (0 is the
// calling thread) and returns when every call has returned.
class Pool {
 public:
  explicit Pool(int n) : n_(n), poll_(polling_pays(n)), workers_((size_t)n) {
    for (int w = 1; w < n; ++w) threads_.emplace_back([this, w] { loop(w); });
  }
  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
      gen_.fetch_add(1, std::memory_order_release);
    }
    cv_.notify_all();
    for (std::thread& t : threads_) t.join();
  }
  int size() const { return n_; }
  std::vector<Worker>& workers() { return workers_; }
  std::vector<Batch> chunks[2];  // a batch's set-up chunks, by batch parity
  bool busy = false;
  size_t last_records = 0;  // records the last frame kept: the next one reserves as many
  SharedVertexTable vertices;  // the threads' vertex cache (docs/speed.md "Session 8: threads")

  template <class Fn>
  void run(Fn& fn) {
    job_ = [](void* p, int w) { (*static_cast<Fn*>(p))(w); };
    arg_ = &fn;
    running_.store(n_ - 1, std::memory_order_relaxed);
    started_.store(wait_clock_now(), std::memory_order_relaxed);  // ordered by gen_'s release
    {
      std::lock_guard<std::mutex> lock(m_);
      gen_.fetch_add(1, std::memory_order_release);
    }
    cv_.notify_all();
    fn(0);
    spin_then_wait(
        poll_, done_m_, done_cv_, [&] { return running_.load(std::memory_order_acquire) == 0; },
        [] { return int64_t{0}; });  // the last worker's end: the waiter's clock stands in for it
  }

 private:
  void loop(int w) {
    uint64_t seen = 0;
    for (;;) {
      spin_then_wait(
          poll_, m_, cv_, [&] { return gen_.load(std::memory_order_acquire) != seen; },
          [&] { return started_.load(std::memory_order_relaxed); });
      seen = gen_.load(std::memory_order_acquire);
      {
        std::lock_guard<std::mutex> lock(m_);
        if (stop_) return;
      }
      job_(arg_, w);  // never throws (the frame body catches)
      if (running_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        { std::lock_guard<std::mutex> lock(done_m_); }
        done_cv_.notify_all();
      }
    }
  }

  const int n_;
  const bool poll_;  // polling_pays(n_)
  std::vector<Worker> workers_;
  std::vector<std::thread> threads_;
  std::mutex m_, done_m_;
  std::condition_variable cv_, done_cv_;
  std::atomic<uint64_t> gen_{0};
  std::atomic<int64_t> started_{0};  // when run() last started the workers (wait_clock_now; poll_then)
  bool stop_ = false;  // under m_
  std::atomic<int> running_{0};
  void (*job_)(void*, int) = nullptr;
  void* arg_ = nullptr;
};

// The calling thread's pool (a nested call, from a sink's emit, gets a pool of its own).
class PoolLease {
 public:
  explicit PoolLease(int n) {
    thread_local std::unique_ptr<Pool> mine;
    if (mine && mine->busy) {
      own_.reset(new Pool(n));
      pool_ = own_.get();
    } else {
      if (!mine || mine->size() != n) {
        mine.reset();
        mine.reset(new Pool(n));
      }
      pool_ = mine.get();
    }
    pool_->busy = true;
  }
  ~PoolLease() { pool_->busy = false; }
  Pool& operator*() const { return *pool_; }

 private:
  std::unique_ptr<Pool> own_;
  Pool* pool_ = nullptr;
};

void add_stats(RasterStats& to, RasterStats& from) {
  std::vector<uint64_t*> dst;
  auto collect = [&](const char*, uint64_t& x) { dst.push_back(&x); };
  to.visit(collect);
  size_t i = 0;
  auto add = [&](const char*, uint64_t& x) { *dst[i++] += x; };
  from.visit(add);
  TriStats& a = to.tris;
  const TriStats& b = from.tris;
  a.geom_rejected_range += b.geom_rejected_range, a.in += b.in, a.drawn += b.drawn, a.zero_area += b.zero_area;
  a.backface += b.backface, a.no_samples += b.no_samples, a.range += b.range;
}

// One frame on the pool's threads (the scheme of model/unit/threads.hpp).
class FrameRun {
 public:
  FrameRun(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris, FrameOutput& f,
           FragmentStore* keep, FragmentSink* sink, const ThreadOptions& opts, Pool& pool)
      : cfg_(cfg), st_(st), tris_(tris), f_(f), keep_(keep), sink_(sink), obs_(opts.observer), W_(pool.workers()),
        chunks_{&pool.chunks[0], &pool.chunks[1]}, T_((int)W_.size()), R_(opts.band_rows),
        P_(std::min<int64_t>(opts.band_rows, kThreadFineBandRows)), band_rows_{P_, R_}, B_((size_t)opts.batch_prims),
        C_(std::min((size_t)opts.setup_chunk_prims, B_)), step_((uint64_t)opts.step_pixels),
        records_(keep != nullptr || sink != nullptr), nv_(records_ ? st.num_varyings : 0),
        nbatches_((int64_t)((tris.size() + B_ - 1) / B_)), poll_(polling_pays(T_)), barrier_(T_) {
    for (int g = 0; g < 2; ++g)
      for (int k = 0; k < 31; ++k)
        if (band_rows_[g] == (int64_t)1 << k) band_shift_[g] = k;
    const size_t most = (B_ + C_ - 1) / C_;  // chunks in a batch
    for (int q = 0; q < 2; ++q) {
      if (chunks_[q]->size() != most) chunks_[q]->resize(most);
      base_weight_[q].assign(most, 0), base_tri_[q].assign(most, 0);
    }
    cursor_.resize((size_t)T_);
  }

  // Contract: the whole frame; `f` is prepared here (frame_begin's checks come first).
  void run(Pool& pool) {
    phase(0, ThreadPhase::Frame);
    frame_check(cfg_, st_);
    f_.width = st_.viewport_w;
    f_.height = st_.viewport_h;
    f_.fragments.shape(st_.num_varyings);
    f_.stats = RasterStats{};
    if (keep_ && keep_ != &f_.fragments) keep_->shape(st_.num_varyings);
    if (sink_) sink_->draw_state(st_);
    const size_t words = (size_t)f_.width * (size_t)f_.height;
    // A depth buffer of the right size is cleared by the threads, each its own bands; a new
    // one is allocated and cleared here while the other threads set up the first batch.
    reuse_depth_ = f_.depth.size() == words;
    for (Worker& w : W_) {
      w.stats = RasterStats{};
      w.error = nullptr;
      for (int q = 0; q < 2; ++q) {
        w.step[q].store.shape(st_.num_varyings);
        w.step[q].runs.clear();
      }
    }
    for (int q = 0; q < 2; ++q)
      for (Batch& b : *chunks_[q]) {
        b.route[0].resize((size_t)T_), b.route[1].resize((size_t)T_);
        // Room for the planes of this frame's varying count (the last frame's may differ).
        b.num.resize(b.eqs.size() * (size_t)nv_), b.num_exp.resize(b.eqs.size() * (size_t)nv_);
      }
    // The frame's store grows between steps (serial); a frame like the last needs no growth.
    if (keep_) keep_->reserve(pool.last_records);
    // One vertex cache table for all the threads (a thread's own would miss the vertices the
    // others computed: docs/speed.md "Session 8: threads"), for draws that fill one.
    vertices_ = nullptr;
    if (tris_.size() > kVertexCacheMinPrims) {
      // Setup reads a vertex's 1/w_c only for the 1/w plane, built with records and varyings
      // (UnitChain's rule): otherwise the shared table need not compute it.
      pool.vertices.begin(st_.num_varyings, /*rw_unread=*/!records_ || st_.num_varyings <= 0);
      vertices_ = &pool.vertices;
    }
    ctl_.fill_depth = reuse_depth_;
    ctl_.setup = nbatches_ > 0 ? 0 : -1;
    ctl_.route_map = route_map_[0] = next_map_ = -1;  // the first batch: both band maps
    nchunks_[0] = (std::min(B_, tris_.size()) + C_ - 1) / C_;
    // A new depth buffer: filled by the calling thread in step 1 (the first raster step), a band
    // at a time, while the others rasterise the rows already filled; filled before the steps,
    // the others waited for it whenever the first batch's setup was short (the grazing plane's 2
    // triangles: docs/speed.md "Session 10: threads").
    defer_clear_ = !reuse_depth_;
    clear_rows_.store(0, std::memory_order_relaxed);
    if (defer_clear_) {
      f_.depth.clear();
      f_.depth.reserve(words);  // the rows are appended by new_depth_rows (the data never moves)
    }
    claims_.store(0, std::memory_order_relaxed);
    ctl_.done = false;
    auto body = [this](int w) { thread_body(w); };
    pool.run(body);
    for (Worker& w : W_)
      if (w.error) std::rethrow_exception(w.error);
    for (Worker& w : W_) add_stats(f_.stats, w.stats);
    pool.last_records = out_size_;
    phase(0, ThreadPhase::Done);
  }

 private:
  void phase(int w, ThreadPhase p) {
    if (obs_) obs_->phase(w, p);
  }

  void thread_body(int w) {
    Worker& me = W_[(size_t)w];
    NoTaps taps;
    std::optional<GeometryChain<NoTaps>> geometry;
    std::optional<SetupStage> setup;
    std::optional<FragmentChain<NoTaps>> chain;  // made after the depth buffer exists
    // The step's store, retargeted per step (KeepFragments: the span path, model/unit/backend.hpp).
    KeepFragments to_store(me.step[0].store);
    WindowSink window;                                  // this thread's rows of a split step …
    std::optional<FragmentChain<NoTaps>> direct_chain;  // … and the chain writing them
    std::vector<SetupTriangle> pieces;
    InputTriangle in;
    // The triangle being rasterised, unpacked from its batch buffer (unpack_used).
    const std::unique_ptr<TriangleEquations> eq(new TriangleEquations);
    for (;;) {
      if (!failed_.load(std::memory_order_relaxed)) {
        try {
          if (ctl_.fill_depth) fill_depth(w);
          if (ctl_.clear_new && w == 0) new_depth_rows();
          if (ctl_.out_parity >= 0) output(w, ctl_.out_parity);
          if (ctl_.raster >= 0) {
            phase(w, ThreadPhase::Raster);
            to_store.retarget(me.step[ctl_.rec_parity].store);
            if (!chain) chain.emplace(cfg_, st_, me.stats, f_.depth.data(), f_.width, records_ ? &to_store : nullptr, taps);
            raster(w, *chain, ctl_.split, *eq);
            if (ctl_.split) {
              if (!direct_chain) direct_chain.emplace(cfg_, st_, me.stats, f_.depth.data(), f_.width, &window, taps);
              raster_split(w, *chain, *direct_chain, window, *eq);
            }
          }
          if (ctl_.setup >= 0) {
            phase(w, ThreadPhase::Setup);
            if (!geometry) {
              geometry.emplace(cfg_, st_, taps), setup.emplace(cfg_, st_, records_);
              if (vertices_) geometry->vertex_cache().share(*vertices_);
            }
            set_up(w, *geometry, *setup, pieces, in);
          }
        } catch (...) {
          me.error = std::current_exception();
          failed_ = true;
        }
      }
      phase(w, ThreadPhase::Wait);
      barrier_.wait([&] {
        phase(w, ThreadPhase::Serial);
        try {
          decide(w);
        } catch (...) {  // the frame's store could not grow: every thread stops after this step
          me.error = std::current_exception();
          failed_ = true;
          ctl_.done = true;
        }
      });
      if (ctl_.done) break;
    }
    if (w == 0 && !failed_.load(std::memory_order_relaxed)) new_depth_rows();  // a frame that ended before
    if (w != 0) phase(w, ThreadPhase::Done);
  }

  // Thread 0: the rest of a deferred new depth buffer, P_ rows at a time, each published
  // (clear_rows_: rows from the viewport's bottom) for the threads waiting to rasterise it.
  void new_depth_rows() {
    const size_t words = (size_t)f_.width * (size_t)f_.height;
    if (f_.depth.size() >= words) return;
    phase(0, ThreadPhase::Clear);
    const uint32_t code = depth_max_code(cfg_.raster);
    for (int64_t r = (int64_t)(f_.depth.size() / (size_t)f_.width); r < f_.height;) {
      const int64_t n = std::min<int64_t>(P_, f_.height - r);
      f_.depth.insert(f_.depth.end(), (size_t)(n * f_.width), code);  // within the reserved capacity
      r += n;
      clear_rows_.store(r, std::memory_order_release);
    }
  }
  // Before a thread other than 0 rasterises up to row `row` (from the viewport's bottom) in the
  // step that fills a new depth buffer: wait until thread 0 has filled it.
  void wait_rows(int64_t row) {
    if (ctl_.clear_new) spin_then_yield(poll_, [&] { return clear_rows_.load(std::memory_order_acquire) > row; });
  }

  // Step 0 with a reused depth buffer: this thread's bands cleared.
  void fill_depth(int w) {
    phase(w, ThreadPhase::Setup);
    const uint32_t code = depth_max_code(cfg_.raster);
    const int64_t h = f_.height;
    for (int64_t r0 = (int64_t)w * R_; r0 < h; r0 += (int64_t)T_ * R_) {
      const int64_t r1 = std::min<int64_t>(h, r0 + R_);
      std::fill(f_.depth.begin() + r0 * f_.width, f_.depth.begin() + r1 * f_.width, code);
    }
  }

  // Stages 1–5 on the chunks of batch ctl_.setup this thread claims (claim_chunk, until none is
  // left: a thread with less raster work in the step sets up more); the triangles routed to their
  // bands' threads and weighted (rows × width, saturating).
  void set_up(int w, GeometryChain<NoTaps>& geometry, SetupStage& setup, std::vector<SetupTriangle>& pieces,
              InputTriangle& in) {
    const int q = (int)(ctl_.setup & 1);
    const size_t lo = (size_t)ctl_.setup * B_, len = std::min(B_, tris_.size() - lo);
    for (;;) {
      const size_t c = claim_chunk(w, nchunks_[q]);
      if (c >= nchunks_[q]) return;
      const size_t p0 = lo + c * C_;
      set_up_chunk(w, (*chunks_[q])[c], p0, std::min(lo + len, p0 + C_), geometry, setup, pieces, in);
    }
  }

  // The next unclaimed chunk of the n of the batch being set up (n: none left). The first half of
  // the threads claim from the batch's front, the others from its back, so a thread's chunks are
  // mostly consecutive primitives: a vertex shared by neighbouring primitives is then found in
  // vertex-table lines this thread wrote rather than in the other core's cache (docs/speed.md
  // "Session 11: threads"). Which thread sets a chunk up changes no output.
  size_t claim_chunk(int w, size_t n) {
    const bool from_back = w >= (T_ + 1) / 2;
    uint64_t cur = claims_.load(std::memory_order_relaxed);
    for (;;) {
      const uint64_t front = cur & kClaimMask, back = cur >> kClaimBits;
      if (front + back >= n) return n;
      const uint64_t next = from_back ? cur + (uint64_t{1} << kClaimBits) : cur + 1;
      if (claims_.compare_exchange_weak(cur, next, std::memory_order_relaxed))
        return from_back ? (size_t)(n - 1 - back) : (size_t)front;
    }
  }

  // Stages 1–5 on primitives p0 … p1 − 1 into chunk buffer b.
  void set_up_chunk(int w, Batch& b, size_t p0, size_t p1, GeometryChain<NoTaps>& geometry, SetupStage& setup,
                    std::vector<SetupTriangle>& pieces, InputTriangle& in) {
    Worker& me = W_[(size_t)w];
    b.n = 0;
    b.weight = 0;
    for (int g = 0; g < 2; ++g)
      for (std::vector<size_t>& r : b.route[g]) r.clear();
    b.rows = 0;
    // The input triangles themselves kInputPrefetchAhead ahead (their key words are hashed for
    // the vertex cache's prefetch), as UnitChain::draw_all; the chunk's first ones at its start.
    const auto prefetch_input = [&](size_t p) {
      const char* t = reinterpret_cast<const char*>(&tris_[p]);
      for (size_t o = 0; o < sizeof(ClipTriangle); o += kInputPrefetchLine) __builtin_prefetch(t + o);
    };
    for (size_t p = p0; p < std::min(p1, p0 + kInputPrefetchAhead); ++p) prefetch_input(p);
    // The vertex cache's slots fetched kVertexCachePrefetchAhead primitives ahead, as
    // UnitChain::draw_all (a hint: no effect on any output).
    for (size_t p = p0; p < std::min(p1, p0 + kVertexCachePrefetchAhead); ++p) geometry.prefetch(tris_[p]);
    for (size_t p = p0; p < p1; ++p) {
      if (p + kInputPrefetchAhead < p1) prefetch_input(p + kInputPrefetchAhead);
      if (p + kVertexCachePrefetchAhead < p1) geometry.prefetch(tris_[p + kVertexCachePrefetchAhead]);
      ++me.stats.prims_in;
      // The vertex cache's triangle without the geometry chain's copies, as UnitChain::draw.
      if (const SetupTriangle* t = geometry.cached(tris_[p], (uint32_t)p, me.stats)) {
        PrimDisposition d;
        d.add(me.stats, setup.step(*t, [&](const TriangleEquations& eq) { add_triangle(b, eq); }));
        d.count(me.stats, false);
        continue;
      }
      in.prim = (uint32_t)p;
      in.tri = tris_[p];
      pieces.clear();
      if (!count_geometry(me.stats, geometry.run_stages(in, pieces, me.stats))) continue;
      PrimDisposition d;
      d.range = geometry.pieces_rejected() > 0;
      for (const SetupTriangle& t : pieces)
        d.add(me.stats, setup.step(t, [&](const TriangleEquations& eq) { add_triangle(b, eq); }));
      d.count(me.stats, pieces.empty());
    }
  }

  void add_triangle(Batch& b, const TriangleEquations& eq) {
    const TriSetup& t = eq.edges;
    if (t.y1 < t.y0 || t.x1 < t.x0) return;  // no candidate pixel: nothing to rasterise
    if (b.n == b.eqs.size()) {
      b.eqs.emplace_back(), b.meta.emplace_back();
      b.num.resize(b.eqs.size() * (size_t)nv_), b.num_exp.resize(b.eqs.size() * (size_t)nv_);
    }
    const size_t i = b.n++;
    pack_used(eq, nv_, b, i);
    EqMeta& m = b.meta[i];
    const uint64_t rows = (uint64_t)((int64_t)t.y1 - t.y0 + 1), width = (uint64_t)((int64_t)t.x1 - t.x0 + 1);
    const uint64_t weight = rows * width;
    m.start = b.weight;
    m.chunk = weight <= step_ ? (int64_t)rows : (int64_t)std::clamp<uint64_t>(step_ / width, 1, rows);
    m.items = ((int64_t)rows - 1) / m.chunk + 1;
    b.weight = add_weight(b.weight, weight);
    b.rows += rows;
    // Routed in the map chosen for the batch before its setup, or in both (decide()).
    for (int g = ctl_.route_map < 0 ? 0 : ctl_.route_map; g <= (ctl_.route_map < 0 ? 1 : ctl_.route_map); ++g) {
      m.b0[g] = band_of(t.y0, g);
      m.b1[g] = band_of(t.y1, g);
      std::vector<std::vector<size_t>>& route = b.route[g];
      if (m.b1[g] - m.b0[g] + 1 >= T_) {
        for (std::vector<size_t>& r : route) r.push_back(i);
      } else {
        for (int64_t band = m.b0[g]; band <= m.b1[g]; ++band) route[(uint32_t)band % (uint32_t)T_].push_back(i);
      }
    }
  }

  // The band of row y (in the viewport: y ≥ viewport_y) in band map g.
  int64_t band_of(int64_t y, int g) const {
    const int64_t r = y - st_.viewport_y;
    return band_shift_[g] >= 0 ? r >> band_shift_[g] : r / band_rows_[g];
  }

  // A routed triangle's packed members and planes (unpack_used), fetched ahead.
  void prefetch(const Batch& b, size_t i) const {
    const char* p = reinterpret_cast<const char*>(&b.eqs[i]);
    for (size_t o = 0; o < sizeof(PackedEq); o += kCacheLineBytes) __builtin_prefetch(p + o);
    __builtin_prefetch(p + sizeof(PackedEq) - 1);
    if (nv_ > 0) {
      const char* n = reinterpret_cast<const char*>(&b.num[i * (size_t)nv_]);
      const size_t bytes = (size_t)nv_ * sizeof(Plane);
      for (size_t o = 0; o < bytes; o += kCacheLineBytes) __builtin_prefetch(n + o);
      __builtin_prefetch(n + bytes - 1);
      __builtin_prefetch(&b.num_exp[i * (size_t)nv_]);
    }
    __builtin_prefetch(&b.meta[i]);
  }

  // Stages 6–10 on this thread's bands of the items of batch ctl_.raster that start below
  // ctl_.raster_end (skip: none, only the cursor moves past them: a split step); then
  // me.next_start is where its next item starts.
  void raster(int w, FragmentChain<NoTaps>& chain, bool skip, TriangleEquations& eq) {
    Worker& me = W_[(size_t)w];
    const int q = (int)(ctl_.raster & 1);
    const int g = map_[q];
    const int64_t R = band_rows_[g];
    const uint64_t end = ctl_.raster_end;
    FragmentStore& store = me.step[ctl_.rec_parity].store;
    std::vector<Run>& runs = me.step[ctl_.rec_parity].runs;
    store.clear();
    runs.clear();
    const int64_t vy = st_.viewport_y;
    for (; me.cur_p < nchunks_[q]; ++me.cur_p, me.cur_r = 0) {
      const Batch& b = (*chunks_[q])[me.cur_p];
      const std::vector<size_t>& list = b.route[g][(size_t)w];
      const uint64_t base = base_weight_[q][me.cur_p], tri0 = base_tri_[q][me.cur_p];
      for (; me.cur_r < list.size(); ++me.cur_r, me.cur_k = 0) {
        const size_t i = list[me.cur_r];
        const EqMeta& m = b.meta[i];
        const TriSetup& e = b.eqs[i].edges;
        const int64_t y0 = e.y0, y1 = e.y1;
        const uint64_t width = (uint64_t)((int64_t)e.x1 - e.x0 + 1);
        const uint64_t start = add_weight(base, m.start);
        const int64_t items = m.items;
        if (!skip && me.cur_r + 1 < list.size()) prefetch(b, list[me.cur_r + 1]);
        bool unpacked = false;  // eq holds triangle i (unpacked at its first band in this call)
        for (; (int64_t)me.cur_k < items; ++me.cur_k) {
          const int64_t ra = y0 + (int64_t)me.cur_k * m.chunk, rb = std::min(y1, ra + m.chunk - 1);
          const uint64_t at = add_weight(start, me.cur_k * (uint64_t)m.chunk * width);
          if (at >= end) {
            me.next_start = at;
            return;
          }
          if (skip) continue;
          const int64_t b0 = items == 1 ? m.b0[g] : band_of(ra, g), b1 = items == 1 ? m.b1[g] : band_of(rb, g);
          for (int64_t band = b0 + (int64_t)(((uint32_t)w + (uint32_t)T_ - (uint32_t)b0 % (uint32_t)T_) % (uint32_t)T_); band <= b1; band += T_) {
            const int64_t lo = std::max(ra, vy + band * R), hi = std::min(rb, vy + band * R + R - 1);
            const size_t before = store.size();
            wait_rows(hi - vy);
            if (!unpacked) unpack_used(b, i, nv_, eq), unpacked = true;
            chain.rows(eq, (int)lo, (int)hi);
            if (store.size() > before) add_run(runs, tri0 + i, lo - vy, before, store.size() - before);
          }
        }
      }
    }
    me.next_start = kNoStart;
  }

  // A split step (plan_split): stages 6–10 on this thread's contiguous part of the step's rows of
  // its one triangle. Thread 0's part leads the step's records and goes straight into the frame's
  // store from record window_base_ (through `direct`). With ctl_.in_place the other parts go
  // straight in too: part w from window_base_ + the fragments the parts before it generate
  // (counted here by traversal: at least the records they keep, so the parts never overlap; equal
  // when no fragment of theirs fails the depth test, else decide() closes the gap); without, into
  // their step stores as one run. In the step that fills a new depth buffer the rows are claimed
  // instead, a piece of P_ rows at a time, by whichever thread is free (thread 0 once it
  // has filled).
  void raster_split(int w, FragmentChain<NoTaps>& chain, FragmentChain<NoTaps>& direct, WindowSink& window,
                    TriangleEquations& eq) {
    const int q = (int)(ctl_.raster & 1);
    unpack_used((*chunks_[q])[ctl_.split_chunk], ctl_.split_tri, nv_, eq);
    if (ctl_.clear_new) {  // the step that fills a new depth buffer: pieces claimed in row order
      const int64_t ra = ctl_.split_rows[0], rb = ctl_.split_rows[(size_t)T_] - 1;
      for (;;) {
        const size_t k = (size_t)next_piece_.fetch_add(1, std::memory_order_relaxed);
        const int64_t lo = ra + (int64_t)k * P_;
        if (lo > rb) return;
        const int64_t hi = std::min(rb, lo + P_ - 1);
        if (!ctl_.in_place) {
          split_rows(w, chain, eq, lo, hi);
          continue;
        }
        // In place: from the step's first record + the fragments the earlier pieces generate
        // (plan_split counted them), at most as many as this piece generates.
        wait_rows(hi - st_.viewport_y);
        phase(w, ThreadPhase::Direct);
        window.reset(keep_->records_for_overwrite(window_base_ + piece_at_[k]), piece_at_[k + 1] - piece_at_[k], nv_);
        direct.rows(eq, (int)lo, (int)hi);
        piece_kept_[k] = window.count();
        phase(w, ThreadPhase::Raster);
      }
    }
    const int64_t lo = ctl_.split_rows[(size_t)w], hi = ctl_.split_rows[(size_t)w + 1] - 1;
    if (lo > hi) return;
    if (w == 0 || ctl_.in_place) {
      phase(w, ThreadPhase::Direct);
      const size_t width = (size_t)((int64_t)eq.edges.x1 - eq.edges.x0 + 1);
      const size_t at = window_base_ + (w == 0 ? 0 : generated(eq.edges, ctl_.split_rows[0], lo - 1));
      window.reset(keep_->records_for_overwrite(at), (size_t)(hi - lo + 1) * width, nv_);
      direct.rows(eq, (int)lo, (int)hi);
      W_[(size_t)w].placed = at;
      W_[(size_t)w].direct = window.count();
      return;
    }
    split_rows(w, chain, eq, lo, hi);
  }
  // The fragments stages 6–10 generate in rows lo … hi of a triangle (traversal's covered pixels,
  // before the depth test: at least the records those rows keep).
  static size_t generated(const TriSetup& tri, int64_t lo, int64_t hi) {
    TriSetup t = tri;
    t.y0 = (int)std::max<int64_t>(t.y0, lo);
    t.y1 = (int)std::min<int64_t>(t.y1, hi);
    size_t n = 0;
    if (t.y0 <= t.y1) traverse(t, [&](int, int xb, int xe) { n += (size_t)(xe - xb + 1); });
    return n;
  }
  // Rows lo … hi of a split step's triangle into this thread's step store, as one run.
  void split_rows(int w, FragmentChain<NoTaps>& chain, const TriangleEquations& eq, int64_t lo, int64_t hi) {
    StepRecords& rec = W_[(size_t)w].step[ctl_.rec_parity];
    const size_t before = rec.store.size();
    wait_rows(hi - st_.viewport_y);
    chain.rows(eq, (int)lo, (int)hi);
    const int q = (int)(ctl_.raster & 1);
    if (rec.store.size() > before)
      add_run(rec.runs, base_tri_[q][ctl_.split_chunk] + ctl_.split_tri, lo - st_.viewport_y, before,
              rec.store.size() - before);
  }

  // The records of the previous raster step (parity q) at their place in the sequential order:
  // into the frame's store, thread w writing the w-th of T contiguous parts of the step's range
  // (from every thread's records: were each thread to write its own runs, the bunny's runs of a
  // few records would put both threads' writes on most cache lines of the store), or, on the
  // calling thread, to the sink. The merge starts at the run holding the part's first record
  // (found by binary search, not by merging the runs before it), and consecutive runs of one
  // thread go out in one copy (docs/speed.md "Session 9: threads").
  void output(int w, int q) {
    if (!keep_ && !(sink_ && w == 0)) return;
    phase(w, ThreadPhase::Output);
    const size_t n = out_size_ - out_base_;  // the step's records
    const size_t lo = keep_ ? n * (size_t)w / (size_t)T_ : 0, hi = keep_ ? n * (size_t)(w + 1) / (size_t)T_ : n;
    if (lo >= hi) return;
    OutputCursor& c = cursor_[(size_t)w];
    c.head.assign((size_t)T_, 0);
    const auto runs = [&](int t) -> const std::vector<Run>& { return W_[(size_t)t].step[q].runs; };
    // The first run of thread t with a key ≥ k, and the step's records before key k.
    const auto first_at = [&](int t, unsigned __int128 k) {
      const std::vector<Run>& r = runs(t);
      return (size_t)(std::lower_bound(r.begin(), r.end(), k, [](const Run& a, unsigned __int128 b) { return a.key < b; }) -
                      r.begin());
    };
    const auto records_before = [&](unsigned __int128 k) {
      size_t sum = 0;
      for (int t = 0; t < T_; ++t) {
        const std::vector<Run>& r = runs(t);
        const size_t i = first_at(t, k);
        sum += i < r.size() ? r[i].first : W_[(size_t)t].step[q].store.size();
      }
      return sum;
    };
    // The run holding record lo: of each thread's last run starting at or before lo (records
    // before its key ≤ lo: monotone in the run index), the one of the largest key.
    size_t at = 0;
    if (lo > 0) {
      bool found = false;
      unsigned __int128 start = 0;
      for (int t = 0; t < T_; ++t) {
        const std::vector<Run>& r = runs(t);
        size_t a = 0, b = r.size();  // the runs [0, a) start at or before lo; [b, end) after
        while (a < b) {
          const size_t m = a + (b - a) / 2;
          if (records_before(r[m].key) <= lo) a = m + 1;
          else b = m;
        }
        if (a > 0 && (!found || r[a - 1].key > start)) start = r[a - 1].key, found = true;
      }
      if (found) {
        for (int t = 0; t < T_; ++t) c.head[(size_t)t] = first_at(t, start);
        at = records_before(start);
      }
    }
    // The runs in the sequential order from there (a T-way merge by key); `at`: the step's
    // records before the run. A pending copy grows while the runs follow each other in one
    // thread's store.
    int pend_t = -1;
    size_t pend_src = 0, pend_dst = 0, pend_n = 0;
    const auto flush = [&] {
      if (pend_n == 0) return;
      const FragmentStore& src = W_[(size_t)pend_t].step[q].store;
      if (keep_) keep_->write_at(out_base_ + pend_dst, src, pend_src, pend_n);
      else sink_->emit_span(FragmentRecords{src.data() + pend_src * src.record_bytes(), pend_n, src.num_varyings()});
      pend_n = 0;
    };
    while (at < hi) {
      int best = -1;
      for (int t = 0; t < T_; ++t) {
        const std::vector<Run>& r = runs(t);
        if (c.head[(size_t)t] == r.size()) continue;
        if (best < 0 || run_before(r[c.head[(size_t)t]], runs(best)[c.head[(size_t)best]])) best = t;
      }
      if (best < 0) break;
      const Run& run = runs(best)[c.head[(size_t)best]++];
      const size_t a = std::max(at, lo), b = std::min(at + run.count, hi);
      if (a < b) {
        const size_t src = run.first + (a - at);
        if (pend_n > 0 && pend_t == best && pend_src + pend_n == src && pend_dst + pend_n == a) {
          pend_n += b - a;
        } else {
          flush();
          pend_t = best, pend_src = src, pend_dst = a, pend_n = b - a;
        }
      }
      at += run.count;
    }
    flush();
  }

  // Between two steps, on the last thread `w` to arrive: what the next step does.
  void decide(int w) {
    ctl_.fill_depth = false;
    const bool was_fill = ctl_.clear_new;  // the step just done filled a new depth buffer
    ctl_.clear_new = defer_clear_;  // the step after step 0 fills a deferred new depth buffer
    defer_clear_ = false;
    ctl_.out_parity = -1;
    if (ctl_.raster >= 0) {  // the step's records go out in the next step
      size_t total = 0;
      uint64_t next = kNoStart;
      for (const Worker& w : W_) total += w.step[ctl_.rec_parity].store.size(), next = std::min(next, w.next_start);
      if (records_) {  // after the records written straight into the frame (a split step)
        ctl_.out_parity = ctl_.rec_parity;
        out_base_ = close_parts(w, was_fill);
        out_size_ = out_base_ + total;
        if (keep_) keep_->resize_for_overwrite(out_size_);
      }
      for (Worker& t : W_) t.direct = 0;
      if (next == kNoStart) {
        ++rastered_;
        ctl_.raster = -1;
      } else {
        raster_from_ = next;
        ctl_.raster_end = add_weight(next, step_);
      }
    }
    if (ctl_.setup >= 0) {  // batch ctl_.setup is set up: the chunks' bases
      const int q = (int)(ctl_.setup & 1);
      uint64_t wsum = 0, tsum = 0;
      for (size_t c = 0; c < nchunks_[q]; ++c) {
        const Batch& b = (*chunks_[q])[c];
        base_weight_[q][c] = wsum, base_tri_[q][c] = tsum;
        wsum = add_weight(wsum, b.weight);
        tsum += b.n;
      }
      batch_empty_[q] = tsum == 0;
      // Coarse bands when the batch's triangles are on average shorter than a fine band (few
      // straddle a coarse band: each straddle is rasterised by two threads), fine ones otherwise
      // (a raster step of a few tall triangles spans few coarse bands: one thread would get most
      // of it). docs/speed.md "Session 12: threads".
      // The choice is made from a batch's own rows and applies to the next batch, whose setup
      // then routes each triangle in that map only (a second routing cost the bunny v0 ≈ 0.3 ms
      // per frame: docs/speed.md "Session 13: threads"); the frame's first batch is routed in
      // both maps and takes its own choice.
      uint64_t rows = 0;
      for (size_t c = 0; c < nchunks_[q]; ++c) rows += (*chunks_[q])[c].rows;
      next_map_ = rows < tsum * (uint64_t)P_ ? 1 : 0;
      map_[q] = route_map_[q] >= 0 ? route_map_[q] : next_map_;
      if (obs_) obs_->batch_bands(ctl_.setup, (int)band_rows_[map_[q]]);
      set_up_ = ctl_.setup + 1;
      ctl_.setup = -1;
    }
    if (failed_.load(std::memory_order_relaxed)) {
      ctl_.done = true;
      return;
    }
    if (ctl_.raster < 0) {
      while (rastered_ < set_up_ && batch_empty_[rastered_ & 1]) ++rastered_;
      if (rastered_ < set_up_) {  // the next batch from its first item (weight 0)
        ctl_.raster = rastered_;
        raster_from_ = 0;
        ctl_.raster_end = add_weight(0, step_);
        for (Worker& w : W_) w.cur_p = 0, w.cur_r = 0, w.cur_k = 0;
      }
    }
    const int64_t busy = ctl_.raster >= 0 ? ctl_.raster : rastered_;
    if (set_up_ < nbatches_ && set_up_ <= busy + 1) {
      ctl_.setup = set_up_;
      ctl_.route_map = route_map_[set_up_ & 1] = next_map_;
      const size_t lo = (size_t)set_up_ * B_, len = std::min(B_, tris_.size() - lo);
      nchunks_[set_up_ & 1] = (len + C_ - 1) / C_;
      claims_.store(0, std::memory_order_relaxed);
    }
    if (ctl_.raster >= 0) ctl_.rec_parity ^= 1;
    // The step that fills a new depth buffer: when kThreadFillStepFactor steps' worth of items are
    // still one triangle's and go in place (the grazing plane), they make one split step, whose
    // pieces the threads claim — the others rasterise while thread 0 fills, and it claims the
    // rest after (a step of step_pixels held less raster than the fill: docs/speed.md "Session
    // 12: threads").
    bool planned = false;
    if (ctl_.clear_new && ctl_.raster >= 0 && ctl_.raster_end < kWeightCap) {
      const uint64_t end = ctl_.raster_end;
      ctl_.raster_end = add_weight(raster_from_, step_ * kThreadFillStepFactor);
      plan_split();
      planned = ctl_.split && ctl_.in_place;
      if (!planned) ctl_.raster_end = end;
    }
    if (!planned) plan_split();
    ctl_.done = ctl_.raster < 0 && ctl_.setup < 0 && ctl_.out_parity < 0;
  }

  // After a split step, the parts written straight into the frame's store made contiguous (a part
  // that kept fewer records than it generated — depth-test failures — left a gap before the next:
  // the later parts move down, in order, and the frame's next split steps copy their parts ≥ 1
  // from the step stores instead); returns the end of the frame's records so far.
  size_t close_parts(int w, bool pieces) {
    size_t at = out_size_ + W_[0].direct;
    if (!ctl_.split || !ctl_.in_place) return at;
    if (pieces) {  // the claimed pieces of a fill step, in row order
      for (size_t k = 0; k + 1 < piece_at_.size(); ++k) {
        const size_t placed = window_base_ + piece_at_[k];
        if (placed > at && piece_kept_[k] > 0) {
          phase(w, ThreadPhase::Compact);
          std::memmove(keep_->records_for_overwrite(at), keep_->records_for_overwrite(placed),
                       piece_kept_[k] * keep_->record_bytes());
          phase(w, ThreadPhase::Serial);
          in_place_ok_ = false;
        }
        at += piece_kept_[k];
      }
      return at;
    }
    for (int t = 1; t < T_; ++t) {
      const Worker& p = W_[(size_t)t];
      if (p.direct == 0) continue;
      if (p.placed < at) throw std::logic_error("threads: a split step's parts overlap");
      if (p.placed > at) {
        phase(w, ThreadPhase::Compact);
        std::memmove(keep_->records_for_overwrite(at), keep_->records_for_overwrite(p.placed),
                     p.direct * keep_->record_bytes());
        phase(w, ThreadPhase::Serial);
        in_place_ok_ = false;
      }
      at += p.direct;
    }
    return at;
  }

  // Whether the next raster step is a split step (model/unit/threads.hpp): the fragments kept,
  // every item starting in [raster_from_, raster_end) of one triangle, at least a row per
  // thread, and room in the frame's store for part 0's candidate pixels. Then its rows are cut
  // into T_ contiguous parts of about equal estimated coverage and the store's size covers that
  // room for thread 0 to write into — or, with room for the whole step's candidate pixels, for
  // every part (ctl_.in_place, raster_split).
  void plan_split() {
    ctl_.split = false;
    ctl_.in_place = false;
    if (!keep_ || T_ < 2 || ctl_.raster < 0 || ctl_.raster_end >= kWeightCap) return;
    const int q = (int)(ctl_.raster & 1);
    const uint64_t from = raster_from_, end = ctl_.raster_end;
    size_t c = 0;
    while (c < nchunks_[q] && !((*chunks_[q])[c].n > 0 && from - base_weight_[q][c] < (*chunks_[q])[c].weight)) ++c;
    if (c == nchunks_[q] || from < base_weight_[q][c]) return;
    const Batch& b = (*chunks_[q])[c];
    const uint64_t rel = from - base_weight_[q][c];
    const size_t i = (size_t)(std::upper_bound(b.meta.begin(), b.meta.begin() + (ptrdiff_t)b.n, rel,
                                               [](uint64_t v, const EqMeta& m) { return v < m.start; }) -
                              b.meta.begin()) - 1;
    const EqMeta& m = b.meta[i];
    const TriSetup& t = b.eqs[i].edges;
    const uint64_t width = (uint64_t)((int64_t)t.x1 - t.x0 + 1), rows = (uint64_t)((int64_t)t.y1 - t.y0 + 1);
    const uint64_t start = base_weight_[q][c] + m.start, item = (uint64_t)m.chunk * width;
    if (start + rows * width < end || (from - start) % item != 0) return;  // another triangle's items in the step
    const int64_t k0 = (int64_t)((from - start) / item), k1 = std::min<int64_t>(m.items - 1, (int64_t)((end - 1 - start) / item));
    const int64_t ra = t.y0 + k0 * m.chunk, rb = std::min<int64_t>(t.y1, t.y0 + (k1 + 1) * m.chunk - 1);
    if (rb - ra + 1 < T_) return;
    // The parts: cumulative estimated coverage (+1 a row) over samples of `s` rows.
    const int64_t n = rb - ra + 1, s = std::max<int64_t>(1, n / kSplitSamples);
    split_weight_.clear();
    uint64_t total = 0;
    for (int64_t r = ra; r <= rb; r += s) {
      total += (uint64_t)(row_coverage(t, r) + 1) * (uint64_t)std::min(s, rb - r + 1);
      split_weight_.push_back(total);
    }
    ctl_.split_rows.assign((size_t)T_ + 1, rb + 1);
    ctl_.split_rows[0] = ra;
    if (ctl_.clear_new) {  // rows claimed a P_-row piece at a time, thread 0 once it has filled
      ctl_.split_rows[1] = ra;  // the new depth buffer (its part: none written straight)
      next_piece_.store(0, std::memory_order_relaxed);
    }
    size_t k = 0;
    for (int p = 1; p < T_ && !ctl_.clear_new; ++p) {
      const uint64_t goal = total * (uint64_t)p / (uint64_t)T_;
      while (k < split_weight_.size() && split_weight_[k] <= goal) ++k;
      ctl_.split_rows[(size_t)p] = std::min(rb + 1, ra + (int64_t)k * s);
    }
    // Room for part 0's candidate pixels within the store's capacity (the frame reserves the last
    // frame's size; growing it here would copy the frame so far, serially): else bands.
    const size_t room = out_size_ + (size_t)(ctl_.split_rows[1] - ra) * (size_t)width;
    if (room > keep_->capacity()) return;
    const size_t room_all = out_size_ + (size_t)(rb + 1 - ra) * (size_t)width;
    ctl_.in_place = in_place_ok_ && room_all <= keep_->capacity();
    if (ctl_.in_place && ctl_.clear_new) {  // the claimed pieces' places: the fragments generated before each
      const size_t n = (size_t)((rb - ra) / P_ + 1);
      piece_at_.assign(n + 1, 0);
      piece_kept_.assign(n, 0);
      TriSetup e = t;
      e.y0 = (int)ra, e.y1 = (int)rb;
      traverse(e, [&](int j, int xb, int xe) { piece_at_[(size_t)((j - ra) / P_) + 1] += (size_t)(xe - xb + 1); });
      for (size_t k = 0; k < n; ++k) piece_at_[k + 1] += piece_at_[k];
    }
    ctl_.split = true;
    ctl_.split_chunk = c;
    ctl_.split_tri = i;
    window_base_ = out_size_;
    keep_->resize_for_overwrite(ctl_.in_place ? room_all : room);
  }

  const Config& cfg_;
  const DrawState& st_;
  const std::vector<ClipTriangle>& tris_;
  FrameOutput& f_;
  FragmentStore* keep_;
  FragmentSink* sink_;
  ThreadObserver* obs_;
  std::vector<Worker>& W_;
  std::vector<Batch>* const chunks_[2];  // the pool's chunk buffers, by batch parity
  const int T_;
  const int64_t R_;  // rows of a coarse band (of a band when filling a reused depth buffer)
  const int64_t P_;  // rows of a fine band; of a new depth buffer published at a time (and of a
                     // piece claimed then)
  const int64_t band_rows_[2];  // the band maps' heights: fine (P_), coarse (R_)
  const size_t B_, C_;
  const uint64_t step_;
  const bool records_;
  const int nv_;
  const int64_t nbatches_;
  const bool poll_;  // polling_pays(T_)
  Barrier barrier_;
  std::atomic<bool> failed_{false};
  bool reuse_depth_ = false;
  bool in_place_ok_ = true;   // no split step of the frame has closed a gap yet (close_parts)
  bool defer_clear_ = false;  // a new depth buffer, filled by thread 0 in step 1 …
  alignas(kCacheLineBytes) std::atomic<int64_t> clear_rows_{0};  // … rows filled so far
  char pad2_[kCacheLineBytes - sizeof(std::atomic<int64_t>)];
  alignas(kCacheLineBytes) std::atomic<uint64_t> next_piece_{0};  // that step's next piece of rows
  char pad3_[kCacheLineBytes - sizeof(std::atomic<uint64_t>)];
  SharedVertexTable* vertices_ = nullptr;  // the threads' vertex cache table, or none
  int band_shift_[2] = {-1, -1};  // log2 band_rows_[g] when a power of two
  int map_[2] = {0, 0};  // the band map of each batch parity's batch (0 fine, 1 coarse): decide()
  int route_map_[2] = {-1, -1};  // the map its triangles were routed in (−1: both)
  int next_map_ = -1;  // the map chosen from the last batch set up: the next batch's (−1: none yet)

  // The step every thread runs next; written by decide() only, between two steps.
  struct Control {
    bool done = false;
    bool fill_depth = false;
    bool clear_new = false;   // thread 0 fills the new depth buffer first; the others wait for their rows
    int64_t setup = -1;       // batch set up in this step (−1: none), …
    int route_map = -1;       // … its triangles routed in this band map (−1: both)
    int64_t raster = -1;      // batch rasterised in this step (−1: none) …
    uint64_t raster_end = 0;  // … its items that start below this weight
    int rec_parity = 1;       // buffers of this step's records (flips at each raster step)
    int out_parity = -1;      // buffers of the previous raster step, output in this step (−1: none)
    bool split = false;       // a split step (plan_split): triangle split_tri of chunk split_chunk, …
    bool in_place = false;    // … every part written straight into the frame's store (else part 0 only)
    size_t split_chunk = 0, split_tri = 0;
    std::vector<int64_t> split_rows;  // … rows [split_rows[w], split_rows[w + 1]) on thread w
  } ctl_;
  uint64_t raster_from_ = 0;  // the weight where the step being planned starts
  size_t window_base_ = 0;    // a split step: thread 0's first record in the frame's store
  std::vector<uint64_t> split_weight_;  // plan_split's cumulative weights (kept: no allocation per step)
  // A fill step's claimed pieces written in place: piece k from window_base_ + piece_at_[k] (the
  // fragments the pieces before it generate), keeping piece_kept_[k] records (its claimer's).
  std::vector<size_t> piece_at_, piece_kept_;
  size_t out_base_ = 0, out_size_ = 0;  // first record of the step being output; records so far
  int64_t set_up_ = 0, rastered_ = 0;   // batches set up, batches rasterised
  bool batch_empty_[2] = {true, true};
  size_t nchunks_[2] = {0, 0};                          // chunks of the batch, by batch parity
  std::vector<uint64_t> base_weight_[2], base_tri_[2];  // per chunk, by batch parity
  // The chunks of the batch being set up claimed so far from its front (the low kClaimBits bits)
  // and from its back (the high ones); reset between steps.
  static constexpr int kClaimBits = 32;
  static constexpr uint64_t kClaimMask = (uint64_t{1} << kClaimBits) - 1;
  alignas(kCacheLineBytes) std::atomic<uint64_t> claims_{0};
  char pad_[kCacheLineBytes - sizeof(std::atomic<uint64_t>)];
  // output()'s merge, per thread: each thread's next run.
  struct alignas(kCacheLineBytes) OutputCursor {
    std::vector<size_t> head;
  };
  std::vector<OutputCursor> cursor_;
};

}  // namespace

PollState next_poll_state(PollState s, std::chrono::nanoseconds needed, bool rested) {
  if (!rested) return {std::min(kThreadPollMax, s.poll * 2), false, 0};
  const std::chrono::nanoseconds half = std::max(kThreadPollMin, s.poll / 2);
  if (s.raised) return {half, false, kThreadPollCooldown};  // raising did not help: poll less for a while
  if (needed <= kThreadPollMax && s.cooldown == 0)  // polling would have ended it: twice the need
    return {std::clamp(std::max(s.poll, needed) * 2, kThreadPollMin, kThreadPollMax), true, 0};
  return {half, false, std::max(0, s.cooldown - 1)};  // a long wait, or cooling down: poll less
}

void run_raster_unit_threads(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                             FrameOutput& f, FragmentStore* keep, FragmentSink* sink, const ThreadOptions& opts) {
  if (opts.threads < 1 || opts.band_rows < 1 || opts.batch_prims < 1 || opts.step_pixels < 1 ||
      opts.setup_chunk_prims < 1)
    throw std::invalid_argument("thread options: threads " + std::to_string(opts.threads) + ", band_rows " +
                                std::to_string(opts.band_rows) + ", batch_prims " + std::to_string(opts.batch_prims) +
                                ", step_pixels " + std::to_string(opts.step_pixels) + ", setup_chunk_prims " +
                                std::to_string(opts.setup_chunk_prims) + " (each must be ≥ 1)");
  if (keep && sink) throw std::invalid_argument("run_raster_unit_threads: keep and sink both given");
  if (opts.threads == 1) {  // the sequential chain itself
    KeepFragments keeper(keep ? *keep : f.fragments);
    NoTaps taps;
    if (keep && keep != &f.fragments) keep->shape(st.num_varyings);
    run_raster_unit_to(cfg, st, tris, f, keep ? &keeper : sink, taps);
    return;
  }
  PoolLease pool(opts.threads);
  FrameRun run(cfg, st, tris, f, keep, sink, opts, *pool);
  run.run(*pool);
}

FrameOutput run_raster_unit(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                            const ThreadOptions& opts) {
  FrameOutput f;
  run_raster_unit_threads(cfg, st, tris, f, &f.fragments, nullptr, opts);
  return f;
}

FrameOutput run_raster_unit(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                            const DrawState& line_st, const std::vector<ClipLine>& lines, const ThreadOptions& opts) {
  FrameOutput f = run_raster_unit(cfg, st, tris, opts);
  KeepFragments keep(f.fragments);
  NoTaps taps;
  draw_lines(cfg, line_st, lines, tris.size(), f, &keep, taps);
  return f;
}

}  // namespace fxr
