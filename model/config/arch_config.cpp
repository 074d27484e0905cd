// The micro-architecture knobs. Contract in model/config/arch_config.hpp.
#include "model/config/arch_config.hpp"

#include <algorithm>

#include "model/config/json_input.hpp"

namespace fxr {

namespace {
bool pow2(int v) { return v > 0 && (v & (v - 1)) == 0; }
}  // namespace

void validate_arch(const ArchConfig& a, const std::string& where) {
  if (!pow2(a.tri_fifo_depth))
    throw ConfigError(where + ": field 'arch.tri_fifo_depth': " + std::to_string(a.tri_fifo_depth) +
                      " is not a power of two (the FIFO's pointers wrap)");
  if (!pow2(a.depth_queue_depth))
    throw ConfigError(where + ": field 'arch.depth_queue_depth': " + std::to_string(a.depth_queue_depth) +
                      " is not a power of two (the queue's pointers wrap)");
}

int arch_divide_lanes(const ArchConfig& a, int num_varyings) {
  const int nv = std::max(1, num_varyings);
  return a.divide_lanes == 0 ? nv : std::min(a.divide_lanes, nv);
}

nlohmann::json arch_to_json(const ArchConfig& a) { return to_json_params(a); }

ArchConfig arch_from_json(const nlohmann::json& j, const std::string& where) {
  ArchConfig a;
  from_json_params(j, a, where + ": /arch");
  validate_arch(a, where);
  return a;
}

std::pair<Config, ArchConfig> load_config_with_arch(const std::string& path) {
  nlohmann::json j = read_json_file(path, "configuration file");
  ArchConfig a;
  if (j.is_object() && j.contains("arch")) {
    a = arch_from_json(j.at("arch"), path);
    j.erase("arch");
  }
  return {config_from_json(j, path), a};
}

void emit_arch_md_table(std::ostream& os, const ArchConfig& a) {
  os << "### `arch` (micro-architecture: clocks only, never values)\n\n"
        "Read by the cycle model (`fxraster cycles`, docs/cycles.md) from the unit `arch` of a\n"
        "configuration file; the defaults are rtl/fxr_raster_backend.sv's parameters. Not part of the\n"
        "number formats (not in vector manifests, not in fxr_config_pkg). Rules: `tri_fifo_depth` and\n"
        "`depth_queue_depth` are powers of two.\n\n";
  emit_md_params(os, param_rows(a));
  os << "\n";
}

}  // namespace fxr
