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
  static const char* const n[kNumStages] = {"geometry", "setup", "traverse", "interp_front", "interp_back", "depth", "divide"};
  return s >= 0 && s < kNumStages ? n[s] : "?";
}

int CycleRun::bottleneck() const {
  int b = kSetup;
  for (int s = kGeometry; s < kNumStages; ++s)
    if (stage[(size_t)s].busy > stage[(size_t)b].busy) b = s;
  return b;
}

namespace {

// ---- tokens ------------------------------------------------------------------------------------
// sc_fifo needs a default constructor, assignment and operator<< (sc_fifo::print).

struct TriTok {
  const SetupTriangle* tri = nullptr;
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
struct HandTok {  // interp front → back: the span's samples
  std::shared_ptr<std::vector<PlaneSample>> samples;
  uint64_t t = 0;
};
struct SampleTok {
  PlaneSample ps;
  uint64_t t = 0;
};
struct DepthEntry {  // a sample in fxr_depth's queue
  PlaneSample ps;
  bool pass = false, hazard_tracked = false;
  int64_t pixel = 0;
  uint64_t head = 0;  // earliest clock it can leave (its read answered, compared at the head)
  uint64_t t = 0;
};
struct PipeTok {  // in a pipelined stage: an output and the clock it reaches the pipeline's end
  const SetupTriangle* tri = nullptr;
  std::shared_ptr<const TriangleEquations> eq;
  Fragment f;
  uint64_t t = 0;
};
template <class T>
std::ostream& print_tok(std::ostream& os, const T& x) {
  return os << "@" << x.t;
}
std::ostream& operator<<(std::ostream& os, const TriTok& x) { return print_tok(os, x); }
std::ostream& operator<<(std::ostream& os, const EqTok& x) { return print_tok(os, x); }
std::ostream& operator<<(std::ostream& os, const SpanTok& x) { return print_tok(os, x); }
std::ostream& operator<<(std::ostream& os, const HandTok& x) { return print_tok(os, x); }
std::ostream& operator<<(std::ostream& os, const SampleTok& x) { return print_tok(os, x); }
std::ostream& operator<<(std::ostream& os, const DepthEntry& x) { return print_tok(os, x); }
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
};

class Clocked : public sc_core::sc_module {
 public:
  Clocked(sc_core::sc_module_name n, Shared& sh, int stage) : sc_core::sc_module(n), sh_(sh), stage_(stage) {}

 protected:
  StageClocks& clk() { return sh_.run->stage[(size_t)stage_]; }
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
    // Held from `at` until the result is in the register; the clocks counted once when a
    // pipeline's results queue up behind one held result.
    const uint64_t from = std::max(a, stall_end_);
    if (x.t > from) clk().stalled += x.t - from;
    stall_end_ = std::max(stall_end_, x.t);
    ++clk().out;
    out.write(x);
    return x.t;  // the clock the result is valid from
  }
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

  Shared& sh_;
  int stage_;
  uint64_t busy_end_ = 0, stall_end_ = 0;
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
    uint64_t free_at = 0;
    for (;;) {
      const TriTok k = take(in, free_at);
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
      pipe_.write(p);  // blocks while the pipeline is full (its output not taken)
      free_at = ta + (uint64_t)ii_;
    }
  }
  void emit() {
    for (;;) {
      const PipeTok p = pipe_.read();
      if (!p.eq) {
        wait_until(p.t);
        continue;
      }
      ++sh_.run->drawn;
      EqTok e;
      e.eq = p.eq;
      put(out, e, p.t);
    }
  }

  SetupStage stage_;
  sc_core::sc_fifo<PipeTok> pipe_;
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

