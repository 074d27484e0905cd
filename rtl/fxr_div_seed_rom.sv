// fxr_div_seed_rom: the recip_mul seed table (combinational ROM), computed at elaboration by a
// constant function that is the same formula as fxr::div_seed_table (model/arith/div.cpp):
//   entry i = RNE(2^(SeedBits+1) / (1 + (i + 1/2)*2^-SeedIndexBits)) - 2^SeedBits,
// clamped to 2^SeedBits - 1 (only i = 0 can round up to exactly 1.0). The implicit leading one
// is added back by the caller: y0 = (2^SeedBits + entry) * 2^-(SeedBits+1) in (1/2, 1].
// Exact integer arithmetic in 64 bits: SeedBits + SeedIndexBits + 2 <= 36 (param ranges 20, 14).
module fxr_div_seed_rom #(
  parameter int SeedIndexBits = 8,
  parameter int SeedBits      = 8
) (
  input  logic [SeedIndexBits-1:0] idx_i,
  output logic [SeedBits-1:0]      seed_o
);
  localparam int Entries = 1 << SeedIndexBits;

  function automatic logic [SeedBits-1:0] seed_entry(input int i);
    logic [63:0] num, den, q, r;
    num = 64'd1 << (SeedBits + 1 + SeedIndexBits + 1);
    den = (64'd1 << (SeedIndexBits + 1)) + 64'(2 * i + 1);
    q   = num / den;
    r   = num % den;
    if ((2 * r > den) || ((2 * r == den) && q[0])) q = q + 64'd1;
    q = q - (64'd1 << SeedBits);
    if (q >= (64'd1 << SeedBits)) q = (64'd1 << SeedBits) - 64'd1;
    seed_entry = q[SeedBits-1:0];  // (Yosys 0.23 does not parse `return`)
  endfunction

  // Two nested loops of at most 2^7 iterations each (Verilator refuses loops above 1024).
  localparam int InnerBits = (SeedIndexBits > 7) ? 7 : SeedIndexBits;
  localparam int Inner     = 1 << InnerBits;
  localparam int Outer     = Entries / Inner;

  logic [Entries*SeedBits-1:0] rom;
  for (genvar o = 0; o < Outer; o++) begin : gen_outer
    for (genvar n = 0; n < Inner; n++) begin : gen_entry
      localparam int                  I     = o * Inner + n;  // localparams: Icarus 11
      localparam int                  Lo    = I * SeedBits;
      localparam logic [SeedBits-1:0] Entry = seed_entry(I);
      assign rom[Lo +: SeedBits] = Entry;
    end
  end

  assign seed_o = rom[idx_i * SeedBits +: SeedBits];
endmodule
