// The whole unit (rtl/fxr_raster_unit.sv) verilated at another configuration
// (tb/variants/unit/<name>.json; built once per file by fxr_unit_variant in tb/CMakeLists.txt,
// FXR_UNIT_VARIANT_* naming the verilated class, the suite and the configuration file) against
// the model at the same file: the default scene, every file of scenes/ (their triangles, drawn at
// the variant's configuration instead of their own) and the clipped primitives of
// tests/model/piece_cases.hpp; fragments, final depth buffer and every counter equal (the checks
// of tb/unit/unit_check.hpp). docs/rtl.md, "fxr_raster_unit", unit variants.
#include FXR_UNIT_VARIANT_HEADER

#include <algorithm>
#include <filesystem>

#include "frontend/scene.hpp"
#include "model/config/config.hpp"
#include "tests/model/piece_cases.hpp"
#include "unit/unit_check.hpp"

namespace {

using Dut = FXR_UNIT_VARIANT_DUT;
using fxr::tb::Draw;
using fxr::tb::Handshake;
using fxr::tb::UnitRun;

const fxr::Config& variant_config() {
  static const fxr::Config c = fxr::load_config(FXR_UNIT_VARIANT_CONFIG);
  return c;
}

UnitRun run(const Draw& d, const Handshake& h, const std::string& name) {
  fxr::tb::RtlRunOptions<Dut> o;
  o.run = name;
  o.write_wave = false;
  return fxr::tb::run_unit<Dut>(d, d.u, h, o);
}

std::string run_name(const std::string& what) { return std::string("unit_") + FXR_UNIT_VARIANT_NAME + "_" + what; }

#if !FXR_UNIT_VARIANT_SCENES
// The variant really is another configuration.
TEST(FXR_UNIT_VARIANT_SUITE, ConfigurationDiffersFromTheDefault) {
  EXPECT_NE(fxr::config_to_json(variant_config()).dump(), fxr::config_to_json(fxr::Config{}).dump());
}

#else
// The default scene and scenes/ (labels rtl and slow: about 90 s).
TEST(FXR_UNIT_VARIANT_SUITE, DefaultSceneMatchesTheModel) {
  const fxr::Scene sc = fxr::default_scene();
  const Draw d = fxr::tb::model_draw(run_name("default"), variant_config(), sc.state, sc.tris);
  ASSERT_GT(d.fragments, 10000u);
  const UnitRun a = run(d, Handshake{1, 0, 0, 1, 1, 0}, d.name);
  fxr::tb::expect_match(d, a, d.name);
  fxr::tb::print_figures(d, a);
}

TEST(FXR_UNIT_VARIANT_SUITE, SceneFilesMatchTheModel) {
  int n = 0;
  for (const auto& p : fxr::tb::scene_files()) {
    const fxr::Scene sc = fxr::load_scene(p.string());
    if (sc.tris.empty()) continue;
    const Draw d = fxr::tb::model_draw(run_name(p.stem().string()), variant_config(), sc.state, sc.tris);
    const UnitRun a = run(d, Handshake{(uint64_t)(20 + n), n % 2 ? 20u : 0u, n % 2 ? 20u : 0u, 1, n % 2 ? 6u : 1u, 0},
                          d.name);
    fxr::tb::expect_match(d, a, d.name);
    fxr::tb::print_figures(d, a);
    ++n;
  }
  EXPECT_GE(n, 7);
}
#endif

// Clipped primitives whose pieces end differently, with gaps and back-pressure. When the
// variant's reciprocal range does not reach 2^160 (recip.exp_bits < 9) the through-the-eye
// primitive loses two of its three pieces in stage 3 and must still be drawn by the third (the
// per-piece rule, docs/pipeline.md): the case is reached, not only matched.
#if !FXR_UNIT_VARIANT_SCENES
TEST(FXR_UNIT_VARIANT_SUITE, ClippedPiecesMatchTheModel) {
  const Draw d = fxr::tb::model_draw(run_name("pieces"), variant_config(), fxr::piece_cases::state(),
                                     {fxr::piece_cases::through_the_eye(), fxr::piece_cases::near_into_the_band()});
  if (variant_config().recip.exp_bits < 9) {
    EXPECT_EQ(d.stats.tris.geom_rejected_range, 2u);
    EXPECT_EQ(d.stats.prims_drawn, 2u);
    EXPECT_EQ(d.stats.prims_rejected_range, 0u);
  }
  for (const Handshake& h : {Handshake{5, 0, 0, 1, 1, 0}, Handshake{6, 30, 30, 1, 5, 10}}) {
    const UnitRun a = run(d, h, d.name + "_" + std::to_string(h.seed));
    fxr::tb::expect_match(d, a, d.name + " seed " + std::to_string(h.seed));
  }
}

#endif

}  // namespace
