// tb/backend/mixed_bench.hpp — the SystemC testbench of the mixed simulations (issue 12,
// docs/cycles.md "Mixed simulation"): an RTL top verilated with `--sc` (an SC_MODULE with sc_in /
// sc_out ports, sc_bv<N> for the record ports) driven clock by clock inside a SystemC simulation:
// reset, the draw state, the input records one offered per clock, every output taken, the depth
// memory (tb/depth_mem.hpp). Used by mixed_test.cpp (fxr_raster_backend) and mixed_unit_test.cpp
// (fxr_raster_unit). `Pins` is one sc_signal per DUT port, named as the port, with
// bind(dut, clock) and kRegs (true: the draw state goes through fxr_raster_unit's register
// block, one register per clock after reset; false: drive_draw_state's ports).
#pragma once

#include <systemc.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <vector>

#include "depth_mem.hpp"
#include "model/unit/io.hpp"
#include "model/unit/backend.hpp"
#include "model/vectors/record_vectors.hpp"
#include "txn/draw_state_ports.hpp"
#include "txn_harness.hpp"

namespace fxr::tb::mixed {

template <class P>
using PortT = typename std::remove_reference_t<P>::data_type;

// A packed record as 32-bit words (RecordBinding's port interface), copied to / from sc_bv.
template <int N>
struct Words {
  std::array<uint32_t, (N + 31) / 32> w{};
  uint32_t operator[](size_t i) const { return w[i]; }
  uint32_t& operator[](size_t i) { return w[i]; }
};
template <int N>
void to_bv(const Words<N>& w, sc_dt::sc_bv<N>& bv) {
  for (size_t i = 0; i < w.w.size(); ++i) bv.set_word((int)i, w.w[i]);
}
template <int N>
void from_bv(const sc_dt::sc_bv<N>& bv, Words<N>& w) {
  for (size_t i = 0; i < w.w.size(); ++i) w.w[i] = bv.get_word((int)i);
}
template <class T>
struct BvWidth;
template <int N>
struct BvWidth<sc_dt::sc_bv<N>> {
  static constexpr int value = N;
};

struct Collect : FragmentSink {
  std::vector<Fragment> v;
  void emit(const Fragment& f) override { v.push_back(f); }
};

// Reset, the draw state, then an input record offered per clock; every output taken. Drives in
// the clock's second half, samples the handshakes a quarter clock before the edge. Clocks are
// counted from the first input transfer to the last output; the run ends `drain` clocks after
// the last output once every input is in.
template <class Dut, class Pins>
SC_MODULE(Bench) {
  Pins pins;
  sc_core::sc_clock clk{"clk", 1, sc_core::SC_NS};
  Dut dut{"dut"};
  const std::vector<VecRow>* in_rows = nullptr;
  RecordBinding in_b, out_b;
  VecLayout out_lay;
  std::vector<VecRow> out_rows;
  DepthMem* mem = nullptr;
  DrawState st;
  int wib = 0;
  std::vector<int64_t> regs;  // Pins::kRegs: the register block's values, address = index
  uint64_t reg_mask = 0;
  uint64_t drain = 400;
  uint64_t cycle = 0, first_in = 0, last_out = 0, outputs = 0;
  bool done = false;

  SC_CTOR(Bench) {
    pins.bind(dut, clk);
    SC_THREAD(main);
  }
  uint64_t clocks() const { return outputs ? last_out - first_in + 1 : 0; }
  void main() {
    using InBv = PortT<decltype(dut.in_i)>;
    using OutBv = PortT<decltype(dut.out_o)>;
    constexpr int kIn = BvWidth<InBv>::value, kOut = BvWidth<OutBv>::value;
    if constexpr (!Pins::kRegs) drive_draw_state(pins, st, wib);
    pins.out_ready_i = true;
    pins.in_valid_i = false;
    pins.rst_ni = false;
    mem->reset();
    for (int i = 0; i < 4; ++i) wait(clk.posedge_event());
    wait(clk.negedge_event());
    pins.rst_ni = true;
    if constexpr (Pins::kRegs) {  // one register per clock, no input meanwhile
      for (size_t a = 0; a < regs.size(); ++a) {
        pins.reg_we_i = true;
        pins.reg_addr_i = (uint32_t)a;
        pins.reg_wdata_i = (uint32_t)((uint64_t)regs[a] & reg_mask);
        wait(clk.negedge_event());
      }
      pins.reg_we_i = false;
    }
    size_t next = 0;
    uint64_t idle = 0;
    Words<kIn> wi;
    Words<kOut> wo;
    InBv bv_in;
    OutBv bv_out;
    VecRow row(out_lay.size(), 0);
    for (;;) {
      // Drive for the coming edge.
      mem->drive(pins);
      const bool have = next < in_rows->size();
      if (have) {
        wi = Words<kIn>{};
        in_b.drive(wi, (*in_rows)[next]);
        to_bv(wi, bv_in);
        pins.in_i = bv_in;
      }
      pins.in_valid_i = have;
      wait(0.25, sc_core::SC_NS);  // combinational outputs settled
      if (have && pins.in_ready_o.read()) {
        if (next == 0) first_in = cycle;
        ++next;
      }
      if (pins.out_valid_o.read()) {
        from_bv(pins.out_o.read(), wo);
        out_b.sample(wo, row);
        out_rows.push_back(row);
        last_out = cycle;
        ++outputs;
        idle = 0;
      } else if (next == in_rows->size() && ++idle > drain) {
        break;  // drained
      }
      mem->observe(pins);
      wait(clk.negedge_event());
      ++cycle;
    }
    done = true;
    sc_core::sc_stop();
  }
};

// Runs a bench (a fresh kernel must be current, its modules built): wall clock seconds.
inline double run_bench() {
  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace fxr::tb::mixed
