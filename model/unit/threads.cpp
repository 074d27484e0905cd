// The raster unit on several threads (contract and scheme in model/unit/threads.hpp; the choice
// and its figures in docs/speed.md, "Deterministic threads").
#include "model/unit/threads.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "model/unit/chain.hpp"
#include "model/unit/line_chain.hpp"

namespace fxr {

namespace {

// All threads wait until the last one arrives.
class Barrier {
 public:
  explicit Barrier(int n) : n_(n) {}
  void wait() {
    std::unique_lock<std::mutex> lock(m_);
    const uint64_t gen = gen_;
    if (++count_ == n_) {
      count_ = 0;
      ++gen_;
      cv_.notify_all();
      return;
    }
    cv_.wait(lock, [&] { return gen_ != gen; });
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  int n_, count_ = 0;
  uint64_t gen_ = 0;
};

// Fragments [begin, end) of a thread's store: triangle `tri` (sequence number in the draw), band
// `band` of the rows.
struct Run {
  uint64_t tri = 0;
  int64_t band = 0;
  size_t begin = 0, end = 0;
};

// The members of a set-up triangle stages 6–10 read (the planes of `nv` varyings): a batch
// buffer copies only these (a TriangleEquations holds kMaxVaryings planes).
void copy_used(const TriangleEquations& a, int nv, TriangleEquations& b) {
  b.prim = a.prim;
  b.edges = a.edges;
  b.depth = a.depth;
  b.interp.den = a.interp.den;
  b.interp.den_exp = a.interp.den_exp;
  b.interp.n = a.interp.n;
  for (int m = 0; m < nv; ++m) {
    b.interp.num[m] = a.interp.num[m];
    b.interp.num_exp[m] = a.interp.num_exp[m];
  }
}

int64_t floor_div64(int64_t a, int64_t d) { return a / d - ((a % d != 0) && (a < 0)); }

struct Worker {
  RasterStats stats;
  FragmentStore store;
  std::vector<Run> runs;
  std::vector<TriangleEquations> eqs[2];  // batch buffers (steps alternate)
  size_t n_eqs[2] = {0, 0};
  std::exception_ptr error;
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

}  // namespace

void run_raster_unit_threads(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                             FrameOutput& f, FragmentStore* keep, FragmentSink* sink, const ThreadOptions& opts) {
  if (opts.threads < 1 || opts.band_rows < 1 || opts.batch_prims < 1)
    throw std::invalid_argument("thread options: threads " + std::to_string(opts.threads) + ", band_rows " +
                                std::to_string(opts.band_rows) + ", batch_prims " + std::to_string(opts.batch_prims) +
                                " (each must be ≥ 1)");
  if (keep && sink) throw std::invalid_argument("run_raster_unit_threads: keep and sink both given");
  KeepFragments keeper(keep ? *keep : f.fragments);
  FragmentSink* out = keep ? &keeper : sink;
  if (opts.threads == 1) {  // the sequential chain itself
    NoTaps taps;
    if (keep && keep != &f.fragments) keep->shape(st.num_varyings);
    run_raster_unit_to(cfg, st, tris, f, out, taps);
    return;
  }
  frame_begin(cfg, st, f);
  if (keep) keep->shape(st.num_varyings);
  const int T = opts.threads;
  const bool varyings = out != nullptr;
  const int nv = varyings ? st.num_varyings : 0;
  const size_t B = (size_t)opts.batch_prims;
  const size_t nbatches = (tris.size() + B - 1) / B;
  const int64_t R = opts.band_rows;
  std::vector<Worker> W((size_t)T);
  std::atomic<bool> failed{false};
  Barrier barrier(T);

  const auto body = [&](int w) {
    Worker& me = W[(size_t)w];
    NoTaps taps;
    GeometryChain<NoTaps> geometry(cfg, st, taps);
    SetupStage setup(cfg, st, varyings);
    me.store.shape(st.num_varyings);
    KeepFragments to_store(me.store);
    FragmentChain<NoTaps> chain(cfg, st, me.stats, f.depth.data(), f.width, varyings ? &to_store : nullptr, taps);
    InputTriangle in;
    std::vector<SetupTriangle> pieces;
    uint64_t seq = 0;  // sequence number of the next triangle rasterised
    // Stages 6–10 of one triangle on this thread's bands.
    const auto raster = [&](const TriangleEquations& eq) {
      const int y0 = eq.edges.y0, y1 = eq.edges.y1;
      if (y1 < y0 || eq.edges.x1 < eq.edges.x0) return;
      const int64_t b0 = floor_div64((int64_t)y0 - st.viewport_y, R), b1 = floor_div64((int64_t)y1 - st.viewport_y, R);
      for (int64_t b = b0 + ((w - b0) % T + T) % T; b <= b1; b += T) {
        const int64_t r0 = st.viewport_y + b * R;
        const size_t begin = me.store.size();
        chain.rows(eq, (int)std::max<int64_t>(r0, y0), (int)std::min<int64_t>(r0 + R - 1, y1));
        if (me.store.size() > begin) me.runs.push_back({seq, b, begin, me.store.size()});
      }
    };
    for (size_t step = 0; step <= nbatches; ++step) {
      if (!failed.load(std::memory_order_relaxed)) {
        try {
          if (step >= 1) {  // rasterise batch step − 1: every thread's triangles, in thread order
            const int buf = (int)((step - 1) & 1);
            for (int t = 0; t < T; ++t) {
              const Worker& src = W[(size_t)t];
              for (size_t i = 0; i < src.n_eqs[buf]; ++i, ++seq) raster(src.eqs[buf][i]);
            }
          }
          if (step < nbatches) {  // set up this thread's share of batch `step`
            const int buf = (int)(step & 1);
            const size_t lo = step * B, len = std::min(B, tris.size() - lo);
            const size_t p0 = lo + len * (size_t)w / (size_t)T, p1 = lo + len * (size_t)(w + 1) / (size_t)T;
            size_t& n = me.n_eqs[buf];
            std::vector<TriangleEquations>& eqs = me.eqs[buf];
            n = 0;
            for (size_t p = p0; p < p1; ++p) {
              ++me.stats.prims_in;
              in.prim = (uint32_t)p;
              in.tri = tris[p];
              pieces.clear();
              if (!count_geometry(me.stats, geometry.run(in, pieces, me.stats))) continue;
              PrimDisposition d;
              d.range = geometry.pieces_rejected() > 0;
              for (const SetupTriangle& t : pieces)
                d.add(me.stats, setup.step(t, [&](const TriangleEquations& eq) {
                  if (n == eqs.size()) eqs.emplace_back();
                  copy_used(eq, nv, eqs[n++]);
                }));
              d.count(me.stats, pieces.empty());
            }
          }
        } catch (...) {
          me.error = std::current_exception();
          failed = true;
        }
      }
      barrier.wait();
    }
  };
  {
    std::vector<std::thread> threads;
    threads.reserve((size_t)T - 1);
    for (int w = 1; w < T; ++w) threads.emplace_back(body, w);
    body(0);
    for (std::thread& t : threads) t.join();
  }
  for (Worker& w : W)
    if (w.error) std::rethrow_exception(w.error);
  for (Worker& w : W) add_stats(f.stats, w.stats);
  if (!out) return;

  // The fragment stream: the runs of all threads in (triangle, band) order.
  size_t total = 0;
  for (const Worker& w : W) total += w.store.size();
  if (keep) keep->reserve(keep->size() + total);
  else sink->draw_state(st);
  std::vector<size_t> head((size_t)T, 0);
  for (;;) {
    int best = -1;
    for (int t = 0; t < T; ++t) {
      const std::vector<Run>& r = W[(size_t)t].runs;
      if (head[(size_t)t] == r.size()) continue;
      if (best < 0) { best = t; continue; }
      const Run &a = r[head[(size_t)t]], &b = W[(size_t)best].runs[head[(size_t)best]];
      if (a.tri < b.tri || (a.tri == b.tri && a.band < b.band)) best = t;
    }
    if (best < 0) break;
    const Run& run = W[(size_t)best].runs[head[(size_t)best]++];
    const FragmentStore& src = W[(size_t)best].store;
    if (keep) keep->append(src, run.begin, run.end - run.begin);
    else
      for (size_t i = run.begin; i < run.end; ++i) sink->emit(src[i]);
  }
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
