// fxr_div_radix2: radix-2 non-restoring significand divider, pipelined or iterative.
// Implements fxr::div_sig_radix2_steps (model/arith/div.cpp) bit for bit; ports as fxr_div.
//
// DivSchedulePipelined: pre -> Stages recurrence registers (BitsPerStage steps each) -> post.
//   One result per clock; the whole pipeline stalls while out_valid_o && !out_ready_i.
// DivScheduleIterative: pre loads one working register, which runs Stages cycles of
//   BitsPerStage steps; post writes the output register. II = Stages + 1.
// Latency (both) = Stages + 2, Stages = ceil((QuotBits - 1) / BitsPerStage) = fxr::div_cost.
module fxr_div_radix2 #(
  parameter int NumBits      = 32,
  parameter int DenBits      = 32,
  parameter int QuotBits     = 24,
  parameter int BitsPerStage = 1,
  parameter int Schedule     = fxr_config_pkg::DivSchedulePipelined
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
  // Derived widths, as fxr::div_align_bits / div_rem_bits / div_radix2_steps.
  localparam int AlignBits = (NumBits > DenBits) ? NumBits : DenBits;
  localparam int RemBits   = AlignBits + 2;
  localparam int Steps     = QuotBits - 1;
  localparam int Stages    = (Steps + BitsPerStage - 1) / BitsPerStage;

  // Stage contents (one operand in flight): partial remainder r (signed), digit bits p,
  // aligned divisor b, k (exp_adj -1), dbz / nz flags. Plain packed vectors (Yosys 0.23 does
  // not handle arrays of structs).
  logic [RemBits-1:0]         pre_r;  // two's complement partial remainders throughout
  logic [QuotBits-1:0]        pre_p;
  logic [AlignBits-1:0]       pre_b;
  logic                       pre_k, pre_dbz, pre_nz;
  fxr_div_radix2_pre #(
    .NumBits (NumBits),
    .DenBits (DenBits),
    .QuotBits(QuotBits)
  ) u_pre (
    .num_i(in_num_i),
    .den_i(in_den_i),
    .r_o  (pre_r),
    .p_o  (pre_p),
    .b_o  (pre_b),
    .k_o  (pre_k),
    .dbz_o(pre_dbz),
    .nz_o (pre_nz)
  );

  // Operand entering the post stage.
  logic [RemBits-1:0]   last_r;
  logic [QuotBits-1:0]  last_p;
  logic [AlignBits-1:0] last_b;
  logic                 last_k, last_dbz, last_nz;
  logic [QuotBits-1:0]  post_sig;
  logic [1:0]           post_exp;
  logic                 post_dbz;
  fxr_div_radix2_post #(
    .AlignBits(AlignBits),
    .QuotBits (QuotBits)
  ) u_post (
    .r_i      (last_r),
    .p_i      (last_p),
    .b_i      (last_b),
    .k_i      (last_k),
    .dbz_i    (last_dbz),
    .nz_i     (last_nz),
    .sig_o    (post_sig),
    .exp_adj_o(post_exp),
    .dbz_o    (post_dbz)
  );

  // Output register.
  logic                out_valid_q;
  logic [QuotBits-1:0] out_sig_q;
  logic [1:0]          out_exp_q;
  logic                out_dbz_q;
  logic                out_load;  // a post result is ready to be captured
  logic                out_free;  // output register can take a result this cycle

  assign out_free      = ~out_valid_q | out_ready_i;
  assign out_valid_o   = out_valid_q;
  assign out_sig_o     = out_sig_q;
  assign out_exp_adj_o = out_exp_q;
  assign out_dbz_o     = out_dbz_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      out_valid_q <= 1'b0;
    end else if (out_free) begin
      out_valid_q <= out_load;
    end
  end
  always_ff @(posedge clk_i) begin
    if (out_free && out_load) begin
      out_sig_q <= post_sig;
      out_exp_q <= post_exp;
      out_dbz_q <= post_dbz;
    end
  end

  if (Schedule == fxr_config_pkg::DivSchedulePipelined) begin : gen_pipelined
    // Register stage s holds an operand after s * BitsPerStage recurrence steps (s = 0: pre).
    // Global stall: every register advances when the output register can take a result.
    // Flattened per-stage vectors (Yosys 0.23 reads neither arrays of structs nor
    // multi-dimensional packed arrays): field of stage s at [s*Width +: Width].
    logic [(Stages+1)*RemBits-1:0]   r_q;
    logic [(Stages+1)*QuotBits-1:0]  p_q;
    logic [(Stages+1)*AlignBits-1:0] b_q;
    logic [Stages:0]                 k_q, dbz_q, nz_q, v_q;

    assign in_ready_o = out_free;
    assign out_load   = v_q[Stages];
    assign last_r     = r_q[Stages*RemBits +: RemBits];
    assign last_p     = p_q[Stages*QuotBits +: QuotBits];
    assign last_b     = b_q[Stages*AlignBits +: AlignBits];
    assign last_k     = k_q[Stages];
    assign last_dbz   = dbz_q[Stages];
    assign last_nz    = nz_q[Stages];

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        v_q[0] <= 1'b0;
      end else if (out_free) begin
        v_q[0] <= in_valid_i;
      end
    end
    always_ff @(posedge clk_i) begin
      if (out_free && in_valid_i) begin
        r_q[0 +: RemBits]   <= pre_r;
        p_q[0 +: QuotBits]  <= pre_p;
        b_q[0 +: AlignBits] <= pre_b;
        k_q[0]   <= pre_k;
        dbz_q[0] <= pre_dbz;
        nz_q[0]  <= pre_nz;
      end
    end

    for (genvar s = 0; s < Stages; s++) begin : gen_stage
      // Slice offsets of stage s (in) and s + 1 (out). Icarus 11 evaluates genvar expressions
      // in port connections and part selects of nested generate loops as X: use localparams.
      localparam int RIn  = s * RemBits;
      localparam int ROut = (s + 1) * RemBits;
      localparam int PIn  = s * QuotBits;
      localparam int POut = (s + 1) * QuotBits;
      localparam int BIn  = s * AlignBits;
      localparam int BOut = (s + 1) * AlignBits;
      localparam int SIn  = s;
      localparam int SOut = s + 1;
      // Step j's input at [j*Width +: Width], its output at [(j+1)*Width +: Width]. Nets, not
      // variables: slices have different drivers.
      wire [(BitsPerStage+1)*RemBits-1:0]  r_c;
      wire [(BitsPerStage+1)*QuotBits-1:0] p_c;
      assign r_c[0 +: RemBits]  = r_q[RIn +: RemBits];
      assign p_c[0 +: QuotBits] = p_q[PIn +: QuotBits];
      for (genvar j = 0; j < BitsPerStage; j++) begin : gen_step
        localparam int  JrIn   = j * RemBits;
        localparam int  JrOut  = (j + 1) * RemBits;
        localparam int  JpIn   = j * QuotBits;
        localparam int  JpOut  = (j + 1) * QuotBits;
        localparam bit  StepEn = (s * BitsPerStage + j) < Steps;  // last stage may be partial
        logic [RemBits-1:0]  r_out;
        logic [QuotBits-1:0] p_out;
        assign r_c[JrOut +: RemBits]  = r_out;
        assign p_c[JpOut +: QuotBits] = p_out;
        fxr_div_radix2_step #(
          .AlignBits(AlignBits),
          .QuotBits (QuotBits)
        ) u_step (
          .en_i(StepEn && v_q[SIn]),  // an empty stage's step is skipped (its result is not read)
          .r_i (r_c[JrIn +: RemBits]),
          .p_i (p_c[JpIn +: QuotBits]),
          .b_i (b_q[BIn +: AlignBits]),
          .r_o (r_out),
          .p_o (p_out)
        );
      end
      always_ff @(posedge clk_i or negedge rst_ni) begin
        if (!rst_ni) begin
          v_q[SOut] <= 1'b0;
        end else if (out_free) begin
          v_q[SOut] <= v_q[SIn];
        end
      end
      always_ff @(posedge clk_i) begin
        if (out_free && v_q[SIn]) begin
          r_q[ROut +: RemBits]   <= r_c[BitsPerStage*RemBits +: RemBits];
          p_q[POut +: QuotBits]  <= p_c[BitsPerStage*QuotBits +: QuotBits];
          b_q[BOut +: AlignBits] <= b_q[BIn +: AlignBits];
          k_q[SOut]              <= k_q[SIn];
          dbz_q[SOut]            <= dbz_q[SIn];
          nz_q[SOut]             <= nz_q[SIn];
        end
      end
    end
  end else begin : gen_iterative
    localparam int CntBits = $clog2(Stages + 1);
    localparam int IdxBits = CntBits + 8;  // cnt * BitsPerStage + j, BitsPerStage <= 8 < 2^8
    localparam logic [CntBits-1:0] LastCnt = CntBits'(Stages);

    logic [RemBits-1:0]   r_q;
    logic [QuotBits-1:0]  p_q;
    logic [AlignBits-1:0] b_q;
    logic                 k_q, dbz_q, nz_q;
    logic                 busy_q;
    logic [CntBits-1:0]   cnt_q;
    logic                 done;
    logic                 accept;
    wire [(BitsPerStage+1)*RemBits-1:0]  r_c;  // step j: in [j*W +: W], out [(j+1)*W +: W]
    wire [(BitsPerStage+1)*QuotBits-1:0] p_c;

    assign done       = busy_q && (cnt_q == LastCnt);
    assign out_load   = done;
    assign in_ready_o = ~busy_q | (done & out_free);
    assign accept     = in_valid_i & in_ready_o;
    assign last_r     = r_q;
    assign last_p     = p_q;
    assign last_b     = b_q;
    assign last_k     = k_q;
    assign last_dbz   = dbz_q;
    assign last_nz    = nz_q;

    assign r_c[0 +: RemBits]  = r_q;
    assign p_c[0 +: QuotBits] = p_q;
    for (genvar j = 0; j < BitsPerStage; j++) begin : gen_step
      localparam int JrIn  = j * RemBits;  // localparams, not genvar expressions (Icarus 11)
      localparam int JrOut = (j + 1) * RemBits;
      localparam int JpIn  = j * QuotBits;
      localparam int JpOut = (j + 1) * QuotBits;
      localparam logic [IdxBits-1:0] JIdx = IdxBits'(j);
      logic [IdxBits-1:0]  step_idx;
      logic [RemBits-1:0]  r_out;
      logic [QuotBits-1:0] p_out;
      assign r_c[JrOut +: RemBits]  = r_out;
      assign p_c[JpOut +: QuotBits] = p_out;
      assign step_idx = IdxBits'(cnt_q) * IdxBits'(BitsPerStage) + JIdx;
      fxr_div_radix2_step #(
        .AlignBits(AlignBits),
        .QuotBits (QuotBits)
      ) u_step (
        .en_i(step_idx < IdxBits'(Steps)),
        .r_i (r_c[JrIn +: RemBits]),
        .p_i (p_c[JpIn +: QuotBits]),
        .b_i (b_q),
        .r_o (r_out),
        .p_o (p_out)
      );
    end

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        busy_q <= 1'b0;
        cnt_q  <= '0;
      end else if (accept) begin
        busy_q <= 1'b1;
        cnt_q  <= '0;
      end else if (done && out_free) begin
        busy_q <= 1'b0;
      end else if (busy_q && !done) begin
        cnt_q <= cnt_q + 1'b1;
      end
    end
    always_ff @(posedge clk_i) begin
      if (accept) begin
        r_q   <= pre_r;
        p_q   <= pre_p;
        b_q   <= pre_b;
        k_q   <= pre_k;
        dbz_q <= pre_dbz;
        nz_q  <= pre_nz;
      end else if (busy_q && !done) begin
        r_q <= r_c[BitsPerStage*RemBits +: RemBits];
        p_q <= p_c[BitsPerStage*QuotBits +: QuotBits];
      end
    end
  end
endmodule
