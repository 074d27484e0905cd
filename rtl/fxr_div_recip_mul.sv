// fxr_div_recip_mul: reciprocal-multiply significand divider with a remainder correction,
// fully pipelined (one result per clock). Implements fxr::div_sig_recip_mul (model/arith/div.cpp)
// bit for bit; ports as fxr_div.
//
// Register stages (latency = 2 * NrSteps + 4 = fxr::div_cost):
//   0            align (a, b exact), k = (a < b), a' = a << k, seed ROM (fxr_seed_rom) -> y0
//   2i+1, 2i+2   Newton-Raphson step i (fxr_nr_step, the reciprocal core shared with fxr_recip):
//                t = ~trunc_F(bn*y); y <- trunc_F(y*t), bn = b*2^-(AlignBits-1), y <= 1/bn
//   2N+1         q~ = (a' * y) >> (AlignBits + NrFracBits - QuotBits) [truncated]
//   2N+2         r = a'*2^(QuotBits-1) - q~*b (exact); one correction step either way; clamps
//                (only inaccurate configurations reach them)
//   output       RNE on the sign / zero of t = 2r - b (fxr_round)
// The whole pipeline stalls while out_valid_o && !out_ready_i.
module fxr_div_recip_mul #(
  parameter int NumBits       = 32,
  parameter int DenBits       = 32,
  parameter int QuotBits      = 24,
  parameter int SeedIndexBits = 8,
  parameter int SeedBits      = 8,
  parameter int NrSteps       = 2,
  parameter int NrFracBits    = 28
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
  // Derived widths (see the model's comments for the bounds).
  localparam int W      = (NumBits > DenBits) ? NumBits : DenBits;  // div_align_bits
  localparam int F      = NrFracBits;
  localparam int YBits  = F;               // y < 1 (one-sided: y <= 1/bn <= 1, and y < 1 at F bits)
  localparam int QtBits = QuotBits + 2;    // q~ < a'*y*2^(qb-1)/2^(W-1) < 2^(qb+2)
  localparam int QShift = W + F - QuotBits;
  localparam int RBits  = W + QuotBits + 3;  // signed r = a'*2^(qb-1) - q~*b
  localparam int QcBits = QuotBits + 4;      // signed q~ +- 1
  localparam int NS     = 2 * NrSteps + 3;   // register stages before the output register
  localparam int StQ    = 2 * NrSteps + 1;   // stage of q~
  localparam int StC    = 2 * NrSteps + 2;   // stage of the corrected q, r
  localparam int SeedW  = SeedBits + 1;      // seed with its leading one

  logic out_free;  // the whole pipeline advances this cycle
  assign in_ready_o = out_free;

  // ---- stage 0: align, compare, seed --------------------------------------------------------
  logic [W-1:0]             a, b;
  logic                     k;
  logic [W:0]               a1;
  logic [SeedIndexBits-1:0] idx;
  logic [SeedBits-1:0]      seed_frac;
  logic [SeedW-1:0]         seed;

  fxr_div_align #(
    .NumBits(NumBits),
    .DenBits(DenBits)
  ) u_align (
    .num_i(in_num_i),
    .den_i(in_den_i),
    .a_o  (a),
    .b_o  (b)
  );
  assign k  = a < b;
  assign a1 = k ? {a, 1'b0} : {1'b0, a};

  // Seed index: the SeedIndexBits divisor bits after its leading one (zero-extended if fewer).
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
  assign seed = {1'b1, seed_frac};  // y0 = seed * 2^-SeedW in [1/2, 1)

  // ---- pass-through registers (stage s at [s*Width +: Width]) -------------------------------
  logic [(StQ+1)*(W+1)-1:0] a1_q;  // used up to stage 2N (the q~ multiply)
  logic [NS*W-1:0]          b_q;   // used up to stage 2N+2
  logic [NS-1:0]            v_q, k_q, dbz_q, nz_q;
  logic [SeedW-1:0]             y0_q;
  wire  [(NrSteps+1)*YBits-1:0] y_s;  // y after step i >= 1 (registered at stage 2i); slot 0:
                                      // y0 at F fraction bits, read only when NrSteps == 0
  // y0 at F fraction bits (precision lost when the seed is wider than F bits: truncated).
  if (F > SeedW) begin : gen_y0_widen
    assign y_s[0 +: YBits] = YBits'({y0_q, {(F - SeedW){1'b0}}});
  end else if (F == SeedW) begin : gen_y0_same
    assign y_s[0 +: YBits] = y0_q;
  end else begin : gen_y0_trunc
    assign y_s[0 +: YBits] = YBits'(y0_q >> (SeedW - F));
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      v_q <= '0;
    end else if (out_free) begin
      v_q <= {v_q[NS-2:0], in_valid_i};
    end
  end
  always_ff @(posedge clk_i) begin
    if (out_free) begin
      k_q   <= {k_q[NS-2:0], k};
      dbz_q <= {dbz_q[NS-2:0], in_den_i == '0};
      nz_q  <= {nz_q[NS-2:0], in_num_i == '0};
      b_q   <= {b_q[(NS-1)*W-1:0], b};
      a1_q  <= {a1_q[StQ*(W+1)-1:0], a1};
      y0_q  <= seed;
    end
  end

  if (NrSteps > 0) begin : gen_y0_unused
    logic unused_y0;  // the steps read y0_q directly
    assign unused_y0 = ^y_s[0 +: YBits];
  end

  // ---- Newton-Raphson steps (the reciprocal core) ----------------------------------------------
  for (genvar i = 0; i < NrSteps; i++) begin : gen_nr
    localparam int SA = 2 * i;  // stage holding y_i
    if (i == 0) begin : gen_first  // from the seed, SeedW fraction bits
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

  // ---- quotient multiply (stage 2N -> 2N+1) --------------------------------------------------
  localparam int AQ = 2 * NrSteps * (W + 1);
  localparam int YQ = NrSteps * YBits;
  logic [W+1+YBits-1:0] prod;  // a'*y, exact
  logic [QtBits-1:0]    qt;
  logic [QtBits-1:0]    qt_q;  // q~
  assign prod = {{YBits{1'b0}}, a1_q[AQ +: W+1]} * {{(W+1){1'b0}}, y_s[YQ +: YBits]};
  if (QShift >= 0) begin : gen_qt_shr
    assign qt = QtBits'(prod >> QShift);  // precision lost: the QShift low product bits
  end else begin : gen_qt_shl
    logic [QtBits-1:0] prod_ext;  // q~ needs QtBits > the product width here
    assign prod_ext = QtBits'(prod);
    assign qt       = prod_ext << (-QShift);
  end
  always_ff @(posedge clk_i) begin
    if (out_free) begin
      qt_q <= qt;
    end
  end

  // ---- back-multiply, correction, clamps (stage 2N+1 -> 2N+2) --------------------------------
  logic [W-1:0]         bc;      // b at stage 2N+1
  logic [W:0]           a1c;     // a' at stage 2N+1
  logic signed [RBits-1:0]  bs, r0, r1;
  logic signed [QcBits-1:0] q1;
  logic [QtBits+W-1:0]      qb_prod;  // q~*b, exact
  localparam logic signed [QcBits-1:0] QLo = QcBits'(1) << (QuotBits - 1);        // sig range
  localparam logic signed [QcBits-1:0] QHi = (QcBits'(1) << QuotBits) - QcBits'(1);
  logic [QuotBits-1:0]  qc_q;
  logic [W-1:0]         rc_q;
  assign bc  = b_q[StQ*W +: W];
  assign a1c = a1_q[StQ*(W+1) +: W+1];

  assign bs      = $signed(RBits'(bc));
  assign qb_prod = {{W{1'b0}}, qt_q} * {{QtBits{1'b0}}, bc};
  always_comb begin
    r0 = $signed(RBits'({a1c, {(QuotBits - 1){1'b0}}})) - $signed(RBits'(qb_prod));
    q1 = $signed(QcBits'(qt_q));
    r1 = r0;
    if (r0 < 0) begin
      q1 = q1 - 1;
      r1 = r0 + bs;
    end else if (r0 >= bs) begin
      q1 = q1 + 1;
      r1 = r0 - bs;
    end
    // Clamps: reached only when q~ was more than one ulp off (inaccurate configurations).
    if (r1 < 0) r1 = '0;
    if (r1 >= bs) r1 = bs - 1;
    if (q1 < QLo) q1 = QLo;
    if (q1 > QHi) q1 = QHi;
  end
  always_ff @(posedge clk_i) begin
    if (out_free) begin
      qc_q <= q1[QuotBits-1:0];
      rc_q <= r1[W-1:0];
    end
  end

  // ---- RNE, special cases, output register ---------------------------------------------------
  logic [W-1:0]        bo;
  logic [W+1:0]        t;  // 2r - b, two's complement
  logic [QuotBits-1:0] sig_rnd;
  logic [1:0]          exp_rnd;
  assign bo = b_q[StC*W +: W];
  assign t  = {1'b0, rc_q, 1'b0} - {2'b00, bo};
  fxr_round #(
    .QuotBits(QuotBits)
  ) u_round (
    .q_i      (qc_q),
    .t_neg_i  (t[W+1]),
    .t_zero_i (t == '0),
    .k_i      (k_q[StC]),
    .sig_o    (sig_rnd),
    .exp_adj_o(exp_rnd)
  );

  logic                out_valid_q;
  logic [QuotBits-1:0] out_sig_q;
  logic [1:0]          out_exp_q;
  logic                out_dbz_q;
  assign out_free      = ~out_valid_q | out_ready_i;
  assign out_valid_o   = out_valid_q;
  assign out_sig_o     = out_sig_q;
  assign out_exp_adj_o = out_exp_q;
  assign out_dbz_o     = out_dbz_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      out_valid_q <= 1'b0;
    end else if (out_free) begin
      out_valid_q <= v_q[StC];
    end
  end
  always_ff @(posedge clk_i) begin
    if (out_free && v_q[StC]) begin
      out_dbz_q <= dbz_q[StC];
      if (dbz_q[StC]) begin
        out_sig_q <= '1;
        out_exp_q <= 2'b00;
      end else if (nz_q[StC]) begin
        out_sig_q <= '0;
        out_exp_q <= 2'b00;
      end else begin
        out_sig_q <= sig_rnd;
        out_exp_q <= exp_rnd;
      end
    end
  end
endmodule
