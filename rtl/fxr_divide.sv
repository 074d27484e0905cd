// fxr_divide: stage 9, the divider of the varyings (issue 10). One plane sample in, one fragment
// out. Model: fxr::DivideStage (model/stages/divide.hpp: normalize_den, divide_varying;
// model/arith/div.hpp); docs/rtl.md "fxr_divide"; vectors: the transaction dumps' divide.in /
// divide.out (docs/vectors.md, "Transaction vectors"; tb/txn/divide_txn_test.cpp). The issue's
// "fxr_interp" (plane values -> normalisation -> divider lanes) is fxr_interp + this module.
//
// Ports:
//   clk_i, rst_ni                 clock, active-low asynchronous reset
//   in_valid_i / in_ready_o       input handshake (transfer when both are high)
//   in_i                          fxr_rec_pkg::plane_sample_t: prim, x, y, depth code, the 1/w sum
//                                 den and every v/w sum num<m> (signed) with their block exponents
//   out_valid_o / out_ready_i     output handshake
//   out_o                         fxr_rec_pkg::fragment_t: prim, x, y, depth code and every varying
//                                 var<m> as sign, QuotBits significand and exponent
//
// Function (the model bit for bit): D = den <= 0 -> every varying 0. Else D is normalised to
// DenBits significant bits (leading-one position, RNE, carry renormalises) -> d, e_d = msb + den_exp;
// per varying N = num<m>: N == 0 -> 0 (sign +); else |N| is normalised to NumBits -> n, e_n, the
// sign is N's, and the significand divider gives sig, exp_adj for n / d:
//   var = (-1)^neg * sig * 2^(exp_adj + e_n - e_d - (QuotBits - 1)), e_n = msb(|N|) + num<m>_exp.
// Divider (div.algorithm from fxr_config_pkg):
//   radix2 / recip_mul (per_varying): Lanes instances of fxr_div, one varying each;
//   shared_recip: one fxr_div_shared_recip: the reciprocal core once for the group's D and one
//   multiplier per lane (rounded once; within fxr::div_bound(), not correctly rounded).
// Lanes (parameter): varyings divided per clock. Lanes = NumVaryings (default): one fragment per
// clock; fewer: ceil(NumVaryings / Lanes) clocks per fragment (a group of Lanes varyings per
// clock; with shared_recip the core sees the same D once per group).
//
// Pipeline: in_q (the sample) -> group issue: normalisation of D and of the group's Lanes
// numerators into nq -> the lanes (fxr_div or fxr_div_shared_recip, their own latency) -> the
// group's results into the fragment (last group: the output register). The sideband of each group
// in flight (pixel fields, signs, zero flags, exponents) waits in a FIFO of FifoDepth entries
// (>= the lanes' latency + 2: never the bottleneck). Latency (input transfer to out_valid_o) =
// lane latency + 3 + (groups - 1), II = groups (pipelined lanes; fxr::divide_cost); out_ready_i
// low holds the fragment and, through the lanes' own stall, everything behind it.
module fxr_divide #(
  parameter int WindowIntBits    = fxr_config_pkg::RasterWindowIntBits,
  parameter int SubpixelBits     = fxr_config_pkg::RasterSubpixelBits,
  parameter int DepthFormat      = fxr_config_pkg::RasterDepthFormat,  // raster_depth_format_e
  parameter int InterpBlockBits  = fxr_config_pkg::RasterInterpBlockBits,
  parameter int AttrSubpixelBits = fxr_config_pkg::RasterAttrSubpixelBits,
  parameter int AttrCoordBits    = fxr_config_pkg::RasterAttrCoordBits,
  parameter int RecipExpBits     = fxr_config_pkg::RecipExpBits,
  parameter int Algorithm        = fxr_config_pkg::DivAlgorithm,       // div_algorithm_e
  parameter int NumBits          = fxr_config_pkg::DivNumBits,
  parameter int DenBits          = fxr_config_pkg::DivDenBits,
  parameter int QuotBits         = fxr_config_pkg::DivQuotBits,
  parameter int SeedIndexBits    = fxr_config_pkg::DivSeedIndexBits,
  parameter int SeedBits         = fxr_config_pkg::DivSeedBits,
  parameter int NrSteps          = fxr_config_pkg::DivNrSteps,
  parameter int NrFracBits       = fxr_config_pkg::DivNrFracBits,
  parameter int BitsPerStage     = fxr_config_pkg::DivBitsPerStage,
  parameter int Schedule         = fxr_config_pkg::DivSchedule,        // div_schedule_e
  parameter int NumVaryings      = fxr_rec_pkg::NumVaryings,
  // Micro-architecture: varyings divided per clock (divider lanes).
  parameter int Lanes            = NumVaryings,
  // derived (model/stages/setup.hpp, model/unit/record.hpp, model/arith/div.cpp)
  localparam bit Attr       = AttrSubpixelBits > SubpixelBits,     // attr_planes
  localparam int G          = SubpixelBits > 0 ? SubpixelBits : 1,
  localparam int CB         = WindowIntBits + G,                   // coord_bits
  localparam int EVB        = 2 * CB + 2,                          // edge_value_bits
  localparam int Db         = DepthFormat == fxr_config_pkg::RasterDepthFormatD24 ? 24 : 16,
  localparam int PEB        = Attr ? 2 * AttrCoordBits + 2 : EVB,  // plane_edge_bits
  localparam int IPB        = PEB + InterpBlockBits + 1 + 2,       // interp_plane_bits
  localparam int F32ExpBits = 8,
  localparam int EB         = (RecipExpBits > F32ExpBits + 1 ? RecipExpBits : F32ExpBits + 1) + 2,
  localparam int PrimBits   = 32,                                  // kPrimIdBits
  localparam int PB         = WindowIntBits,                       // pixel index (signed)
  localparam int Groups     = (NumVaryings + Lanes - 1) / Lanes,   // clocks per fragment
  localparam int GB         = Groups > 1 ? $clog2(Groups) : 1,
  localparam int XB         = EB + 4,                              // exponent arithmetic
  localparam int MB         = $clog2(IPB) + 1,                     // msb index of a plane sum
  localparam int LaneLat    = Algorithm == fxr_config_pkg::DivAlgorithmRadix2
                              ? (QuotBits - 1 + BitsPerStage - 1) / BitsPerStage + 2
                              : (Algorithm == fxr_config_pkg::DivAlgorithmSharedRecip ? 2 * NrSteps + 3
                                                                                    : 2 * NrSteps + 4),
  localparam int FifoBits   = $clog2(LaneLat + 2),
  localparam int FifoDepth  = 1 << FifoBits
) (
  input  logic                       clk_i,
  input  logic                       rst_ni,
  input  logic                       in_valid_i,
  output logic                       in_ready_o,
  input  fxr_rec_pkg::plane_sample_t in_i,
  output logic                       out_valid_o,
  input  logic                       out_ready_i,
  output fxr_rec_pkg::fragment_t     out_o
);
  // ---- record layout (the generated structs; first field most significant) ---------------------
  localparam int PixBits = PrimBits + 2 * PB + Db;      // prim, x, y, depth (both records)
  localparam int PlB     = IPB + EB;                    // a plane sum and its exponent
  localparam int PSB     = PixBits + (NumVaryings + 1) * PlB;
  localparam int VarB    = 1 + QuotBits + EB;           // neg, sig, exp of a varying
  localparam int FB      = PixBits + NumVaryings * VarB;
  localparam int LaneSB  = 2 + XB;                      // per lane: neg, zero, exponent part

  logic [PSB-1:0] in_flat;
  logic [FB-1:0]  out_flat;
  assign in_flat = in_i;
  assign out_o   = out_flat;

  // ---- in_q: the sample --------------------------------------------------------------------------
  logic           in_q_valid;
  logic [PSB-1:0] in_q;
  logic [GB-1:0]  gi;          // the next group to issue
  logic           issue_fire;  // group gi of in_q goes into nq
  logic           issue_last;
  assign issue_last = 32'(gi) == Groups - 1;
  assign in_ready_o = ~in_q_valid | (issue_fire & issue_last);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      in_q_valid <= 1'b0;
      gi         <= '0;
    end else begin
      if (in_valid_i && in_ready_o) in_q_valid <= 1'b1;
      else if (issue_fire && issue_last) in_q_valid <= 1'b0;
      if (issue_fire) gi <= issue_last ? '0 : gi + GB'(1);
    end
  end
  always_ff @(posedge clk_i) begin
    if (in_valid_i && in_ready_o) in_q <= in_flat;
  end

  // ---- normalisation of the issued group (combinational from in_q) -----------------------------
  logic signed [IPB-1:0] den;
  logic signed [EB-1:0]  den_exp;
  logic [DenBits-1:0]    d_sig;
  logic [MB-1:0]         d_msb;
  logic                  d_pos;
  assign den     = in_q[NumVaryings * PlB + EB +: IPB];
  assign den_exp = in_q[NumVaryings * PlB +: EB];
  assign d_pos   = ~den[IPB-1] & (den != '0);
  fxr_divide_norm #(
    .InBits (IPB),
    .OutBits(DenBits),
    .MsbBits(MB)
  ) u_norm_den (
    .en_i (in_q_valid),  // read at issue_fire only
    .x_i  (den),
    .sig_o(d_sig),
    .msb_o(d_msb)
  );
  logic signed [XB-1:0] e_d;  // msb(D) + den_exp
  assign e_d = XB'($signed({1'b0, d_msb})) + XB'(den_exp);

  logic [Lanes*NumBits-1:0] n_sig;
  logic [Lanes*LaneSB-1:0]  lane_sb;
  for (genvar l = 0; l < Lanes; l++) begin : gen_lane_norm
    logic signed [IPB-1:0] num;
    logic signed [EB-1:0]  num_exp;
    logic [IPB-1:0]        mag;
    logic [NumBits-1:0]    sig;
    logic [MB-1:0]         msb;
    logic                  valid_m, zero;
    logic signed [XB-1:0]  e_part;
    // varying m = gi * Lanes + l (lanes beyond NumVaryings divide 0 and are dropped)
    // Evaluated only with a sample in in_q (read at issue_fire only): an idle stage costs the
    // simulator nothing here (docs/rtl.md, "Co-simulation speed").
    always_comb begin
      num     = '0;
      num_exp = '0;
      valid_m = 1'b0;
      mag     = '0;
      if (in_q_valid) begin
        for (int m = 0; m < NumVaryings; m++) begin
          if (32'(gi) * Lanes + l == m) begin
            num     = in_q[(NumVaryings - 1 - m) * PlB + EB +: IPB];
            num_exp = in_q[(NumVaryings - 1 - m) * PlB +: EB];
            valid_m = 1'b1;
          end
        end
        mag = num[IPB-1] ? IPB'(-num) : num;
      end
    end
    fxr_divide_norm #(
      .InBits (IPB),
      .OutBits(NumBits),
      .MsbBits(MB)
    ) u_norm_num (
      .en_i (in_q_valid),
      .x_i  (mag),
      .sig_o(sig),
      .msb_o(msb)
    );
    assign zero = ~valid_m | (num == '0) | ~d_pos;
    // exponent without exp_adj: msb(|N|) + num_exp - e_d - (QuotBits - 1)
    assign e_part = XB'($signed({1'b0, msb})) + XB'(num_exp) - e_d - XB'(QuotBits - 1);
    assign n_sig[l*NumBits +: NumBits]  = zero ? '0 : sig;
    assign lane_sb[l*LaneSB +: LaneSB] = {num[IPB-1] & ~zero, zero, e_part};
  end

  // ---- nq: the normalised group ------------------------------------------------------------------
  localparam int SBB = PixBits + Lanes * LaneSB + GB + 1;  // sideband: pixel, lanes, group, last
  logic                     nq_valid, nq_fire;
  logic [Lanes*NumBits-1:0] nq_num;
  logic [DenBits-1:0]       nq_den;
  logic [SBB-1:0]           nq_sb;
  logic                     lanes_in_ready, fifo_full;
  assign nq_fire    = nq_valid & lanes_in_ready & ~fifo_full;
  assign issue_fire = in_q_valid & (~nq_valid | nq_fire);
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      nq_valid <= 1'b0;
    end else if (issue_fire) begin
      nq_valid <= 1'b1;
    end else if (nq_fire) begin
      nq_valid <= 1'b0;
    end
  end
  always_ff @(posedge clk_i) begin
    if (issue_fire) begin
      nq_num <= n_sig;
      nq_den <= d_pos ? d_sig : '0;
      nq_sb  <= {in_q[PSB-1 -: PixBits], lane_sb, gi, issue_last};
    end
  end

  // ---- the divider lanes -------------------------------------------------------------------------
  logic                      lanes_out_valid, lanes_out_ready;
  logic [Lanes*QuotBits-1:0] r_sig;
  logic [Lanes*2-1:0]        r_exp;
  if (Algorithm == fxr_config_pkg::DivAlgorithmSharedRecip) begin : gen_shared
    logic unused_dbz;  // D <= 0 is a zero flag of every lane already
    fxr_div_shared_recip #(
      .NumBits      (NumBits),
      .DenBits      (DenBits),
      .QuotBits     (QuotBits),
      .SeedIndexBits(SeedIndexBits),
      .SeedBits     (SeedBits),
      .NrSteps      (NrSteps),
      .NrFracBits   (NrFracBits),
      .Lanes        (Lanes)
    ) u_lanes (
      .clk_i        (clk_i),
      .rst_ni       (rst_ni),
      .in_valid_i   (nq_valid & ~fifo_full),
      .in_ready_o   (lanes_in_ready),
      .in_num_i     (nq_num),
      .in_den_i     (nq_den),
      .out_valid_o  (lanes_out_valid),
      .out_ready_i  (lanes_out_ready),
      .out_sig_o    (r_sig),
      .out_exp_adj_o(r_exp),
      .out_dbz_o    (unused_dbz)
    );
  end else begin : gen_per_varying
    // Every lane sees the same handshake, so all lanes hold the same state: lane 0's is used.
    logic [Lanes-1:0] l_in_ready, l_out_valid, l_dbz;
    for (genvar l = 0; l < Lanes; l++) begin : gen_div
      fxr_div #(
        .Algorithm    (Algorithm),
        .NumBits      (NumBits),
        .DenBits      (DenBits),
        .QuotBits     (QuotBits),
        .SeedIndexBits(SeedIndexBits),
        .SeedBits     (SeedBits),
        .NrSteps      (NrSteps),
        .NrFracBits   (NrFracBits),
        .BitsPerStage (BitsPerStage),
        .Schedule     (Schedule)
      ) u_div (
        .clk_i        (clk_i),
        .rst_ni       (rst_ni),
        .in_valid_i   (nq_valid & ~fifo_full),
        .in_ready_o   (l_in_ready[l]),
        .in_num_i     (nq_num[l*NumBits +: NumBits]),
        .in_den_i     (nq_den),
        .out_valid_o  (l_out_valid[l]),
        .out_ready_i  (lanes_out_ready),
        .out_sig_o    (r_sig[l*QuotBits +: QuotBits]),
        .out_exp_adj_o(r_exp[l*2 +: 2]),
        .out_dbz_o    (l_dbz[l])
      );
    end
    assign lanes_in_ready  = l_in_ready[0];
    assign lanes_out_valid = l_out_valid[0];
    logic unused_lanes;  // the other lanes' handshake equals lane 0's; D <= 0 is a zero flag
    assign unused_lanes = ^{l_in_ready, l_out_valid, l_dbz};
  end

  // ---- sideband FIFO: one entry per group in the lanes -------------------------------------------
  logic [SBB-1:0]     fifo_mem [FifoDepth];
  logic [FifoBits:0]  wr_ptr, rd_ptr;
  logic [SBB-1:0]     head;
  logic               lanes_out_fire;
  assign fifo_full = (wr_ptr[FifoBits] != rd_ptr[FifoBits]) && (wr_ptr[FifoBits-1:0] == rd_ptr[FifoBits-1:0]);
  assign head      = fifo_mem[rd_ptr[FifoBits-1:0]];
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wr_ptr <= '0;
      rd_ptr <= '0;
    end else begin
      if (nq_fire) wr_ptr <= wr_ptr + 1'b1;
      if (lanes_out_fire) rd_ptr <= rd_ptr + 1'b1;
    end
  end
  always_ff @(posedge clk_i) begin
    if (nq_fire) fifo_mem[wr_ptr[FifoBits-1:0]] <= nq_sb;
  end

  // ---- results into the fragment -------------------------------------------------------------
  logic                    h_last;
  logic [GB-1:0]           h_group;
  logic [Lanes*LaneSB-1:0] h_lanes;
  logic [PixBits-1:0]      h_pix;
  assign {h_pix, h_lanes, h_group, h_last} = head;

  logic                          out_valid_q;
  logic                          out_free;
  logic [NumVaryings*VarB-1:0]   acc, vars;
  assign out_free        = ~out_valid_q | out_ready_i;
  assign lanes_out_ready = ~h_last | out_free;
  assign lanes_out_fire  = lanes_out_valid & lanes_out_ready;
  logic [Lanes-1:0]          l_neg, l_zero;
  logic [Lanes*XB-1:0]       l_e;  // the exponent with exp_adj
  for (genvar l = 0; l < Lanes; l++) begin : gen_res
    logic signed [XB-1:0] e_part;
    assign {l_neg[l], l_zero[l], e_part} = h_lanes[l*LaneSB +: LaneSB];
    assign l_e[l*XB +: XB] = e_part + XB'($signed(r_exp[l*2 +: 2]));
  end
  always_comb begin
    vars = acc;
    for (int l = 0; l < Lanes; l++) begin
      for (int m = 0; m < NumVaryings; m++) begin
        if (32'(h_group) * Lanes + l == m) begin
          vars[(NumVaryings - 1 - m) * VarB +: VarB] =
              l_zero[l] ? '0 : {l_neg[l], r_sig[l*QuotBits +: QuotBits], l_e[l*XB +: EB]};
        end
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (lanes_out_fire && !h_last) acc <= vars;
  end
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      out_valid_q <= 1'b0;
    end else if (out_free) begin
      out_valid_q <= lanes_out_fire & h_last;
    end
  end
  always_ff @(posedge clk_i) begin
    if (lanes_out_fire && h_last) out_flat <= {h_pix, vars};
  end
  assign out_valid_o = out_valid_q;
endmodule
