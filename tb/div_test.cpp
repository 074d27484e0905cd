// Co-simulation of rtl/fxr_div.sv (Verilator) against the model fxr::div_sig: committed and
// generated vectors, 10^6 lock-step random inputs, latency / throughput, a caught corruption.
#include "Vfxr_div.h"
#include "cosim_tests.hpp"
#include "fxr/div.hpp"

namespace {

struct DivPorts {
  using Dut = Vfxr_div;
  static std::vector<std::string> fields() { return {"in_num", "in_den", "out_sig", "out_exp_adj", "out_dbz"}; }
  static int latency() { return fxr::div_cost(fxr::Config{}.div).latency; }
  static int ii() { return fxr::div_cost(fxr::Config{}.div).ii; }
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

}  // namespace

FXR_COSIM_TESTS(Div, DivPorts, "div", "out_sig", 3)
