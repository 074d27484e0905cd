// The cycle-approximate SystemC model. Contract in sc/cycle_model.hpp; what is modelled and
// what is approximated: docs/cycles.md.
//
// Time. One clock is 1 ns of SystemC time. A transaction on a link carries `t`, the clock from
// which its consumer may take it. Every module is one or two SC_THREADs that wait for whole
// numbers of clocks between transactions (never clock by clock): the simulation costs a few
// events per transaction, which is what makes it fast (docs/cycles.md, "Speed").
//
// Links. An sc_fifo of `link_depth` entries is the valid / ready register between two RTL
// stages: a producer puts a result at the clock it is valid (blocking while the link is full:
// its stall), a consumer takes it when it is ready for the next transaction (blocking while the
// link is empty: starved). A pipelined stage (setup, divide) is an accept thread and an output
// thread joined by an internal FIFO of `latency` − 1 entries (with the one the output thread
// holds: its pipeline registers): the whole pipeline holds while its output is not taken, as
// the RTL's stall rule, and a triangle setup culls still takes its place in it.
#include "sc/cycle_model.hpp"

#include <systemc.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <deque>
#include <memory>
#include <unordered_map>

#include "model/stages/depth.hpp"
#include "model/stages/divide.hpp"
#include "model/stages/interp.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/traverse.hpp"
#include "model/unit/backend.hpp"
#include "model/unit/chain.hpp"

namespace fxr::cyc {

const char* stage_name(int s) {
  static const char* const n[kNumStages] = {"input", "clip", "recip", "viewport", "setup", "traverse", "interp_front", "interp_back", "depth", "divide"};
  return s >= 0 && s < kNumStages ? n[s] : "?";
}

int CycleRun::bottleneck() const {
  int b = kSetup;
  for (int s = kInput; s < kNumStages; ++s)
    if (stage[(size_t)s].busy > stage[(size_t)b].busy) b = s;
  return b;
}

namespace {

// ---- tokens ------------------------------------------------------------------------------------
// sc_fifo needs a default constructor, assignment and operator<< (sc_fifo::print).

struct GeoPrim;
struct GeoPiece;
struct TriTok {  // setup's input; in stages 1–4 the primitive and, after the clipper, the piece
  const SetupTriangle* tri = nullptr;
  const GeoPrim* prim = nullptr;
  const GeoPiece* piece = nullptr;
  uint64_t t = 0;
};
struct EqTok {
  std::shared_ptr<const TriangleEquations> eq;
  uint64_t t = 0;
};
struct SpanTok {
  Span sp;
  std::shared_ptr<const TriangleEquations> eq;
  bool last_of_tri = false;
  size_t tri = 0;  // its triangle's index in the equations FIFO's order
  uint64_t t = 0;
};
struct PipeTok {  // in setup's pipeline: its equations (none: culled) and the clock it reaches the end
  std::shared_ptr<const TriangleEquations> eq;
  uint64_t t = 0;
  uint64_t froze = 0;  // the pipeline's held clocks when it entered
};
template <class T>
std::ostream& print_tok(std::ostream& os, const T& x) {
  return os << "@" << x.t;
}
std::ostream& operator<<(std::ostream& os, const TriTok& x) { return print_tok(os, x); }
std::ostream& operator<<(std::ostream& os, const EqTok& x) { return print_tok(os, x); }
std::ostream& operator<<(std::ostream& os, const SpanTok& x) { return print_tok(os, x); }
std::ostream& operator<<(std::ostream& os, const PipeTok& x) { return print_tok(os, x); }

// ---- clocks ------------------------------------------------------------------------------------

const sc_core::sc_time kClock(1, sc_core::SC_NS);
// Thread stacks: the model's steps keep records of i128 planes on the stack.
constexpr size_t kStack = 1 << 20;

uint64_t now_clock() { return (uint64_t)(sc_core::sc_time_stamp().value() / kClock.value()); }

// What every module shares: its counters, waits in whole clocks, take / put on links.
struct Shared {
  CycleRun* run = nullptr;
  bool timeline = false;
  bool span_clocks = false;
  bool traverse_clocks = false;
};

// A stage's counters: busy clocks as the union of [b, e) intervals, stalled clocks of held results.
class Acct {
 public:
  Acct(Shared& sh, int stage) : sh_(sh), stage_(stage) {}
  StageClocks& clk() { return sh_.run->stage[(size_t)stage_]; }
  // Busy clocks as the union of [b, e) intervals (in non-decreasing b order).
  void busy(uint64_t b, uint64_t e) {
    b = std::max(b, busy_end_);
    if (e <= b) return;
    clk().busy += e - b;
    busy_end_ = e;
    if (sh_.timeline) {
      auto& v = sh_.run->busy[(size_t)stage_];
      if (!v.empty() && v.back().second == b) v.back().second = e;
      else v.emplace_back(b, e);
    }
  }
  // A result valid from `a` put into its link valid from `v` (v > a: held): the clocks counted
  // once when a pipeline's results queue up behind one held result.
  void put(uint64_t a, uint64_t v) {
    hold(a, v);
    ++clk().out;
  }
  // A result held in the stage's output register over [a, e).
  void hold(uint64_t a, uint64_t e) {
    const uint64_t from = std::max(a, stall_end_);
    if (e > from) clk().stalled += e - from;
    stall_end_ = std::max(stall_end_, e);
  }

