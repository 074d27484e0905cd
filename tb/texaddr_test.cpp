// Co-simulation of rtl/fxr_texaddr.sv (Verilator) against the model fxr::texaddr: committed and
// generated vectors, lock-step random inputs, latency / throughput, lost outputs and a caught
// corruption (tb/cosim_tests.hpp). Rules: docs/texaddr.md.
#include "Vfxr_texaddr.h"
#include "cosim_tests.hpp"
#include "texaddr_ports_gen.hpp"  // generated: fxraster layout --emit-ports

using TexaddrDefault = fxr::tb::gen::TexaddrPortsGen<Vfxr_texaddr>;

FXR_COSIM_TESTS(Texaddr, TexaddrDefault, "texaddr", "s_w", 0)
