// `fxraster config` and the other entry points refuse every invalid cross-field combination
// (model/config/validate.hpp): exit 2, the file and the field named, nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/tools/cli.hpp"

namespace fxr::test {
namespace {

struct BadConfig {
  const char* rule;
  const char* json;   // the configuration file
  const char* field;  // the field the error must name
};

// One violating combination per rule of config_rules(), and the issue's example.
const std::vector<BadConfig> kBad = {
    {"raster.edge_values_fit_int64", R"({"version": 1, "raster": {"window_int_bits": 20, "subpixel_bits": 11}})",
     "raster.window_int_bits"},
    {"raster.interp_sums_fit_int128",
     R"({"version": 1, "raster": {"window_int_bits": 20, "subpixel_bits": 11, "interp_block_bits": 62}})",
     "raster.interp_block_bits"},
    {"raster.depth_products_fit_int64", R"({"version": 1, "raster": {"z_frac_bits": 39}})", "raster.z_frac_bits"},
    {"raster.depth_sums_fit_int128",
     R"({"version": 1, "raster": {"window_int_bits": 20, "subpixel_bits": 11, "z_frac_bits": 38}})",
     "raster.z_frac_bits"},
    {"raster.attr_plane_sums_fit_int128", R"({"version": 1, "raster": {"attr_coord_bits": 40, "interp_block_bits": 43}})",
     "raster.attr_coord_bits"},
    {"recip.nr_frac_bits_above_output", R"({"version": 1, "recip": {"nr_frac_bits": 20}})", "recip.nr_frac_bits"},
    {"recip.seed_index_within_input", R"({"version": 1, "recip": {"in_sig_bits": 8, "seed_index_bits": 8}})",
     "recip.seed_index_bits"},
    {"div.iterative_needs_radix2", R"({"version": 1, "div": {"algorithm": "recip_mul", "schedule": "iterative"}})",
     "div.schedule"},
    {"div.quot_bits_derived", R"({"version": 1, "div": {"quot_bits": 20}})", "div.quot_bits"},
    {"tex_addr.sig_bits_derived", R"({"version": 1, "tex_addr": {"sig_bits": 20}})", "tex_addr.sig_bits"},
    {"issue example", R"({"version": 1, "recip": {"nr_frac_bits": 20}, "div": {"quot_bits": 20}})", "div.quot_bits"},
};

void expect_refused(const CliResult& r, const std::string& file, const std::string& field, const std::string& what) {
  EXPECT_EQ(r.exit, 2) << what << "\n" << r.err;
  EXPECT_NE(r.err.find(file), std::string::npos) << what << ": the file is not named:\n" << r.err;
  EXPECT_NE(r.err.find("field '" + field + "'"), std::string::npos) << what << ": the field is not named:\n" << r.err;
}

TEST(ConfigCli, EmitRefusesEveryInvalidCrossFieldCombination) {
  const std::string d = scratch();
  for (const BadConfig& b : kBad) {
    const std::string f = d + "/bad.json";
    write_file(f, b.json);
    for (const char* opt : {"--emit-sv", "--emit-json", "--emit-md"}) {
      const std::string out = d + "/out";
      std::filesystem::remove(out);
      const CliResult r = run_cli(d, "config --config '" + f + "' " + opt + " '" + out + "'");
      expect_refused(r, "bad.json", b.field, std::string(b.rule) + " " + opt);
      EXPECT_FALSE(std::filesystem::exists(out)) << b.rule << " " << opt << ": output written anyway";
    }
  }
}

TEST(ConfigCli, BoundaryConfigurationsAreEmitted) {
  const std::string d = scratch();
  // Each at the limit of its rule; the derived width follows its source.
  const std::vector<std::string> ok = {
      R"({"version": 1, "raster": {"window_int_bits": 20, "subpixel_bits": 10, "interp_block_bits": 62, "attr_coord_bits": 30}})",
      R"({"version": 1, "raster": {"attr_coord_bits": 40, "interp_block_bits": 42}})",
      R"({"version": 1, "raster": {"window_int_bits": 20, "subpixel_bits": 10, "z_frac_bits": 38}})",
      R"({"version": 1, "recip": {"nr_frac_bits": 25, "in_sig_bits": 8, "seed_index_bits": 7}})",
      R"({"version": 1, "div": {"schedule": "iterative"}})",
      R"({"version": 1, "raster": {"varying_out_sig_bits": 20}})",
  };
  for (const auto& j : ok) {
    write_file(d + "/ok.json", j);
    const CliResult r = run_cli(d, "config --config '" + d + "/ok.json' --emit-sv '" + d + "/pkg.sv'");
    EXPECT_EQ(r.exit, 0) << j << "\n" << r.err;
  }
  // The last one: the RTL's DivQuotBits follows raster.varying_out_sig_bits.
  EXPECT_NE(read_file(d + "/pkg.sv").find("localparam int DivQuotBits = 20;"), std::string::npos)
      << read_file(d + "/pkg.sv");
}

TEST(ConfigCli, VectorsAndRenderRefuseTheSameCombinations) {
  const std::string d = scratch();
  for (const BadConfig& b : kBad) {
    write_file(d + "/bad.json", b.json);
    expect_refused(run_cli(d, "vectors div --count 4 --config '" + d + "/bad.json' --out '" + d + "/v'"), "bad.json",
                   b.field, std::string("vectors ") + b.rule);
    expect_refused(run_cli(d, "render --default --no-bunny --width 16 --height 16 --quiet --config '" + d +
                                  "/bad.json' --out '" + d + "/r'"),
                   "bad.json", b.field, std::string("render ") + b.rule);
    EXPECT_FALSE(std::filesystem::exists(d + "/r/stats.json")) << b.rule;
  }
}

}  // namespace
}  // namespace fxr::test
