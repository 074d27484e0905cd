// Fuzz harness: the configuration reader (parse_json_input + config_from_json) and, for every
// configuration it accepts, the generators that consume it. Invariants: only ConfigError for bad
// input; an accepted configuration is valid, round-trips through JSON unchanged, and its SV
// package and Markdown tables are emitted without error.
#include <sstream>

#include "model/config/config.hpp"
#include "model/config/json_input.hpp"
#include "model/config/validate.hpp"
#include "tests/fuzz/fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fxr;
  const std::string text(reinterpret_cast<const char*>(data), size);
  fuzz::run_expecting_config_errors([&] {
    const Config c = config_from_json(parse_json_input(text, "fuzz.json"), "fuzz.json");
    validate(c, "accepted");  // throws ConfigError → finding below, as a non-valid accept
    const Config back = config_from_json(config_to_json(c), "round trip");
    fuzz::check(back == c && config_hash(back) == config_hash(c), "JSON round trip changed the configuration");
    std::ostringstream sv, md;
    emit_sv_package(sv, c);
    emit_md_tables(md, c);
    fuzz::check(sv.str().find("endpackage") != std::string::npos, "SV package incomplete");
  });
  return 0;
}
