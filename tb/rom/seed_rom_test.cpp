// The RTL seed ROM (rtl/fxr_seed_rom.sv, computed at elaboration) equals the model's table
// (fxr::recip_core_seed_table through recip_seed_table / div_seed_table) at every address, for
// the configuration this binary was verilated with: built once per configuration by
// tb/CMakeLists.txt (fxr_seed_rom_test) with FXR_ROM_* naming the verilated probe
// (tb/rom/seed_rom_probe.sv), the suite and the configuration file ("" = the default).
#include <gtest/gtest.h>
#include <verilated.h>

#include <memory>
#include <string>

#include FXR_ROM_HEADER
#include "model/arith/div.hpp"
#include "model/config/config.hpp"
#include "model/stages/recip.hpp"

namespace {

fxr::Config rom_config() {
  const std::string path = FXR_ROM_CONFIG;
  return path.empty() ? fxr::Config{} : fxr::load_config(path);
}

struct Probe {
  std::unique_ptr<VerilatedContext> ctx = std::make_unique<VerilatedContext>();
  std::unique_ptr<FXR_ROM_DUT> dut;
  Probe() {
    ctx->fatalOnError(false);
    dut = std::make_unique<FXR_ROM_DUT>(ctx.get());
  }
  ~Probe() { dut->final(); }
};

}  // namespace

// Reads every address of one ROM of the probe (`read(dut, idx)` sets the index, evaluates and
// returns the entry) and compares it with the model's table; mismatch lines as tb/harness.hpp.
template <class T, class Read>
void expect_rom_equals(const char* unit, const std::vector<T>& table, Read&& read) {
  Probe p;
  uint64_t differ = 0;
  for (size_t i = 0; i < table.size(); ++i) {
    const uint64_t got = read(*p.dut, (uint32_t)i);
    if (got != (uint64_t)table[i] && differ++ < 20)
      ADD_FAILURE() << "MISMATCH " << unit << " seed idx=" << i << " rtl=" << got << " model=" << table[i];
  }
  EXPECT_FALSE(p.ctx->gotError());
  EXPECT_EQ(differ, 0u) << unit << " seed ROM: checked=" << table.size() << " errors=" << differ;
}

TEST(FXR_ROM_SUITE, ReciprocalSeedRomEqualsTheModelTable) {
  const fxr::Config cfg = rom_config();
  const std::vector<uint64_t> table = fxr::recip_seed_table(cfg.recip);
  ASSERT_EQ(table.size(), size_t{1} << cfg.recip.seed_index_bits);
  expect_rom_equals("recip", table, [](FXR_ROM_DUT& d, uint32_t i) {
    d.recip_idx_i = i;
    d.eval();
    return (uint64_t)d.recip_seed_o;
  });
}

TEST(FXR_ROM_SUITE, DividerSeedRomEqualsTheModelTable) {
  const fxr::Config cfg = rom_config();
  const std::vector<uint32_t> table = fxr::div_seed_table(cfg.div);
  ASSERT_EQ(table.size(), size_t{1} << cfg.div.seed_index_bits);
  expect_rom_equals("div", table, [](FXR_ROM_DUT& d, uint32_t i) {
    d.div_idx_i = i;
    d.eval();
    return (uint64_t)d.div_seed_o;
  });
}