 private:
  Shared& sh_;
  int stage_;
  uint64_t busy_end_ = 0, stall_end_ = 0;
};

class Clocked : public sc_core::sc_module {
 public:
  Clocked(sc_core::sc_module_name n, Shared& sh, int stage) : sc_core::sc_module(n), sh_(sh), acct_(sh, stage) {}

 protected:
  StageClocks& clk() { return acct_.clk(); }
  void wait_until(uint64_t t) {
    const uint64_t n = now_clock();
    if (t > n) wait((double)(t - n), sc_core::SC_NS);
  }
  // Takes the next transaction once the stage is free (clock `free_at`) and it is valid.
  template <class T>
  T take(sc_core::sc_fifo_in<T>& in, uint64_t free_at) {
    wait_until(free_at);
    T x = in.read();
    wait_until(x.t);
    ++clk().in;
    return x;
  }
  // Puts a result valid from clock `at`; while the link is full the stage stalls, and a result
  // put into a register freed in clock F is valid from F + 1.
  template <class T>
  uint64_t put(sc_core::sc_fifo_out<T>& out, T x, uint64_t at) {
    wait_until(at);
    const uint64_t a = now_clock();
    bool blocked = false;
    while (out.num_free() == 0) {
      wait(out.data_read_event());
      blocked = true;
    }
    x.t = blocked ? now_clock() + 1 : now_clock();
    acct_.put(a, x.t);
    out.write(x);
    return x.t;  // the clock the result is valid from
  }
  void busy(uint64_t b, uint64_t e) { acct_.busy(b, e); }

  // One pipeline enable (fxr_recip_stage, fxr_viewport, fxr_setup: advance = out_ready or no
  // valid result in the last register): while a result in the output register is not taken,
  // every result in the pipeline and the input wait, so each result leaves as many clocks later
  // as the pipeline was held since it entered (bubbles are not squeezed out).
  struct Freeze {
    uint64_t froze = 0;  // clocks held so far
    bool held = false;
    sc_core::sc_event thaw;
  };
  // The input of a frozen pipeline: its next slot (free_at, moved by the clocks held since
  // `base`), not while the output register is held (checked after the output thread's put of
  // the same clock).
  void wait_accept(Freeze& fz, uint64_t free_at, uint64_t base) {
    for (;;) {
      wait_until(free_at + (fz.froze - base));
      wait(sc_core::SC_ZERO_TIME);
      if (!fz.held) return;
      wait(fz.thaw);
    }
  }
  // The output of a frozen pipeline: a result reaching the end at t (moved by the clocks held
  // since it entered: the caller's) goes into the output register; from then until its consumer
  // takes it (while the link is full) the pipeline is held.
  template <class T>
  uint64_t put_frozen(sc_core::sc_fifo_out<T>& out, const T& x, uint64_t t, Freeze& fz) {
    const uint64_t v = put(out, x, t);  // the register is free unless link_depth > 1 filled it
    if (v > t) fz.froze += v - t;
    fz.held = true;
    while (out.num_free() == 0) wait(out.data_read_event());
    const uint64_t c = now_clock();
    if (c > v) fz.froze += c - v, acct_.hold(v, c);
    fz.held = false;
    fz.thaw.notify(sc_core::SC_ZERO_TIME);
    return v;
  }

  Shared& sh_;
  Acct acct_;
};

// ---- stage modules -----------------------------------------------------------------------------

// Testbench source: setup's inputs, one per clock (the RTL testbench without gaps).
SC_MODULE(Source) {
  sc_core::sc_fifo_out<TriTok> out;
  const std::vector<SetupTriangle>* tris = nullptr;
  CycleRun* run = nullptr;
  SC_CTOR(Source) {
    SC_THREAD(main);
    set_stack_size(kStack);
  }
  void main() {
    for (const SetupTriangle& t : *tris) {
      TriTok k;
      k.tri = &t;
      k.t = now_clock();
      out->write(k);
      wait(kClock);
    }
  }
};

// Stage 5: fxr_setup, pipelined (SetupStage::cost(): latency, ii); `setup_units` copies divide
// the initiation interval. Culled triangles leave without an output.
class SetupModule : public Clocked {
 public:
  SC_HAS_PROCESS(SetupModule);
  sc_core::sc_fifo_in<TriTok> in;
  sc_core::sc_fifo_out<EqTok> out;
  SetupModule(sc_core::sc_module_name n, Shared& sh, const Config& cfg, const ArchConfig& arch, const DrawState& st)
      : Clocked(n, sh, kSetup),
        stage_(cfg, st, true),
        pipe_("pipe", std::max(1, SetupStage::cost(cfg).latency - 1)) {  // + the output thread's token
    const StageCost c = SetupStage::cost(cfg);
    latency_ = c.latency;
    ii_ = std::max(1, (c.ii + arch.setup_units - 1) / arch.setup_units);
    SC_THREAD(accept);
    set_stack_size(kStack);
    SC_THREAD(emit);
    set_stack_size(kStack);
  }

