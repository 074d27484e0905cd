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
  // aligned divisor b, k (exp_adj -1), dbz / nz flags. Plain packed vectors or arrays of them
  // (Yosys 0.23 does not handle arrays of structs).
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

  // One recurrence step, the loop body of fxr::div_sig_radix2_steps: r >= 0: r' = 2r - b, digit
  // +1 (p' = {p, 1}); r < 0: r' = 2r + b, digit -1 (p' = {p, 0}). Invariant a'*2^i = Q_i*b + r_i
  // with r_i in [-b, b): r' stays in RemBits signed bits (|r| < b < 2^AlignBits). Exact, no
  // rounding. The remainder here (one adder: 2r + (b XOR ~sign) + ~sign, the operand selected,
  // not two sums and a multiplexer), the digit (~r's sign bit) shifted into p by the caller.
  // Written so, a simulator runs it without a data-dependent branch and without packing {r', p'}
  // into one word (the lanes were a third of the unit's simulation; docs/rtl.md, "Co-simulation
  // speed", session 11).
  function automatic logic [RemBits-1:0] nr_rem(input logic [RemBits-1:0] r, input logic [AlignBits-1:0] b);
    nr_rem = {r[RemBits-2:0], 1'b0} + ({{(RemBits - AlignBits){1'b0}}, b} ^ {RemBits{~r[RemBits-1]}})
             + {{(RemBits - 1){1'b0}}, ~r[RemBits-1]};
  endfunction

  if (Schedule == fxr_config_pkg::DivSchedulePipelined) begin : gen_pipelined
    // Register stage s holds an operand after s * BitsPerStage recurrence steps (s = 0: pre).
    // Global stall: every register advances when the output register can take a result.
    // Stages 0 … Stages − 1 as unpacked arrays, one per field, written by one clocked process: a
    // loop over the stages in descending order with blocking assignments (each element is read,
    // the register's value, before the stage below overwrites it: the shift register of
    // nonblocking assignments, without a simulator's delayed-assignment copy of every element;
    // the arrays are read nowhere else). The last stage, read by the post logic, is nonblocking.
    // The form of fxr_viewport_lane (docs/rtl.md, "Co-simulation speed", sessions 8 and 9): flat
    // per-stage vectors made Verilator copy and re-insert each stage's unaligned slice every
    // clock. Yosys makes each element a register (mem2reg).
    (* mem2reg *) logic [RemBits-1:0]   r_a [Stages];
    (* mem2reg *) logic [QuotBits-1:0]  p_a [Stages];
    (* mem2reg *) logic [AlignBits-1:0] b_a [Stages];
    (* mem2reg *) logic [2:0]           f_a [Stages];  // {k, dbz, nz}
    logic [RemBits-1:0]   r_l;  // stage Stages
    logic [QuotBits-1:0]  p_l;
    logic [AlignBits-1:0] b_l;
    logic [2:0]           f_l;
    logic [Stages:0]      v_q;

    assign in_ready_o = out_free;
    assign out_load   = v_q[Stages];
    assign last_r     = r_l;
    assign last_p     = p_l;
    assign last_b     = b_l;
    assign {last_k, last_dbz, last_nz} = f_l;

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        v_q <= '0;
      end else if (out_free) begin
        v_q <= {v_q[Stages-1:0], in_valid_i};
      end
    end
    /* verilator lint_off BLKSEQ */
    always_ff @(posedge clk_i) begin
      if (out_free) begin
        for (int s = Stages - 1; s >= 0; s--) begin
          if (v_q[s]) begin
            logic [RemBits-1:0]  r;
            logic [QuotBits-1:0] p;
            r = r_a[s];
            p = p_a[s];
            // steps s * BitsPerStage + j; the last stage may be partial
            for (int j = 0; j < BitsPerStage; j++)
              if (s * BitsPerStage + j < Steps) begin
                p = {p[QuotBits-2:0], ~r[RemBits-1]};
                r = nr_rem(r, b_a[s]);
              end
            if (s + 1 < Stages) begin
              r_a[s+1] = r;
              p_a[s+1] = p;
              b_a[s+1] = b_a[s];
              f_a[s+1] = f_a[s];
            end else begin
              r_l <= r;
              p_l <= p;
              b_l <= b_a[s];
              f_l <= f_a[s];
            end
          end
        end
        if (in_valid_i) begin
          r_a[0] = pre_r;
          p_a[0] = pre_p;
          b_a[0] = pre_b;
          f_a[0] = {pre_k, pre_dbz, pre_nz};
        end
      end
    end
    /* verilator lint_on BLKSEQ */
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
    /* verilator lint_off BLKSEQ */
    always_ff @(posedge clk_i) begin
      if (accept) begin
        r_q   <= pre_r;
        p_q   <= pre_p;
        b_q   <= pre_b;
        k_q   <= pre_k;
        dbz_q <= pre_dbz;
        nz_q  <= pre_nz;
      end else if (busy_q && !done) begin
        logic [RemBits-1:0]  r;
        logic [QuotBits-1:0] p;
        r = r_q;
        p = p_q;
        // steps cnt * BitsPerStage + j; the last round may be partial
        for (int j = 0; j < BitsPerStage; j++)
          if (IdxBits'(cnt_q) * IdxBits'(BitsPerStage) + IdxBits'(j) < IdxBits'(Steps)) begin
            p = {p[QuotBits-2:0], ~r[RemBits-1]};
            r = nr_rem(r, b_q);
          end
        r_q <= r;
        p_q <= p;
      end
    end
    /* verilator lint_on BLKSEQ */
  end
endmodule
