// Co-simulation of rtl/fxr_setup_fields.sv (Verilator; the per-field core of fxr_setup) against the model's stage 5, fxr::SetupStage:
// committed and generated vectors, 10^6 lock-step random triangles, latency / throughput, lost
// outputs and a caught corruption (tb/cosim_tests.hpp). Vectors: model/vectors/setup_vectors.hpp.
#include "Vfxr_setup_fields.h"
#include "cosim_tests.hpp"
#include "setup_ports_gen.hpp"  // generated: fxraster layout --emit-ports

using SetupDefault = fxr::tb::gen::SetupPortsGen<Vfxr_setup_fields>;

FXR_COSIM_TESTS(Setup, SetupDefault, "setup", "num1_c", 100)  // a bit above 64: the wide ports
