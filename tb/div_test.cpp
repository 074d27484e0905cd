// Co-simulation of rtl/fxr_div.sv (Verilator) against the model fxr::div_sig at the default
// configuration: committed and generated vectors, 10^6 lock-step random inputs, latency /
// throughput, lost outputs and a caught corruption (tb/cosim_tests.hpp). Other parameter sets:
// tb/variants/div/*.json.
#include "Vfxr_div.h"
#include "cosim_tests.hpp"
#include "div_ports_gen.hpp"  // generated: fxraster layout --emit-ports

FXR_COSIM_TESTS(Div, fxr::tb::gen::DivPortsGen<Vfxr_div>, "div", "out_sig", 3)