 private:
  void accept() {
    uint64_t free_at = 0, base = 0;
    for (;;) {
      wait_accept(fz_, free_at, base);
      const TriTok k = take(in, 0);
      wait_accept(fz_, now_clock(), fz_.froze);
      const uint64_t ta = now_clock();
      if (sh_.run->triangles == 0 && sh_.run->primitives == 0) sh_.run->first_in = ta;
      ++sh_.run->triangles;
      busy(ta, ta + (uint64_t)ii_);
      std::shared_ptr<TriangleEquations> eq;
      stage_.step(*k.tri, [&](const TriangleEquations& e) { eq = std::make_shared<TriangleEquations>(e); });
      // A culled triangle goes down the pipeline too (it holds a stage while the pipeline is
      // stalled) and leaves at its end without an output.
      PipeTok p;
      p.eq = eq;
      p.t = ta + (uint64_t)latency_;
      p.froze = fz_.froze;
      pipe_.write(p);  // blocks while the pipeline is full (its output not taken)
      free_at = ta + (uint64_t)ii_;
      base = fz_.froze;
    }
  }
  void emit() {
    for (;;) {
      const PipeTok p = pipe_.read();
      const uint64_t t = p.t + (fz_.froze - p.froze);
      if (!p.eq) {
        wait_until(t);
        continue;
      }
      ++sh_.run->drawn;
      EqTok e;
      e.eq = p.eq;
      put_frozen(out, e, t, fz_);
    }
  }

  SetupStage stage_;
  sc_core::sc_fifo<PipeTok> pipe_;
  Freeze fz_;
  int latency_ = 0, ii_ = 1;
};

// The equations FIFO of fxr_raster_backend (tri_fifo_depth entries, written when traversal
// accepts a triangle, read by the interpolators' ctx_i). Its entries retire in order, at most one
// per clock, once traversal is past the entry and no span of it waits:
//   R_j = max(R_{j−1} + 1, P_j + 1, L_j + 1)
// P_j: the clock traversal is ready for the next triangle after j (fin_q takes the write index
// then, visible a clock later), L_j: the clock the interpolators take j's last span (none: 0).
// A span of triangle i meets its equations only as the FIFO head or the entry after it, so it
// is taken no earlier than R_{i−2} + 1; traversal accepts triangle j only with a free entry,
// R_{j−depth} + 1.
class EqFifo {
 public:
  explicit EqFifo(int depth) : depth_(depth) {}
  int depth() const { return depth_; }
  // traversal accepts triangle j (returns j)
  size_t push(bool has_spans) {
    p_.push_back(kUnknown);
    l_.push_back(has_spans ? kUnknown : 0);
    return p_.size() - 1;
  }
  void past(size_t j, uint64_t t) { p_[j] = t, changed.notify(sc_core::SC_ZERO_TIME); }
  void last_span(size_t j, uint64_t t) { l_[j] = t, changed.notify(sc_core::SC_ZERO_TIME); }
  // R_j once known (kUnknown before).
  uint64_t retire(size_t j) {
    while (r_.size() <= j) {
      const size_t k = r_.size();
      if (p_.size() <= k || p_[k] == kUnknown || l_[k] == kUnknown) return kUnknown;
      uint64_t r = std::max(p_[k] + 1, l_[k] + 1);
      if (k > 0) r = std::max(r, r_[k - 1] + 1);
      r_.push_back(r);
    }
    return r_[j];
  }
  static constexpr uint64_t kUnknown = ~(uint64_t)0;
  sc_core::sc_event changed;
  // Spans the interpolators have taken (the span link's handshake: traversal's output register
  // is free only once its span is taken, which may be after the front has read it and waits
  // for its equations).
  uint64_t spans_taken = 0;
  sc_core::sc_event taken;

 private:
  int depth_;
  std::vector<uint64_t> p_, l_, r_;
};

// Stage 6: fxr_traverse (TraverseStage::timing). A triangle is accepted only with a free entry
// of the equations FIFO (tri_fifo_depth), which the interpolators free at the triangle's last
// span (traversal itself for a triangle without spans).
class TraverseModule : public Clocked {
 public:
  SC_HAS_PROCESS(TraverseModule);
  sc_core::sc_fifo_in<EqTok> in;
  sc_core::sc_fifo_out<SpanTok> out;
  EqFifo* eq_fifo = nullptr;
  TraverseModule(sc_core::sc_module_name n, Shared& sh, const Config& cfg, const ArchConfig& arch, const DrawState& st)
      : Clocked(n, sh, kTraverse), stage_(cfg, st), link_depth_((uint64_t)arch.link_depth) {
    SC_THREAD(main);
    set_stack_size(kStack);
  }

