// tb/depth_mem.hpp — the depth buffer behind rtl/fxr_depth.sv's memory port, for Verilator
// testbenches (docs/rtl.md, "fxr_depth"): a w × h array of codes cleared to the model's clear
// value (the maximum code, model/unit/backend.hpp), requests performed in the order they are
// accepted (a read returns the value after every earlier accepted write), read responses in
// request order after a seeded random latency, and seeded random request back-pressure.
//
// Protocol per clock, as fxr_depth's ports: the memory drives mem_req_ready_i, mem_rsp_valid_i
// and mem_rsp_rdata_i (begin of the cycle, drive()), the DUT its request; at the edge
// (observe()) a request with valid and ready is performed, and an offered response is consumed
// (the DUT always takes it). Latency L (min_latency ≤ L ≤ max_latency, L ≥ 1): a read accepted in
// cycle t is offered from cycle t + L on, and not before the previous response (one per clock).
// A request outside the buffer is counted in bad_addresses (and reads 0).
//
// A second channel for writes (fxr_depth's WritePort = 1: mem_wr_valid_o / mem_wr_ready_i /
// mem_wr_addr_o / mem_wr_data_o) has its own seeded back-pressure (wr_stall_pct); a write on it
// is performed before a read accepted in the same clock.
//
// The plain interface (req_ready / rsp_valid / rsp_data / wr_ready / end_cycle) serves a DUT whose
// port names differ; drive() / observe() connect the port names of fxr_depth (mem_req_*,
// mem_rsp_*, and mem_wr_* when the DUT has them).
#pragma once

#include <cstdint>
#include <deque>
#include <random>
#include <type_traits>
#include <vector>

namespace fxr::tb {

struct DepthMemOptions {
  uint64_t seed = 1;
  unsigned min_latency = 1, max_latency = 1;  // clocks from the accepting edge to the response
  unsigned req_stall_pct = 0;                 // cycles with mem_req_ready low
  unsigned wr_stall_pct = 0;                  // cycles with mem_wr_ready low (write channel)
};

template <class D, class = void>
struct HasWriteChannel : std::false_type {};
template <class D>
struct HasWriteChannel<D, std::void_t<decltype(std::declval<D&>().mem_wr_valid_o)>> : std::true_type {};

class DepthMem {
 public:
  DepthMem(size_t words, uint32_t clear, DepthMemOptions o) : words_(words), clear_(clear), o_(o) {
    if (o_.min_latency < 1) o_.min_latency = 1;
    if (o_.max_latency < o_.min_latency) o_.max_latency = o_.min_latency;
    reset();
  }

  // Back to the cleared buffer, no responses pending, the random sequence from the start.
  void reset() {
    mem_.assign(words_, clear_);
    pending_.clear();
    rng_.seed(o_.seed);
    now_ = 0;
    last_due_ = 0;
    reads = writes = bad_addresses = 0;
    max_pending = 0;
    begin_cycle();
  }

  // The memory's outputs for the current cycle (stable until end_cycle()).
  bool req_ready() const { return req_ready_; }
  bool wr_ready() const { return wr_ready_; }
  bool rsp_valid() const { return !pending_.empty() && pending_.front().due <= now_; }
  uint32_t rsp_data() const { return rsp_valid() ? pending_.front().data : 0u; }

  // The clock edge: the request of this cycle (when req_fire) and the response taken.
  void end_cycle(bool req_fire, bool write, uint64_t addr, uint32_t wdata, bool wr_fire = false,
                 uint64_t wr_addr = 0, uint32_t wr_data = 0) {
    if (rsp_valid()) pending_.pop_front();
    if (wr_fire) {
      ++writes;
      if (wr_addr < mem_.size()) mem_[wr_addr] = wr_data;
      else ++bad_addresses;
    }
    if (req_fire) {
      const bool ok = addr < mem_.size();
      if (!ok) ++bad_addresses;
      if (write) {
        ++writes;
        if (ok) mem_[addr] = wdata;
      } else {
        ++reads;
        const unsigned span = o_.max_latency - o_.min_latency + 1;
        uint64_t due = now_ + o_.min_latency + (span > 1 ? rng_() % span : 0);
        if (due <= last_due_) due = last_due_ + 1;  // in order, one per clock
        last_due_ = due;
        pending_.push_back({due, ok ? mem_[addr] : 0u});
        if (pending_.size() > max_pending) max_pending = pending_.size();
      }
    }
    ++now_;
    begin_cycle();
  }

  // fxr_depth's port names.
  template <class Dut>
  void drive(Dut& d) const {
    d.mem_req_ready_i = req_ready();
    d.mem_rsp_valid_i = rsp_valid();
    d.mem_rsp_rdata_i = rsp_data();
    if constexpr (HasWriteChannel<Dut>::value) d.mem_wr_ready_i = wr_ready();
  }
  template <class Dut>
  void observe(const Dut& d) {
    bool wr_fire = false;
    uint64_t wr_addr = 0;
    uint32_t wr_data = 0;
    if constexpr (HasWriteChannel<Dut>::value) {
      wr_fire = d.mem_wr_valid_o && d.mem_wr_ready_i;
      wr_addr = (uint64_t)d.mem_wr_addr_o;
      wr_data = (uint32_t)d.mem_wr_data_o;
    }
    end_cycle(d.mem_req_valid_o && d.mem_req_ready_i, d.mem_req_write_o, (uint64_t)d.mem_req_addr_o,
              (uint32_t)d.mem_req_wdata_o, wr_fire, wr_addr, wr_data);
  }

  const std::vector<uint32_t>& words() const { return mem_; }
  uint64_t reads = 0, writes = 0, bad_addresses = 0, max_pending = 0;

 private:
  struct Rsp {
    uint64_t due;
    uint32_t data;
  };
  void begin_cycle() {
    req_ready_ = o_.req_stall_pct == 0 || (rng_() % 100) >= o_.req_stall_pct;
    wr_ready_ = o_.wr_stall_pct == 0 || (rng_() % 100) >= o_.wr_stall_pct;
  }

  size_t words_;
  uint32_t clear_;
  DepthMemOptions o_;
  std::vector<uint32_t> mem_;
  std::deque<Rsp> pending_;
  std::mt19937_64 rng_;
  uint64_t now_ = 0, last_due_ = 0;
  bool req_ready_ = true, wr_ready_ = true;
};

}  // namespace fxr::tb