// Stage 7: fxr_interp. The front takes a span, spends InterpStage::span_front_clocks on it and
// hands it to the back in the clock the back is free (then takes the next span); the back puts
// out one sample per clock.
class InterpFront : public Clocked {
 public:
  SC_HAS_PROCESS(InterpFront);
  sc_core::sc_fifo_in<SpanTok> in;
  sc_core::sc_fifo<HandTok>* hand = nullptr;
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
      auto samples = std::make_shared<std::vector<PlaneSample>>();
      stage_.step(*k.eq, k.sp, [&](const PlaneSample& p) { samples->push_back(p); });
      const uint64_t done = ta + (uint64_t)InterpStage::span_front_clocks(*k.eq, k.sp, steps_);
      busy(ta, done);
      wait_until(done);
      const uint64_t a = now_clock();
      HandTok h;
      h.samples = samples;
      h.t = done;
      hand->write(h);
      wait(sc_core::SC_ZERO_TIME);  // the write becomes readable in the update phase
      while (hand->num_available() > 0) wait(hand->data_read_event());  // handed over
      clk().stalled += now_clock() - a;
      ++clk().out;
      free_at = now_clock();  // the next span is accepted in the hand-over clock
    }
  }
  InterpStage stage_;
  int steps_;
};

class InterpBack : public Clocked {
 public:
  SC_HAS_PROCESS(InterpBack);
  sc_core::sc_fifo<HandTok>* hand = nullptr;
  sc_core::sc_fifo_out<SampleTok> out;
  InterpBack(sc_core::sc_module_name n, Shared& sh) : Clocked(n, sh, kInterpBack) {
    SC_THREAD(main);
    set_stack_size(kStack);
  }

 private:
  void main() {
    for (;;) {
      const HandTok h = hand->read();
      ++clk().in;
      uint64_t t = now_clock() + 1;  // the first sample, the clock after the hand-over
      for (const PlaneSample& p : *h.samples) {
        SampleTok s;
        s.ps = p;
        put(out, s, t);
        busy(now_clock(), now_clock() + 1);
        ++sh_.run->samples;
        t = now_clock() + 1;
      }
      // free for the next hand-over in the clock of its last sample
    }
  }
};

// Stage 8: fxr_depth. Accept thread: the queue (depth_queue_depth entries), the read-after-write
// hazard, the model's test in order; head thread: entries leave in order, one per clock, once
// their read is answered (DepthStage::head_clocks), passing ones into the output FIFO (2
// entries, the link to stage 9).
class DepthModule : public Clocked {
 public:
  SC_HAS_PROCESS(DepthModule);
  sc_core::sc_fifo_in<SampleTok> in;
  sc_core::sc_fifo_out<SampleTok> out;
  DepthModule(sc_core::sc_module_name n, Shared& sh, const Config& cfg, const ArchConfig& arch, const DrawState& st,
              FrameOutput& f)
      : Clocked(n, sh, kDepth),
        stage_(cfg, st, DepthBufferView{f.depth.data(), f.width, st.viewport_x, st.viewport_y}),
        queue_("queue", std::max(1, arch.depth_queue_depth - 1)),  // + the entry the head thread holds
        head_clocks_(DepthStage::head_clocks(arch.mem_latency)),
        test_(st.depth_test),
        hazards_(st.depth_test && st.depth_write),
        shared_port_(arch.depth_write_port == 0 && st.depth_test && st.depth_write),
        width_(f.width) {
    SC_THREAD(accept);
    set_stack_size(kStack);
    SC_THREAD(head);
    set_stack_size(kStack);
  }

