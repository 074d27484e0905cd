// Co-simulation of rtl/fxr_texaddr.sv (Verilator) against the model fxr::texaddr: committed and
// generated vectors, lock-step random inputs, latency / throughput, lost outputs and a caught
// corruption (tb/cosim_tests.hpp). Rules: docs/texaddr.md.
#include "Vfxr_texaddr.h"
#include "cosim_tests.hpp"
#include "texaddr_ports_gen.hpp"  // generated: fxraster layout --emit-ports

using TexaddrDefault = fxr::tb::gen::TexaddrPortsGen<Vfxr_texaddr>;

FXR_COSIM_TESTS(Texaddr, TexaddrDefault, "texaddr", "s_w", 0)

// Whole scenes (docs/texaddr.md, "Co-simulation on scenes"): every fragment `fxraster render`
// shades through the unit — its texture coordinates from the divider, the scene's texture size —
// under both filters and all four wrap modes, written at build time by `fxraster vectors texaddr
// SCENE|--default` (outputs from the model), through the RTL with gaps and back-pressure.
TEST(TexaddrScene, DefaultSceneFragmentsMatchTheModel) {
  const std::string hex = fxr::tb::binary_path("vectors/texaddr_scene_default/texaddr.hex");
  const fxr::VecFile f = fxr::read_vectors(hex, nullptr);
  ASSERT_GT(f.rows(), 8u * 50000u);  // 73,494 fragments x 8 at the default size
  ASSERT_EQ(f.rows() % 8, 0u);
  const auto r = fxr::tb::run_file<TexaddrDefault>("texaddr", hex, "texaddr_scene_default");
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.checked, f.rows());
}
TEST(TexaddrScene, TextureBorderSceneFragmentsMatchTheModel) {
  const std::string hex = fxr::tb::binary_path("vectors/texaddr_scene_border/texaddr.hex");
  const fxr::VecFile f = fxr::read_vectors(hex, nullptr);
  ASSERT_GT(f.rows(), 8u * 10000u);
  const auto r = fxr::tb::run_file<TexaddrDefault>("texaddr", hex, "texaddr_scene_border");
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.checked, f.rows());
}
