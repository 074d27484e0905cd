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

TEST(FXR_ROM_SUITE, ReciprocalSeedRomEqualsTheModelTable) {
  const fxr::Config cfg = rom_config();
  const std::vector<uint64_t> table = fxr::recip_seed_table(cfg.recip);
  ASSERT_EQ(table.size(), size_t{1} << cfg.recip.seed_index_bits);
  Probe p;
  uint64_t differ = 0;
  for (size_t i = 0; i < table.size(); ++i) {
    p.dut->recip_idx_i = (uint32_t)i;
    p.dut->eval();
    if ((uint64_t)p.dut->recip_seed_o != table[i] && differ++ < 20)
      ADD_FAILURE() << "MISMATCH recip seed idx=" << i << " rtl=" << (uint64_t)p.dut->recip_seed_o
                    << " model=" << table[i];
  }
  EXPECT_FALSE(p.ctx->gotError());
  EXPECT_EQ(differ, 0u) << "recip seed ROM: checked=" << table.size() << " errors=" << differ;
}

TEST(FXR_ROM_SUITE, DividerSeedRomEqualsTheModelTable) {
  const fxr::Config cfg = rom_config();
  const std::vector<uint32_t> table = fxr::div_seed_table(cfg.div);
  ASSERT_EQ(table.size(), size_t{1} << cfg.div.seed_index_bits);
  Probe p;
  uint64_t differ = 0;
  for (size_t i = 0; i < table.size(); ++i) {
    p.dut->div_idx_i = (uint32_t)i;
    p.dut->eval();
    if ((uint32_t)p.dut->div_seed_o != table[i] && differ++ < 20)
      ADD_FAILURE() << "MISMATCH div seed idx=" << i << " rtl=" << (uint32_t)p.dut->div_seed_o
                    << " model=" << table[i];
  }
  EXPECT_FALSE(p.ctx->gotError());
  EXPECT_EQ(differ, 0u) << "div seed ROM: checked=" << table.size() << " errors=" << differ;
}