 private:
  void main() {
    uint64_t free_at = 0;
    std::vector<Span> spans;
    for (;;) {
      // A free entry of the equations FIFO: entry j − depth retired.
      const size_t j = next_++;
      if (j >= (size_t)eq_fifo->depth()) {
        for (;;) {
          const uint64_t r = eq_fifo->retire(j - (size_t)eq_fifo->depth());
          if (r != EqFifo::kUnknown) {
            free_at = std::max(free_at, r + 1);
            break;
          }
          wait(eq_fifo->changed);
        }
      }
      const EqTok k = take(in, free_at);
      const uint64_t ta = now_clock();
      const TraverseStage::Timing tm = TraverseStage::timing(*k.eq);
      spans.clear();
      stage_.step(*k.eq, [&](const Span& s) { spans.push_back(s); });
      eq_fifo->push(!spans.empty());
      if (tm.empty) {
        free_at = ta + 1;
        eq_fifo->past(j, ta + 1);
        if (sh_.traverse_clocks) sh_.run->traverse_tri.emplace_back(ta, ta);
        continue;
      }
      uint64_t shift = 0;  // clocks lost to a full output register
      const uint64_t rc = (uint64_t)tm.row_clocks();
      for (size_t i = 0; i < spans.size(); ++i) {
        const uint64_t r = (uint64_t)(spans[i].y - k.eq->edges.y0);
        const uint64_t valid = ta + shift + (r + 1) * rc + 1;  // after the row's result clock
        SpanTok s;
        s.sp = spans[i];
        s.eq = k.eq;
        s.last_of_tri = i + 1 == spans.size();
        s.tri = j;
        // A span held in the output register stops the walk in the row's result clock: the
        // rows after it move by as much as this span's valid clock did. The register is free
        // once the interpolators have taken the span before (link_depth spans before).
        uint64_t v = valid;
        wait_until(v);
        const uint64_t a = now_clock();
        bool held = false;
        while (eq_fifo->spans_taken + link_depth_ <= span_index_) {
          wait(eq_fifo->taken);
          held = true;
        }
        if (held) {
          v = now_clock() + 1;
          clk().stalled += v - a;
        }
        shift += put(out, s, v) - valid;
        ++span_index_;
        ++sh_.run->spans;
      }
      free_at = ta + shift + (uint64_t)tm.rows * rc;
      if (sh_.traverse_clocks) sh_.run->traverse_tri.emplace_back(ta, free_at);
      eq_fifo->past(j, free_at);
      busy(ta, free_at);
      clk().busy -= shift;  // those clocks are counted as stalled (put)
    }
  }
  TraverseStage stage_;
  size_t next_ = 0;          // the FIFO index of the next triangle
  uint64_t span_index_ = 0;  // spans put out so far
  uint64_t link_depth_ = 1;
};

// Stages 7 (the interpolators' back), 8 (fxr_depth) and 9 (fxr_divide) after the hand-over of a
// span: no thread of their own. Nothing upstream waits on them but the hand-over (the back is
// free in the clock of its last sample), and every clock of a sample follows from the clocks of
// the samples before it, so a span's samples are timed here in order, in plain code, when the
// front hands the span over (docs/cycles.md, "Speed"): the same rules as links and threads would
// give — a register freed in clock F takes the next result valid from F + 1, a consumer takes a
// result when it is free and the result valid — at no SystemC event per sample.
class BackChain {
 public:
  BackChain(Shared& sh, const Config& cfg, const ArchConfig& arch, const DrawState& st, FrameOutput& f, FragmentSink* sink)
      : sh_(sh),
        back_(sh, kInterpBack),
        depth_(sh, kDepth),
        divide_(sh, kDivide),
        depth_stage_(cfg, st, DepthBufferView{f.depth.data(), f.width, st.viewport_x, st.viewport_y}),
        divide_stage_(cfg, st, true),
        sink_(sink),
        sample_link_((size_t)arch.link_depth),
        pass_link_((size_t)std::max(2, arch.link_depth)),  // fxr_depth's 2-entry output FIFO
        queue_((size_t)std::max(1, arch.depth_queue_depth - 1)),  // + the entry the head holds
        head_clocks_(DepthStage::head_clocks(arch.mem_latency)),
        test_(st.depth_test),
        hazards_(st.depth_test && st.depth_write),
        shared_port_(arch.depth_write_port == 0 && st.depth_test && st.depth_write),
        width_(f.width),
        div_(divide_cost(cfg, std::max(1, st.num_varyings), arch_divide_lanes(arch, st.num_varyings))) {
    sample_read_.assign(sample_link_, 0);
    pass_read_.assign(pass_link_, 0);
    head_read_.assign(queue_, 0);
  }

  // The span's samples handed over in clock h; returns the clock the back is free again (its
  // last sample put into the link to fxr_depth).
  uint64_t span(const std::vector<PlaneSample>& samples, uint64_t h) {
    ++back_.clk().in;
    uint64_t at = h + 1;  // the first sample, the clock after the hand-over
    uint64_t free = h;
    for (const PlaneSample& p : samples) {
      // Back → depth link (sample_link_ registers): held while the sample sample_link_ before
      // this one is not read; then valid the clock after that read.
      const uint64_t r_old = sample_read_[n_samples_ % sample_link_];
      const bool blocked = n_samples_ >= sample_link_ && r_old >= at;
      const uint64_t written = blocked ? r_old : at, valid = blocked ? r_old + 1 : at;
      back_.put(at, valid);
      back_.busy(written, written + 1);
      ++sh_.run->samples;
      sample_read_[n_samples_ % sample_link_] = depth_sample(p, written, valid);
      ++n_samples_;
      free = written;
      at = written + 1;
    }
    return free;
  }