 private:
  void accept() {
    uint64_t free_at = 0;
    for (;;) {
      SampleTok k = take(in, free_at);
      DepthEntry e;
      e.pixel = (int64_t)k.ps.y * (int64_t)width_ + k.ps.x;
      // Read-after-write: wait until the queued entry of this pixel has left.
      if (hazards_) {
        for (;;) {
          auto it = in_queue_.find(e.pixel);
          if (it == in_queue_.end() || it->second == 0) break;
          wait(left_);
        }
        const auto lt = left_at_.find(e.pixel);
        if (lt != left_at_.end()) wait_until(lt->second + 1);
      }
      // A port slot taken by a write (shared request port) delays the read.
      if (shared_port_) wait_until(port_free_);
      const uint64_t ta = now_clock();
      e.ps = k.ps;
      e.pass = stage_.step(k.ps, [](const PlaneSample&) {});
      e.head = ta + (uint64_t)(test_ ? head_clocks_ : 1);
      e.t = ta;
      if (hazards_) {
        ++in_queue_[e.pixel];
        e.hazard_tracked = true;
      }
      port_free_ = ta + 1;
      busy(ta, ta + 1);  // the memory port's read slot
      queue_.write(e);   // blocks while the queue is full
      free_at = now_clock() + 1;
    }
  }
  void head() {
    uint64_t next = 0;
    for (;;) {
      const DepthEntry e = queue_.read();
      wait_until(std::max(e.head, next));
      uint64_t leave = now_clock();
      if (e.pass) {
        ++sh_.run->passed;
        SampleTok s;
        s.ps = e.ps;
        // The write of a passing sample: in the clock it leaves (write channel or, shared, the
        // request port's slot, which the next read then waits for).
        if (shared_port_) port_free_ = std::max(port_free_, leave) + 1;
        put(out, s, leave + 1);
        leave = std::max(leave, now_clock() - 1);
      }
      // Occupied while the sample is in the queue or the output FIFO (the RTL's count registers:
      // from the clock after its input transfer to the clock its successor takes it).
      const uint64_t ob = std::max(e.t + 1, occ_end_), oe = leave + (e.pass ? 2 : 1);
      if (oe > ob) clk().occupied += oe - ob, occ_end_ = oe;
      if (e.hazard_tracked) {
        --in_queue_[e.pixel];
        left_at_[e.pixel] = leave;
        left_.notify(sc_core::SC_ZERO_TIME);
      }
      next = leave + 1;
    }
  }

  DepthStage stage_;
  sc_core::sc_fifo<DepthEntry> queue_;
  int head_clocks_;
  bool test_, hazards_, shared_port_;
  int width_;
  uint64_t port_free_ = 0, occ_end_ = 0;
  std::unordered_map<int64_t, int> in_queue_;
  std::unordered_map<int64_t, uint64_t> left_at_;
  sc_core::sc_event left_;
};

// Stage 9: fxr_divide, pipelined (divide_cost: latency, ii = groups of lanes). Its output is the
// unit's, taken every clock (the testbench's out_ready_i = 1), so it is not a link: a fragment
// leaves `latency` clocks after its input transfer and goes to the sink in order.
class DivideModule : public Clocked {
 public:
  SC_HAS_PROCESS(DivideModule);
  sc_core::sc_fifo_in<SampleTok> in;
  FragmentSink* sink = nullptr;
  DivideModule(sc_core::sc_module_name n, Shared& sh, const Config& cfg, const ArchConfig& arch, const DrawState& st)
      : Clocked(n, sh, kDivide), stage_(cfg, st, true),
        cost_(divide_cost(cfg, std::max(1, st.num_varyings), arch_divide_lanes(arch, st.num_varyings))) {
    SC_THREAD(accept);
    set_stack_size(kStack);
  }

 private:
  void accept() {
    uint64_t free_at = 0;
    for (;;) {
      const SampleTok k = take(in, free_at);
      const uint64_t ta = now_clock();
      stage_.step(k.ps, [&](const Fragment& f) {
        if (sink) sink->emit(f);
      });
      busy(ta, ta + (uint64_t)cost_.ii);
      ++clk().out;
      sh_.run->last_out = ta + (uint64_t)cost_.latency;
      free_at = ta + (uint64_t)cost_.ii;
    }
  }
  DivideStage stage_;
  StageCost cost_;
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
  sc_core::sc_fifo<HandTok> l_hand;
  sc_core::sc_fifo<SampleTok> l_sample, l_pass;
  EqFifo eq_fifo;
  SetupModule setup;
  TraverseModule traverse;
  InterpFront front;
  InterpBack back;
  DepthModule depth;
  DivideModule divide;

