// fxr_div: per-pixel significand divider, stage 9 (v = (v/w) / (1/w)).
// Model: fxr::div_sig (model/arith/div.hpp); docs/arith.md "# Divider".
//
// Function (every algorithm, round to nearest even; shared_recip rounds an approximate product):
//   num in [2^(NumBits-1), 2^NumBits), den in [2^(DenBits-1), 2^DenBits) (msb set):
//   (num*2^-(NumBits-1)) / (den*2^-(DenBits-1)) = sig*2^-(QuotBits-1)*2^exp_adj,
//   sig in [2^(QuotBits-1), 2^QuotBits); exp_adj in {-1, 0, +1} (+1 only when rounding carries out).
//   den == 0: out_dbz_o = 1, sig = all ones, exp_adj = 0. Else num == 0: sig = 0, exp_adj = 0.
//   Other operands with a clear msb: result unspecified (outside the contract).
//
// Ports:
//   clk_i, rst_ni                  clock, active-low asynchronous reset
//   in_valid_i / in_ready_o        input handshake (transfer when both are high)
//   in_num_i [NumBits]             numerator significand
//   in_den_i [DenBits]             denominator significand
//   out_valid_o / out_ready_i      output handshake
//   out_sig_o [QuotBits]           quotient significand
//   out_exp_adj_o [2]              exp_adj, two's complement: 2'b11 = -1, 2'b00 = 0, 2'b01 = +1
//   out_dbz_o                      division by zero (den == 0)
//
// Latency (cycles from the input transfer to out_valid_o, = fxr::div_cost().latency):
//   radix2: ceil((QuotBits - 1) / BitsPerStage) + 2 (25 at the default configuration);
//   II 1 pipelined (DivSchedulePipelined), ceil((QuotBits - 1) / BitsPerStage) + 1 iterative.
//   recip_mul: 2 * NrSteps + 4 (8 at NrSteps 2), II 1 (always pipelined).
//   shared_recip: 2 * NrSteps + 3 (7 at NrSteps 2), II 1 (fxr_div_shared_recip, one lane; not
//   correctly rounded: within fxr::div_bound()).
module fxr_div #(
  parameter int Algorithm      = fxr_config_pkg::DivAlgorithm,  // fxr_config_pkg::div_algorithm_e
  parameter int NumBits        = fxr_config_pkg::DivNumBits,
  parameter int DenBits        = fxr_config_pkg::DivDenBits,
  parameter int QuotBits       = fxr_config_pkg::DivQuotBits,
  parameter int SeedIndexBits  = fxr_config_pkg::DivSeedIndexBits,
  parameter int SeedBits       = fxr_config_pkg::DivSeedBits,
  parameter int NrSteps        = fxr_config_pkg::DivNrSteps,
  parameter int NrFracBits     = fxr_config_pkg::DivNrFracBits,
  parameter int BitsPerStage   = fxr_config_pkg::DivBitsPerStage,
  parameter int Schedule       = fxr_config_pkg::DivSchedule     // fxr_config_pkg::div_schedule_e
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                in_valid_i,
  output logic                in_ready_o,
  input  logic [NumBits-1:0]  in_num_i,
  input  logic [DenBits-1:0]  in_den_i,
  output logic                out_valid_o,
  input  logic                out_ready_i,
  output logic [QuotBits-1:0] out_sig_o,
  output logic [1:0]          out_exp_adj_o,
  output logic                out_dbz_o
);
  if (Algorithm == fxr_config_pkg::DivAlgorithmRadix2) begin : gen_radix2
    fxr_div_radix2 #(
      .NumBits     (NumBits),
      .DenBits     (DenBits),
      .QuotBits    (QuotBits),
      .BitsPerStage(BitsPerStage),
      .Schedule    (Schedule)
    ) u_radix2 (
      .clk_i        (clk_i),
      .rst_ni       (rst_ni),
      .in_valid_i   (in_valid_i),
      .in_ready_o   (in_ready_o),
      .in_num_i     (in_num_i),
      .in_den_i     (in_den_i),
      .out_valid_o  (out_valid_o),
      .out_ready_i  (out_ready_i),
      .out_sig_o    (out_sig_o),
      .out_exp_adj_o(out_exp_adj_o),
      .out_dbz_o    (out_dbz_o)
    );
  end else if (Algorithm == fxr_config_pkg::DivAlgorithmSharedRecip) begin : gen_shared_recip
    fxr_div_shared_recip #(
      .NumBits      (NumBits),
      .DenBits      (DenBits),
      .QuotBits     (QuotBits),
      .SeedIndexBits(SeedIndexBits),
      .SeedBits     (SeedBits),
      .NrSteps      (NrSteps),
      .NrFracBits   (NrFracBits),
      .Lanes        (1)
    ) u_shared_recip (
      .clk_i        (clk_i),
      .rst_ni       (rst_ni),
      .in_valid_i   (in_valid_i),
      .in_ready_o   (in_ready_o),
      .in_num_i     (in_num_i),
      .in_den_i     (in_den_i),
      .out_valid_o  (out_valid_o),
      .out_ready_i  (out_ready_i),
      .out_sig_o    (out_sig_o),
      .out_exp_adj_o(out_exp_adj_o),
      .out_dbz_o    (out_dbz_o)
    );
  end else begin : gen_recip_mul
    fxr_div_recip_mul #(
      .NumBits      (NumBits),
      .DenBits      (DenBits),
      .QuotBits     (QuotBits),
      .SeedIndexBits(SeedIndexBits),
      .SeedBits     (SeedBits),
      .NrSteps      (NrSteps),
      .NrFracBits   (NrFracBits)
    ) u_recip_mul (
      .clk_i        (clk_i),
      .rst_ni       (rst_ni),
      .in_valid_i   (in_valid_i),
      .in_ready_o   (in_ready_o),
      .in_num_i     (in_num_i),
      .in_den_i     (in_den_i),
      .out_valid_o  (out_valid_o),
      .out_ready_i  (out_ready_i),
      .out_sig_o    (out_sig_o),
      .out_exp_adj_o(out_exp_adj_o),
      .out_dbz_o    (out_dbz_o)
    );
  end

  // Parameters of the algorithm not instantiated are unused by design.
  /* verilator lint_off UNUSEDPARAM */
  localparam int UnusedParams = SeedIndexBits + SeedBits + NrSteps + NrFracBits + BitsPerStage +
                                Schedule;
  /* verilator lint_on UNUSEDPARAM */
endmodule
