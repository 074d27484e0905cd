// tb/div_ports.hpp — how the divider's vector fields map onto the ports of fxr_div (any
// verilated parameter set: Dut is the Verilator class of that variant).
#pragma once

#include <string>
#include <vector>

#include "model/config/config.hpp"
#include "model/arith/div.hpp"
#include "model/vectors/vectors.hpp"

template <class D>
struct DivPorts {
  using Dut = D;
  static std::vector<std::string> fields() { return {"in_num", "in_den", "out_sig", "out_exp_adj", "out_dbz"}; }
  static int latency(const fxr::Config& c) { return fxr::div_cost(c.div).latency; }
  static int ii(const fxr::Config& c) { return fxr::div_cost(c.div).ii; }
  static void drive(Dut& d, const fxr::VecRow& r) {
    d.in_num_i = r[0];
    d.in_den_i = r[1];
  }
  static void sample(Dut& d, fxr::VecRow& r) {
    r[2] = d.out_sig_o;
    r[3] = d.out_exp_adj_o;
    r[4] = d.out_dbz_o;
  }
};
