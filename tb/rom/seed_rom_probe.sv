// seed_rom_probe: the two seed ROMs of one configuration side by side — the reciprocal unit's
// and the recip_mul divider's fxr_seed_rom, parameterised from fxr_config_pkg exactly as
// rtl/fxr_recip.sv and rtl/fxr_div_recip_mul.sv instantiate them. Verilated per configuration by
// tb/CMakeLists.txt (fxr_seed_rom_test); tb/rom/seed_rom_test.cpp reads every address.
module seed_rom_probe (
  input  logic [fxr_config_pkg::RecipSeedIndexBits-1:0] recip_idx_i,
  output logic [fxr_config_pkg::RecipSeedFracBits-1:0]  recip_seed_o,
  input  logic [fxr_config_pkg::DivSeedIndexBits-1:0]   div_idx_i,
  output logic [fxr_config_pkg::DivSeedBits-1:0]        div_seed_o
);
  fxr_seed_rom #(
    .SeedIndexBits(fxr_config_pkg::RecipSeedIndexBits),
    .SeedFracBits (fxr_config_pkg::RecipSeedFracBits)
  ) u_recip (
    .idx_i (recip_idx_i),
    .seed_o(recip_seed_o)
  );
  fxr_seed_rom #(
    .SeedIndexBits(fxr_config_pkg::DivSeedIndexBits),
    .SeedFracBits (fxr_config_pkg::DivSeedBits)
  ) u_div (
    .idx_i (div_idx_i),
    .seed_o(div_seed_o)
  );
endmodule
