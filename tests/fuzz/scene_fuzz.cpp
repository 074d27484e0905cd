// Fuzz harness: the scene parser (frontend/scene.cpp). Invariants: only ConfigError for bad input;
// an accepted scene has a viewport in range and every triangle's varyings within the count.
#include "frontend/scene.hpp"
#include "tests/fuzz/fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fxr;
  const std::string text(reinterpret_cast<const char*>(data), size);
  SceneOptions opt;
  opt.no_optional = true;  // optional meshes (the bunny) are not part of the input under test
  fuzz::run_expecting_config_errors([&] {
    const Scene sc = parse_scene(text, "fuzz.json", "", opt);
    fuzz::check(sc.state.viewport_w >= 1 && sc.state.viewport_h >= 1, "empty viewport accepted");
    fuzz::check(sc.state.num_varyings >= 0 && sc.state.num_varyings <= kMaxVaryings, "varying count out of range");
    fuzz::check(sc.u_varying < sc.state.num_varyings && sc.v_varying < sc.state.num_varyings,
                "texture coordinate varying beyond the count");
  });
  return 0;
}