 private:
  // fxr_depth: accepts the sample (read from the link in the returned clock), tests it (the
  // model's step, in order), queues it behind the memory read; the head leaves in order, one per
  // clock, once its read is answered (DepthStage::head_clocks), a passing sample into the 2-entry
  // output FIFO to the divider.
  uint64_t depth_sample(const PlaneSample& ps, uint64_t written, uint64_t valid) {
    const uint64_t read = std::max(accept_free_, written);
    uint64_t ta = std::max(read, valid);
    ++depth_.clk().in;
    const int64_t pixel = (int64_t)ps.y * (int64_t)width_ + ps.x;
    // Read-after-write: taken once the queued entry of the pixel has left (the clock after it
    // left; a passing one once its write is in the output FIFO).
    if (hazards_) {
      const auto it = release_.find(pixel);
      if (it != release_.end()) ta = std::max(ta, it->second);
    }
    // A request-port slot taken by a write (shared port) delays the read.
    if (shared_port_) {
      apply_port_writes(ta, true);
      ta = std::max(ta, port_free_);
      apply_port_writes(ta, false);
      port_free_ = ta + 1;
    }
    const bool pass = depth_stage_.step(ps, [](const PlaneSample&) {});
    depth_.busy(ta, ta + 1);  // the memory port's read slot
    // Into the queue (depth_queue_depth entries: queue_ behind the one the head holds): held
    // while the entry queue_ before this one has not been read by the head.
    const uint64_t h_old = head_read_[n_depth_ % queue_];
    const uint64_t in_queue = n_depth_ >= queue_ ? std::max(ta, h_old) : ta;
    accept_free_ = in_queue + 1;
    // The head: reads the entry once done with the one before, leaves once its read is answered.
    const uint64_t head_read = std::max(head_done_, in_queue);
    head_read_[n_depth_ % queue_] = head_read;
    ++n_depth_;
    uint64_t leave = std::max({head_read, ta + (uint64_t)(test_ ? head_clocks_ : 1), head_next_});
    if (pass) {
      ++sh_.run->passed;
      if (shared_port_) port_writes_.push_back(leave);
      // Into the output FIFO (pass_link_ entries): held while the one pass_link_ before is unread.
      const uint64_t at = leave + 1;
      const uint64_t r_old = pass_read_[n_pass_ % pass_link_];
      const bool blocked = n_pass_ >= pass_link_ && r_old >= at;
      const uint64_t written = blocked ? r_old : at, v = blocked ? r_old + 1 : at;
      depth_.put(at, v);
      pass_read_[n_pass_ % pass_link_] = divide(ps, written, v);
      ++n_pass_;
      leave = std::max(leave, written - 1);
      head_done_ = written;
      if (hazards_) release_[pixel] = written;
    } else {
      head_done_ = leave;
      if (hazards_) release_[pixel] = leave + 1;
    }
    // Occupied while the sample is in the queue or the output FIFO (the RTL's count registers:
    // from the clock after its input transfer to the clock its successor takes it).
    const uint64_t ob = std::max(ta + 1, occ_end_), oe = leave + (pass ? 2 : 1);
    if (oe > ob) depth_.clk().occupied += oe - ob, occ_end_ = oe;
    head_next_ = leave + 1;
    return read;
  }
  // Shared port: the head's writes change the port's next free slot in the clock they leave
  // (those up to clock t; before_accept: including t).
  void apply_port_writes(uint64_t t, bool before_accept) {
    while (!port_writes_.empty() && (before_accept ? port_writes_.front() <= t : port_writes_.front() < t)) {
      port_free_ = std::max(port_free_, port_writes_.front()) + 1;
      port_writes_.pop_front();
    }
  }
  // fxr_divide, pipelined (divide_cost: latency, ii = groups of lanes); its output is the unit's,
  // taken every clock. Returns the clock it read the sample from the FIFO.
  uint64_t divide(const PlaneSample& ps, uint64_t written, uint64_t valid) {
    const uint64_t read = std::max(divide_free_, written);
    const uint64_t ta = std::max(read, valid);
    ++divide_.clk().in;
    divide_stage_.step(ps, [&](const Fragment& f) {
      if (sink_) sink_->emit(f);
    });
    divide_.busy(ta, ta + (uint64_t)div_.ii);
    ++divide_.clk().out;
    sh_.run->last_out = ta + (uint64_t)div_.latency;
    divide_free_ = ta + (uint64_t)div_.ii;
    return read;
  }

  Shared& sh_;
  Acct back_, depth_, divide_;
  DepthStage depth_stage_;
  DivideStage divide_stage_;
  FragmentSink* sink_;
  size_t sample_link_, pass_link_, queue_;
  int head_clocks_;
  bool test_, hazards_, shared_port_;
  int width_;
  StageCost div_;
  // Per link / queue slot: the clock its consumer read the entry last put there.
  std::vector<uint64_t> sample_read_, pass_read_, head_read_;
  uint64_t n_samples_ = 0, n_pass_ = 0, n_depth_ = 0;
  uint64_t accept_free_ = 0, head_done_ = 0, head_next_ = 0, occ_end_ = 0, divide_free_ = 0, port_free_ = 0;
  std::deque<uint64_t> port_writes_;
  std::unordered_map<int64_t, uint64_t> release_;  // pixel → the clock its last queued entry frees it
};

// Stage 7: fxr_interp. The front takes a span, spends InterpStage::span_front_clocks on it and
// hands it to the back in the clock the back is free (then takes the next span); the back puts
// out one sample per clock (BackChain, below).
class InterpFront : public Clocked {
 public:
  SC_HAS_PROCESS(InterpFront);
  sc_core::sc_fifo_in<SpanTok> in;
  BackChain* back = nullptr;
  EqFifo* eq_fifo = nullptr;
  InterpFront(sc_core::sc_module_name n, Shared& sh, const Config& cfg, const ArchConfig& arch, const DrawState& st)
      : Clocked(n, sh, kInterpFront), stage_(cfg, st, true), steps_(arch.interp_div_steps) {
    SC_THREAD(main);
    set_stack_size(kStack);
  }

