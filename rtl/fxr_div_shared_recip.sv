// fxr_div_shared_recip: one reciprocal of the denominator, Lanes numerators multiplied by it, each
// product rounded once (RNE); fully pipelined (one operand set per clock). The divider algorithm
// shared_recip (div.algorithm): fxr_div instantiates it with Lanes = 1, fxr_divide (stage 9) with
// one lane per varying it divides in a clock. Implements fxr::div_recip + fxr::div_mul_round
// (model/arith/div.cpp) bit for bit; docs/arith.md "shared_recip". Not correctly rounded: the
// error bound is fxr::div_bound().
//
// Function, per lane l (num_l in [2^(NumBits-1), 2^NumBits) or 0, den in [2^(DenBits-1), 2^DenBits)
// or 0): a = num_l << (W - NumBits), b = den << (W - DenBits), k = (a < b), a' = a << k;
// y = the reciprocal core's approximation of 1/bn (bn = b*2^-(W-1)) at NrFracBits fraction bits;
// P = a'*y (exact), q = floor(P / 2^QShift) and RNE on the dropped bits; clamps into
// [2^(QuotBits-1), 2^QuotBits] (only an inaccurate reciprocal reaches them); 2^QuotBits
// renormalises. den == 0: out_dbz_o, every sig all ones, exp_adj 0; num_l == 0: sig 0, exp_adj 0.
//
// Ports: as fxr_div, with Lanes numerators and results (lane l at [l*Width +: Width]).
//
// Register stages (latency = 2 * NrSteps + 3 = fxr::div_cost for shared_recip):
//   0            align, compare (per lane), seed ROM (fxr_seed_rom) -> y0
//   2i+1, 2i+2   Newton-Raphson step i (fxr_nr_step, the core shared with fxr_recip)
//   2N+1         per lane P = a' * y: q = P >> QShift, round bit, sticky
//   output       clamps, RNE and renormalisation (fxr_round)
// The whole pipeline stalls while out_valid_o && !out_ready_i.
module fxr_div_shared_recip #(
  parameter int NumBits       = 32,
  parameter int DenBits       = 32,
  parameter int QuotBits      = 24,
  parameter int SeedIndexBits = 8,
  parameter int SeedBits      = 8,
  parameter int NrSteps       = 2,
  parameter int NrFracBits    = 28,
  parameter int Lanes         = 1
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  input  logic                      in_valid_i,
  output logic                      in_ready_o,
  input  logic [Lanes*NumBits-1:0]  in_num_i,
  input  logic [DenBits-1:0]        in_den_i,
  output logic                      out_valid_o,
  input  logic                      out_ready_i,
  output logic [Lanes*QuotBits-1:0] out_sig_o,
  output logic [Lanes*2-1:0]        out_exp_adj_o,
  output logic                      out_dbz_o
);
  localparam int W      = (NumBits > DenBits) ? NumBits : DenBits;  // div_align_bits
  localparam int F      = NrFracBits;
  localparam int YBits  = F;                      // y < 1 (one-sided after a step; truncated seed)
  localparam int QShift = W + F - QuotBits;       // product bits below the quotient's lsb
  localparam int PBits  = W + 1 + YBits;          // a' * y, exact
  localparam int QBits  = QuotBits + 2;           // floor(P / 2^QShift) < 2^(QuotBits+1)
  localparam int StQ    = 2 * NrSteps + 1;        // stage of q (registers before the output one)
  localparam int SeedW  = SeedBits + 1;

  logic out_free;  // the whole pipeline advances this cycle
  assign in_ready_o = out_free;

  // ---- stage 0: align, compare, seed ----------------------------------------------------------
  logic [W-1:0]             b;
  logic [Lanes*(W+1)-1:0]   a1;
  logic [Lanes-1:0]         k, nz;
  logic [SeedIndexBits-1:0] idx;
  logic [SeedBits-1:0]      seed_frac;

  for (genvar l = 0; l < Lanes; l++) begin : gen_align
    logic [W-1:0] a, bl;
    fxr_div_align #(
      .NumBits(NumBits),
      .DenBits(DenBits)
    ) u_align (
      .num_i(in_num_i[l*NumBits +: NumBits]),
      .den_i(in_den_i),
      .a_o  (a),
      .b_o  (bl)
    );
    if (l == 0) begin : gen_b
      assign b = bl;
    end else begin : gen_b_unused
      logic unused_b;  // the same b in every lane
      assign unused_b = ^bl;
    end
    assign k[l]                 = a < b;
    assign a1[l*(W+1) +: W+1]   = k[l] ? {a, 1'b0} : {1'b0, a};
    assign nz[l]                = in_num_i[l*NumBits +: NumBits] == '0;
  end

  if (W - 1 >= SeedIndexBits) begin : gen_idx
    assign idx = b[W-2 -: SeedIndexBits];
  end else begin : gen_idx_ext
    assign idx = {b[W-2:0], {(SeedIndexBits - (W - 1)){1'b0}}};
  end
  fxr_seed_rom #(
    .SeedIndexBits(SeedIndexBits),
    .SeedFracBits (SeedBits)
  ) u_rom (
    .idx_i (idx),
    .seed_o(seed_frac)
  );

  // ---- pass-through registers (stage s at [s*Width +: Width]) ---------------------------------
  localparam int AW = Lanes * (W + 1);
  logic [(StQ)*AW-1:0]         a1_q;  // stages 0 .. 2N (read by the product at 2N)
  /* verilator lint_off UNUSEDSIGNAL */  // the NR steps read stages 0 .. 2N-2
  logic [(StQ)*W-1:0]          b_q;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [StQ:0]                v_q, dbz_q;
  logic [(StQ+1)*Lanes-1:0]    k_q, nz_q;
  logic [SeedW-1:0]            y0_q;
  wire  [(NrSteps+1)*YBits-1:0] y_s;  // y after step i (slot 0: y0 at F bits, for NrSteps 0)

  if (F > SeedW) begin : gen_y0_widen
    assign y_s[0 +: YBits] = YBits'({y0_q, {(F - SeedW){1'b0}}});
  end else if (F == SeedW) begin : gen_y0_same
    assign y_s[0 +: YBits] = y0_q;
  end else begin : gen_y0_trunc  // precision lost: the seed truncated to F bits
    assign y_s[0 +: YBits] = YBits'(y0_q >> (SeedW - F));
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      v_q <= '0;
    end else if (out_free) begin
      v_q <= {v_q[StQ-1:0], in_valid_i};
    end
  end
  always_ff @(posedge clk_i) begin
    if (out_free) begin
      dbz_q <= {dbz_q[StQ-1:0], in_den_i == '0};
      k_q   <= {k_q[StQ*Lanes-1:0], k};
      nz_q  <= {nz_q[StQ*Lanes-1:0], nz};
      y0_q  <= {1'b1, seed_frac};
    end
  end
  if (StQ > 1) begin : gen_pass
    always_ff @(posedge clk_i) begin
      if (out_free) begin
        a1_q <= {a1_q[(StQ-1)*AW-1:0], a1};
        b_q  <= {b_q[(StQ-1)*W-1:0], b};
      end
    end
  end else begin : gen_pass1
    always_ff @(posedge clk_i) begin
      if (out_free) begin
        a1_q <= a1;
        b_q  <= b;
      end
    end
  end

  if (NrSteps > 0) begin : gen_y0_unused
    logic unused_y0;  // the first step reads y0_q directly
    assign unused_y0 = ^y_s[0 +: YBits];
  end

  // ---- Newton-Raphson steps ---------------------------------------------------------------------
  for (genvar i = 0; i < NrSteps; i++) begin : gen_nr
    localparam int SA = 2 * i;
    if (i == 0) begin : gen_first
      fxr_nr_step #(
        .XBits    (W),
        .YFracBits(SeedW),
        .FracBits (F)
      ) u_step (
        .clk_i(clk_i),
        .en_i (out_free),
        .act_i(|v_q),
        .x_i  (b_q[SA*W +: W]),
        .y_i  (y0_q),
        .y_o  (y_s[YBits +: YBits])
      );
    end else begin : gen_next
      fxr_nr_step #(
        .XBits    (W),
        .YFracBits(F),
        .FracBits (F)
      ) u_step (
        .clk_i(clk_i),
        .en_i (out_free),
        .act_i(|v_q),
        .x_i  (b_q[SA*W +: W]),
        .y_i  (y_s[i*YBits +: YBits]),
        .y_o  (y_s[(i+1)*YBits +: YBits])
      );
    end
  end

  // ---- per lane: the product, its floor and rounding flags (stage 2N -> 2N+1) ------------------
  logic [YBits-1:0]       y;
  logic [Lanes*QBits-1:0] q_q;
  logic [Lanes-1:0]       rb_q, st_q;  // round bit, sticky
  assign y = y_s[NrSteps*YBits +: YBits];
  for (genvar l = 0; l < Lanes; l++) begin : gen_mul
    logic [PBits-1:0] prod;
    logic [QBits-1:0] q;
    logic             rb, st;
    assign prod = PBits'(a1_q[(StQ-1)*AW + l*(W+1) +: W+1]) * PBits'(y);
    if (QShift > 1) begin : gen_shr
      assign q  = QBits'(prod >> QShift);
      assign rb = prod[QShift-1];
      assign st = |prod[QShift-2:0];
    end else if (QShift == 1) begin : gen_shr1
      assign q  = QBits'(prod >> 1);
      assign rb = prod[0];
      assign st = 1'b0;
    end else begin : gen_shl  // exact: no bits dropped
      assign q  = QBits'(prod) << (-QShift);
      assign rb = 1'b0;
      assign st = 1'b0;
    end
    always_ff @(posedge clk_i) begin
      if (out_free) begin
        q_q[l*QBits +: QBits] <= q;
        rb_q[l]               <= rb;
        st_q[l]               <= st;
      end
    end
  end

  // ---- output: clamps, RNE, renormalisation, special cases --------------------------------------
  localparam logic [QBits-1:0] QLo = QBits'(1) << (QuotBits - 1);
  localparam logic [QBits-1:0] QHi = QBits'(1) << QuotBits;
  logic                      out_valid_q, out_dbz_q;
  logic [Lanes*QuotBits-1:0] out_sig_q;
  logic [Lanes*2-1:0]        out_exp_q;
  assign out_free      = ~out_valid_q | out_ready_i;
  assign out_valid_o   = out_valid_q;
  assign out_sig_o     = out_sig_q;
  assign out_exp_adj_o = out_exp_q;
  assign out_dbz_o     = out_dbz_q;

  for (genvar l = 0; l < Lanes; l++) begin : gen_out
    logic [QBits-1:0]    qf;
    logic                kl;
    logic [QuotBits-1:0] sig_rnd;
    logic [1:0]          exp_rnd;
    assign qf = q_q[l*QBits +: QBits];
    assign kl = k_q[StQ*Lanes + l];
    fxr_round #(
      .QuotBits(QuotBits)
    ) u_round (
      .q_i      (qf[QuotBits-1:0]),
      .t_neg_i  (~rb_q[l]),
      .t_zero_i (rb_q[l] & ~st_q[l]),
      .k_i      (kl),
      .sig_o    (sig_rnd),
      .exp_adj_o(exp_rnd)
    );
    always_ff @(posedge clk_i) begin
      if (out_free && v_q[StQ]) begin
        if (dbz_q[StQ]) begin
          out_sig_q[l*QuotBits +: QuotBits] <= '1;
          out_exp_q[l*2 +: 2]               <= 2'b00;
        end else if (nz_q[StQ*Lanes + l]) begin
          out_sig_q[l*QuotBits +: QuotBits] <= '0;
          out_exp_q[l*2 +: 2]               <= 2'b00;
        end else if (qf < QLo) begin  // clamp: an inaccurate reciprocal only
          out_sig_q[l*QuotBits +: QuotBits] <= QLo[QuotBits-1:0];
          out_exp_q[l*2 +: 2]               <= kl ? 2'b11 : 2'b00;
        end else if (qf >= QHi) begin  // 2^QuotBits (renormalised) or clamped to it
          out_sig_q[l*QuotBits +: QuotBits] <= QLo[QuotBits-1:0];
          out_exp_q[l*2 +: 2]               <= kl ? 2'b00 : 2'b01;
        end else begin
          out_sig_q[l*QuotBits +: QuotBits] <= sig_rnd;
          out_exp_q[l*2 +: 2]               <= exp_rnd;
        end
      end
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      out_valid_q <= 1'b0;
    end else if (out_free) begin
      out_valid_q <= v_q[StQ];
    end
  end
  always_ff @(posedge clk_i) begin
    if (out_free && v_q[StQ]) begin
      out_dbz_q <= dbz_q[StQ];
    end
  end
endmodule
