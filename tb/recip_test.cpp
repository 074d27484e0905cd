// Co-simulation of rtl/fxr_recip.sv (Verilator) against the model fxr::recip: committed and
// generated vectors, 10^6 lock-step random inputs, every significand, latency / throughput, lost
// outputs and a caught corruption (tb/cosim_tests.hpp). Other parameter sets: tb/variants/recip/.
#include "Vfxr_recip.h"
#include "cosim_tests.hpp"
#include "recip_ports_gen.hpp"  // generated: fxraster layout --emit-ports

using RecipDefault = fxr::tb::gen::RecipPortsGen<Vfxr_recip>;

FXR_COSIM_TESTS(Recip, RecipDefault, "recip", "out_sig", 0)

// The significand datapath sees only the significand: all 2^(n−1) of them at exponent 0, one per
// clock (no gaps or stalls: this is a proof by enumeration, not a handshake test).
TEST(Recip, RtlMatchesModelForAllSignificands) {
  const auto m = fxr::make_vector_model("recip", fxr::Config{});
  const uint64_t n = m->exhaustive_count();
  ASSERT_GT(n, 0u);
  fxr::tb::HarnessOptions o;
  o.unit = "recip";
  o.run_name = "recip_exhaustive";
  o.in_gap_pct = 0;
  o.out_stall_pct = 0;
  const auto r = fxr::tb::run<RecipDefault>(m->layout(), fxr::tb::exhaustive_source(*m), o);
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.checked, n);
}