 private:
  void main() {
    uint64_t free_at = 0;
    for (;;) {
      const SpanTok k = take(in, free_at);
      // Its equations are the FIFO head or the entry after it: entry tri − 2 retired.
      if (k.tri >= 2) {
        for (;;) {
          const uint64_t r = eq_fifo->retire(k.tri - 2);
          if (r != EqFifo::kUnknown) {
            wait_until(r + 1);
            break;
          }
          wait(eq_fifo->changed);
        }
      }
      const uint64_t ta = now_clock();
      ++eq_fifo->spans_taken;
      if (sh_.span_clocks) sh_.run->span_taken.push_back(ta);
      eq_fifo->taken.notify(sc_core::SC_ZERO_TIME);
      if (k.last_of_tri) eq_fifo->last_span(k.tri, ta);
      samples_.clear();
      stage_.step(*k.eq, k.sp, [&](const PlaneSample& p) { samples_.push_back(p); });
      const uint64_t done = ta + (uint64_t)InterpStage::span_front_clocks(*k.eq, k.sp, steps_);
      busy(ta, done);
      // Handed over once the back is free (the clock of its previous span's last sample).
      const uint64_t h = std::max(done, back_free_);
      clk().stalled += h - done;
      ++clk().out;
      back_free_ = back->span(samples_, h);
      free_at = h;  // the next span is accepted in the hand-over clock
    }
  }
  InterpStage stage_;
  int steps_;
  uint64_t back_free_ = 0;
  std::vector<PlaneSample> samples_;
};

// A fresh SystemC kernel per run: SystemC 2.3 cannot elaborate again after sc_start, so each
// simulation gets its own simulation context (the previous one is left, not deleted: its
// processes' stacks may still be referenced by the kernel's globals).
}  // namespace

void fresh_sc_kernel() {
  static bool quiet = (setenv("SYSC_DISABLE_COPYRIGHT_MESSAGE", "1", 0), true);
  (void)quiet;
  sc_core::sc_curr_simcontext = new sc_core::sc_simcontext;
  sc_core::sc_default_global_context = sc_core::sc_curr_simcontext;
}

namespace {

// The back end (stages 5–9) behind `src_out` (setup's input link); builds and runs.
struct Backend {
  Shared sh;
  sc_core::sc_fifo<TriTok> l_in;
  sc_core::sc_fifo<EqTok> l_eq;
  sc_core::sc_fifo<SpanTok> l_span;
  EqFifo eq_fifo;
  SetupModule setup;
  TraverseModule traverse;
  InterpFront front;
  BackChain back;

  Backend(CycleRun& run, const CycleOptions& opt, const Config& cfg, const ArchConfig& arch, const DrawState& st, FrameOutput& f,
          FragmentSink* out)
      : sh{&run, opt.timeline, opt.span_clocks, opt.traverse_clocks},
        l_in("l_in", arch.link_depth),
        l_eq("l_eq", arch.link_depth),
        l_span("l_span", arch.link_depth),
        eq_fifo(arch.tri_fifo_depth),
        setup("setup", sh, cfg, arch, st),
        traverse("traverse", sh, cfg, arch, st),
        front("interp_front", sh, cfg, arch, st),
        back(sh, cfg, arch, st, f, out) {
    setup.in(l_in);
    setup.out(l_eq);
    traverse.in(l_eq);
    traverse.out(l_span);
    traverse.eq_fifo = &eq_fifo;
    front.in(l_span);
    front.back = &back;
    front.eq_fifo = &eq_fifo;
  }
};

void finish(CycleRun& run, std::chrono::steady_clock::time_point t0) {
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  run.sim_events = sc_core::sc_delta_count();
  run.clocks = run.last_out >= run.first_in && run.stage[kDivide].out > 0 ? run.last_out - run.first_in + 1 : 0;
  for (int s = 0; s < kNumStages; ++s) {
    StageClocks& c = run.stage[(size_t)s];
    if (s != kDepth) c.occupied = c.busy + c.stalled;
    const uint64_t used = c.busy + c.stalled;
    c.starved = run.clocks > used ? run.clocks - used : 0;
  }
}

// ---- stages 1–4 ---------------------------------------------------------------------------------
// The values come from fxr::GeometryChain run once per primitive (a clipped piece that fails in
// stage 3 or 4 is dropped alone, docs/pipeline.md); what each RTL stage did with it is recorded by taps, and four
// timing modules (fxr_input, fxr_clip, fxr_recip_stage, fxr_viewport) move it through.

struct GeoPiece {  // a triangle out of the clipper
  const SetupTriangle* tri = nullptr;  // out of the viewport (nullptr: rejected there or before)
  bool recip_ok = false;               // left the reciprocal stage
  bool viewport_ok = false;            // left the viewport stage
};
struct GeoPrim {
  bool converted = false;  // left fxr_input (not rejected for NaN / Inf / range)
  int64_t clip_clocks = 1; // ClipStage::rtl_cycles(): 1 for the trivial cases
  std::vector<GeoPiece> pieces;
};
using GeoTok = TriTok;

// Records per primitive what the chain's stages emitted; the clipper's clocks from a second
// ClipStage on the same input (the chain's own is private to it).
struct GeoTaps {
  GeoTaps(const Config& cfg, const DrawState& st) : clip(cfg, st) {}
  ClipStage clip;
  GeoPrim* p = nullptr;
  template <class S>
  void in(const typename S::In&) {}
  template <class S>
  void out(const typename S::Out& o) {
    if constexpr (std::is_same_v<S, ConvertStage>) {
      p->converted = true;
      clip.step(o, [](const ClippedTriangle&) {});
      p->clip_clocks = std::max<int64_t>(1, clip.rtl_cycles());
    } else if constexpr (std::is_same_v<S, ClipStage>) {
      p->pieces.emplace_back();
    } else if constexpr (std::is_same_v<S, RecipStage>) {
      p->pieces.back().recip_ok = true;
    } else if constexpr (std::is_same_v<S, ViewportStage>) {
      p->pieces.back().viewport_ok = true;
    }
  }
};

// Testbench source of the whole unit: the primitives, one offered per clock; each one's values
// computed as it is offered.
class GeoSource : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(GeoSource);
  sc_core::sc_fifo_out<GeoTok> out;
  GeoSource(sc_core::sc_module_name n, const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& prims)
      : sc_core::sc_module(n), taps_(cfg, st), chain_(cfg, st, taps_), prims_(prims) {
    SC_THREAD(main);
    set_stack_size(kStack);
  }

