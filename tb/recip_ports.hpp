// tb/recip_ports.hpp — how the reciprocal unit's vector fields map onto the ports of fxr_recip
// (any verilated parameter set: Dut is the Verilator class of that variant).
#pragma once

#include <string>
#include <vector>

#include "model/config/config.hpp"
#include "model/stages/recip.hpp"
#include "model/vectors/vectors.hpp"

template <class D>
struct RecipPorts {
  using Dut = D;
  static std::vector<std::string> fields() {
    return {"in_neg", "in_exp", "in_sig", "out_neg", "out_exp", "out_sig", "out_dbz", "out_ovf"};
  }
  static int latency(const fxr::Config& c) { return fxr::recip_cost(c.recip).latency; }
  static int ii(const fxr::Config& c) { return fxr::recip_cost(c.recip).ii; }
  static void drive(Dut& d, const fxr::VecRow& r) {
    d.in_neg_i = r[0];
    d.in_exp_i = r[1];
    d.in_sig_i = r[2];
  }
  static void sample(Dut& d, fxr::VecRow& r) {
    r[3] = d.out_neg_o;
    r[4] = d.out_exp_o;
    r[5] = d.out_sig_o;
    r[6] = d.out_dbz_o;
    r[7] = d.out_ovf_o;
  }
};