  Backend(CycleRun& run, const CycleOptions& opt, const Config& cfg, const ArchConfig& arch, const DrawState& st, FrameOutput& f,
          FragmentSink* out)
      : sh{&run, opt.timeline, opt.span_clocks},
        l_in("l_in", arch.link_depth),
        l_eq("l_eq", arch.link_depth),
        l_span("l_span", arch.link_depth),
        l_hand("l_hand", 1),
        l_sample("l_sample", arch.link_depth),
        l_pass("l_pass", std::max(2, arch.link_depth)),  // fxr_depth's 2-entry output FIFO
        eq_fifo(arch.tri_fifo_depth),
        setup("setup", sh, cfg, arch, st),
        traverse("traverse", sh, cfg, arch, st),
        front("interp_front", sh, cfg, arch, st),
        back("interp_back", sh),
        depth("depth", sh, cfg, arch, st, f),
        divide("divide", sh, cfg, arch, st) {
    setup.in(l_in);
    setup.out(l_eq);
    traverse.in(l_eq);
    traverse.out(l_span);
    traverse.eq_fifo = &eq_fifo;
    front.in(l_span);
    front.hand = &l_hand;
    front.eq_fifo = &eq_fifo;
    back.hand = &l_hand;
    back.out(l_sample);
    depth.in(l_sample);
    depth.out(l_pass);
    divide.in(l_pass);
    divide.sink = out;
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

// Stages 1–4 as one module: each primitive through fxr::GeometryChain (convert, clip, recip,
// viewport: the model's rule that a primitive is rejected whole), latency the sum of the four
// stages' cost(), one primitive per clock plus one clock per extra clipped piece.
class GeometryModule : public Clocked {
 public:
  SC_HAS_PROCESS(GeometryModule);
  sc_core::sc_fifo_out<TriTok> out;
  GeometryModule(sc_core::sc_module_name n, Shared& sh, const Config& cfg, const DrawState& st,
                 const std::vector<ClipTriangle>& prims)
      : Clocked(n, sh, kGeometry),
        chain_(cfg, st, taps_),
        prims_(prims),
        latency_(ConvertStage::cost(cfg).latency + ClipStage::cost(cfg).latency + RecipStage::cost(cfg).latency +
                 ViewportStage::cost(cfg).latency),
        pipe_("pipe", std::max(1, latency_ - 1)) {
    SC_THREAD(accept);
    set_stack_size(kStack);
    SC_THREAD(emit);
    set_stack_size(kStack);
  }

 private:
  void accept() {
    std::vector<SetupTriangle> pieces;
    RasterStats stats;
    InputTriangle in;
    uint64_t free_at = 0;
    for (size_t p = 0; p < prims_.size(); ++p) {
      wait_until(free_at);
      const uint64_t ta = now_clock();
      if (p == 0) sh_.run->first_in = ta;
      ++clk().in;
      ++sh_.run->primitives;
      in.prim = (uint32_t)p;
      in.tri = prims_[p];
      pieces.clear();
      chain_.run(in, pieces, stats);
      const uint64_t occ = std::max<uint64_t>(1, pieces.size());  // a clock per piece out
      busy(ta, ta + occ);
      for (size_t i = 0; i < pieces.size(); ++i) {
        tris_.push_back(pieces[i]);
        PipeTok k;
        k.tri = &tris_.back();
        k.t = ta + (uint64_t)latency_ + i;
        pipe_.write(k);  // blocks while the pipeline is full
      }
      free_at = std::max(ta + occ, now_clock());
    }
  }
  void emit() {
    for (;;) {
      const PipeTok p = pipe_.read();
      TriTok k;
      k.tri = p.tri;
      put(out, k, p.t);
    }
  }
  NoTaps taps_;
  GeometryChain<NoTaps> chain_;
  const std::vector<ClipTriangle>& prims_;
  int latency_ = 0;
  sc_core::sc_fifo<PipeTok> pipe_;
  std::deque<SetupTriangle> tris_;  // stable addresses for the tokens
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
  GeometryModule& geo = *new GeometryModule("geometry", b.sh, cfg, st, prims);
  geo.out(b.l_in);
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