 private:
  void main() {
    std::vector<SetupTriangle> pieces;
    RasterStats stats;
    InputTriangle in;
    for (size_t i = 0; i < prims_.size(); ++i) {
      GeoPrim& g = prims.emplace_back();
      taps_.p = &g;
      in.prim = (uint32_t)i;
      in.tri = prims_[i];
      pieces.clear();
      chain_.run(in, pieces, stats);
      // The pieces the viewport passed, in order (a piece failing stage 3 or 4 is dropped alone).
      size_t k = 0;
      for (GeoPiece& pc : g.pieces)
        if (pc.viewport_ok && k < pieces.size()) pc.tri = &tris.emplace_back(pieces[k++]);
      GeoTok t;
      t.prim = &g;
      t.t = now_clock();
      out->write(t);
      wait(kClock);
    }
  }
  GeoTaps taps_;
  GeometryChain<GeoTaps> chain_;
  const std::vector<ClipTriangle>& prims_;

 public:
  std::deque<GeoPrim> prims;       // stable addresses for the tokens
  std::deque<SetupTriangle> tris;
};

// Stages 1 and 2, fxr_input and fxr_clip, around one output register each.
// fxr_input (clip = false): one register (ConvertStage::cost: latency 1, II 1); a rejected
// primitive leaves without an output.
// fxr_clip (clip = true): a trivially accepted or rejected primitive takes one clock
// (ClipStage::cost: latency 1, II 1); a clipped one occupies the clipper
// ClipStage::rtl_cycles() clocks (input transfer to the decision), then its fan leaves one
// triangle per clock, and the next primitive is taken once the fan is out.
class GeoRegStage : public Clocked {
 public:
  SC_HAS_PROCESS(GeoRegStage);
  sc_core::sc_fifo_in<GeoTok> in;
  sc_core::sc_fifo_out<GeoTok> out;
  GeoRegStage(sc_core::sc_module_name n, Shared& sh, const Config& cfg, bool clip)
      : Clocked(n, sh, clip ? kClip : kInput),
        clip_(clip),
        latency_((uint64_t)(clip ? ClipStage::cost(cfg).latency : ConvertStage::cost(cfg).latency)) {
    SC_THREAD(main);
    set_stack_size(kStack);
  }

 private:
  void main() {
    uint64_t free_at = 0;
    for (;;) {
      GeoTok k = take(in, free_at);
      const uint64_t ta = now_clock();
      if (!clip_ && sh_.run->primitives++ == 0) sh_.run->first_in = ta;
      const uint64_t clocks = clip_ ? (uint64_t)k.prim->clip_clocks : 1;
      busy(ta, ta + clocks);
      uint64_t at = clocks > 1 ? ta + clocks + 1 : ta + latency_;
      if (!clip_) {
        if (k.prim->converted) put(out, k, at);
      } else {
        for (const GeoPiece& pc : k.prim->pieces) {
          k.piece = &pc;
          at = put(out, k, at) + 1;
        }
      }
      free_at = std::max(ta + clocks, clocks > 1 ? now_clock() + 1 : now_clock());
    }
  }
  bool clip_;
  uint64_t latency_;
};

// A pipelined stage of `latency` clocks taking a triangle every `ii` clocks, `capacity`
// triangles in it. frozen: one pipeline enable (fxr_viewport): while its output register is
// held, every triangle in it and the input wait (the clocks since a triangle entered move its
// output by as much); else the results queue behind a held one (fxr_recip_stage's FIFO).
// keep(piece): whether the triangle leaves with an output.
class PipeModule : public Clocked {
 public:
  SC_HAS_PROCESS(PipeModule);
  sc_core::sc_fifo_in<GeoTok> in;
  sc_core::sc_fifo_out<GeoTok> out;
  PipeModule(sc_core::sc_module_name n, Shared& sh, int stage, int latency, int ii, int capacity, bool frozen,
             bool (*keep)(const GeoPiece&))
      : Clocked(n, sh, stage),
        latency_((uint64_t)latency),
        ii_((uint64_t)ii),
        frozen_(frozen),
        keep_(keep),
        pipe_("pipe", std::max(1, capacity - 1)) {  // + the one the output thread holds
    SC_THREAD(accept);
    set_stack_size(kStack);
    SC_THREAD(emit);
    set_stack_size(kStack);
  }

