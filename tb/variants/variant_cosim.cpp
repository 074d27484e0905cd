// Co-simulation of one unit at another parameter set (tb/variants/<unit>/<name>.json), built
// once per variant by tb/CMakeLists.txt (fxr_cosim_variant) with FXR_VARIANT_* naming the
// verilated class, the unit's Ports adapter, the test suite and the configuration file.
#include FXR_VARIANT_HEADER
#include FXR_VARIANT_PORTS_HEADER
#include "cosim_tests.hpp"

using VariantPorts = FXR_VARIANT_PORTS<FXR_VARIANT_DUT>;

FXR_VARIANT_TESTS(FXR_VARIANT_SUITE, VariantPorts, FXR_VARIANT_UNIT, FXR_VARIANT_NAME, FXR_VARIANT_CONFIG)

// The variant really is another parameter set: its configuration differs from the default in the
// unit's section (otherwise the variant would test nothing new).
TEST(FXR_VARIANT_SUITE, ConfigurationDiffersFromTheDefault) {
  const auto v = fxr::make_vector_model(FXR_VARIANT_UNIT, fxr::load_config(FXR_VARIANT_CONFIG));
  const auto d = fxr::make_vector_model(FXR_VARIANT_UNIT, fxr::Config{});
  EXPECT_NE(v->config_json(), d->config_json());
}