 private:
  struct Tok {
    GeoTok g;
    uint64_t t = 0, froze = 0;
  };
  friend std::ostream& operator<<(std::ostream& os, const Tok& x) { return os << "@" << x.t; }
  void accept() {
    uint64_t free_at = 0, base = 0;
    for (;;) {
      if (frozen_) wait_accept(fz_, free_at, base);  // the slot counter stands still while held
      GeoTok k = take(in, free_at);
      if (frozen_) wait_accept(fz_, now_clock(), fz_.froze);
      const uint64_t ta = now_clock();
      busy(ta, ta + ii_);
      Tok p;
      p.g = k;
      p.t = ta + latency_;
      p.froze = fz_.froze;
      pipe_.write(p);
      free_at = ta + ii_;
      base = fz_.froze;
    }
  }
  void emit() {
    for (;;) {
      const Tok p = pipe_.read();
      const uint64_t t = p.t + (fz_.froze - p.froze);
      wait_until(t);
      if (!keep_(*p.g.piece)) continue;
      GeoTok x = p.g;
      x.tri = x.piece->tri;
      if (frozen_) put_frozen(out, x, t, fz_);
      else put(out, x, t);
    }
  }
  uint64_t latency_, ii_;
  bool frozen_;
  bool (*keep_)(const GeoPiece&);
  sc_core::sc_fifo<Tok> pipe_;
  Freeze fz_;  // stays zero unless frozen_
};

// Stages 1–4 in front of a back end's input link.
struct Geometry {
  sc_core::sc_fifo<GeoTok> l_src, l_input, l_clip, l_recip;
  GeoSource src;
  GeoRegStage input, clip;
  PipeModule recip, viewport;
  static int recip_latency(const Config& cfg) { return RecipStage::cost(cfg).latency; }
  Geometry(Backend& b, const Config& cfg, const ArchConfig& arch, const DrawState& st, const std::vector<ClipTriangle>& prims)
      : l_src("l_src", 1),
        l_input("l_input", arch.link_depth),
        l_clip("l_clip", arch.link_depth),
        l_recip("l_recip", arch.link_depth),
        src("source", cfg, st, prims),
        input("input", b.sh, cfg, false),
        clip("clip", b.sh, cfg, true),
        // fxr_recip_stage: fxr_recip's pipeline (II 1, one enable: out_ready low stalls the lanes).
        recip("recip", b.sh, kRecip, recip_latency(cfg), 1, recip_latency(cfg), true,
              [](const GeoPiece& p) { return p.recip_ok; }),
        viewport("viewport", b.sh, kViewport, ViewportStage::cost(cfg, st.num_varyings, arch.viewport_lanes).latency,
                 ViewportStage::cost(cfg, st.num_varyings, arch.viewport_lanes).ii,
                 viewport_capacity(cfg, arch, st), true, [](const GeoPiece& p) { return p.tri != nullptr; }) {
    src.out(l_src);
    input.in(l_src);
    input.out(l_input);
    clip.in(l_input);
    clip.out(l_clip);
    recip.in(l_clip);
    recip.out(l_recip);
    viewport.in(l_recip);
    viewport.out(b.l_in);
  }
  // Triangles in fxr_viewport at once: ⌈latency / II⌉ plus the input register.
  static int viewport_capacity(const Config& cfg, const ArchConfig& arch, const DrawState& st) {
    const StageCost c = ViewportStage::cost(cfg, st.num_varyings, arch.viewport_lanes);
    return (c.latency + c.ii - 1) / c.ii + 1;
  }
};

}  // namespace

CycleRun run_backend_cycles(const Config& cfg, const ArchConfig& arch, const DrawState& st,
                            const std::vector<SetupTriangle>& tris, FrameOutput& f, FragmentSink* sink,
                            const CycleOptions& opt) {
  validate_arch(arch, "arch");
  CycleRun run;
  fresh_sc_kernel();
  const auto t0 = std::chrono::steady_clock::now();
  // The modules stay allocated with their (abandoned) kernel: their threads are still blocked
  // on links, and a module must not be destroyed under a live process.
  Backend& b = *new Backend(run, opt, cfg, arch, st, f, sink);
  Source& src = *new Source("source");
  src.tris = &tris;
  src.run = &run;
  src.out(b.l_in);
  sc_core::sc_start();
  finish(run, t0);
  return run;
}

CycleRun run_unit_cycles(const Config& cfg, const ArchConfig& arch, const DrawState& st,
                         const std::vector<ClipTriangle>& prims, FrameOutput& f, FragmentSink* sink,
                         const CycleOptions& opt) {
  validate_arch(arch, "arch");
  frame_begin(cfg, st, f);
  CycleRun run;
  fresh_sc_kernel();
  const auto t0 = std::chrono::steady_clock::now();
  Backend& b = *new Backend(run, opt, cfg, arch, st, f, sink);  // kept: as above
  new Geometry(b, cfg, arch, st, prims);
  sc_core::sc_start();
  finish(run, t0);
  return run;
}

std::vector<SetupTriangle> setup_inputs(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& prims) {
  std::vector<SetupTriangle> out;
  RasterStats stats;
  NoTaps taps;
  GeometryChain<NoTaps> chain(cfg, st, taps);
  InputTriangle in;
  for (size_t p = 0; p < prims.size(); ++p) {
    in.prim = (uint32_t)p;
    in.tri = prims[p];
    chain.run(in, out, stats);
  }
  return out;
}

}  // namespace fxr::cyc

// libsystemc.so defines main() and calls sc_main(); programs using the cycle model have their
// own main() (fxraster, GoogleTest) and start the simulations themselves (above), so sc_main
// only has to exist for the link. (In this object file: it is linked whenever the model is.)
int sc_main(int, char*[]) { return 0; }
