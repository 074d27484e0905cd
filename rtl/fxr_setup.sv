// fxr_setup: stage 5, triangle setup (issue 10). One snapped triangle and the draw state in, its
// equations out. Model: fxr::SetupStage (model/stages/setup.hpp, setup.cpp, attr.cpp); rules and
// figures: docs/pipeline.md, stage 5 and "Attribute positions"; vectors: vectors/setup/
// (model/vectors/setup_vectors.hpp: the port list is the vector layout, fields + _i / _o).
//
// Ports:
//   clk_i, rst_ni                      clock, active-low asynchronous reset
//   in_valid_i / in_ready_o            input handshake (transfer when both are high)
//   prim_i                             primitive index (passes through to out_prim_o)
//   v<k>_x_i, v<k>_y_i [XB]            snapped window position, signed, SubpixelBits fraction bits
//   v<k>_ax_i, v<k>_ay_i [AXB]         attribute position, signed, AttrSubpixelBits fraction bits
//   v<k>_z_i [ZB]                      z/w, ZFracBits fraction bits (more than 1: range)
//   v<k>_rw_*, v<k>_vw<m>_*            1/w and v_m/w: sign, significand (msb set, or 0), lsb exponent
//   viewport_*_i, scissor_*_i          draw rectangle (pixels); scissor off when a size is negative
//   cull_i (cull_e), front_ccw_i, interp_i (1 = affine)
//   out_valid_o / out_ready_i          output handshake
//   outcome_o                          outcome_e: ok, zero area, back face, no samples, range (the
//                                      model's precedence); when not ok every other output is 0
//   out_prim_o                         prim_i of the triangle
//   e<k>_a_o, e<k>_b_o, e<k>_c_o       edge function k (opposite vertex k) on the sample grid,
//                                      counter-clockwise normalised (E_k >= 0 inside)
//   e<k>_bias_o                        top-left bias (1 = -1: not a top or left edge)
//   area2_o, front_o                   2A (> 0), front-facing
//   x0_o, x1_o, y0_o, y1_o             candidate pixels (inclusive): bounding box ∩ viewport ∩
//                                      scissor ∩ window range
//
// Latency (cycles from the input transfer to out_valid_o, = SetupStage::cost().latency): 3 (the
// coverage stages of fxr_setup_edges). Initiation interval 1. out_ready_i low stalls every stage
// (in_ready_o = out_ready_i | ~out_valid_o); no result is lost or duplicated.
module fxr_setup #(
  parameter int SubpixelBits     = fxr_config_pkg::RasterSubpixelBits,
  parameter int WindowIntBits    = fxr_config_pkg::RasterWindowIntBits,
  parameter int ZFracBits        = fxr_config_pkg::RasterZFracBits,
  parameter int AttrSubpixelBits = fxr_config_pkg::RasterAttrSubpixelBits,
  parameter int AttrSigBits      = fxr_config_pkg::RasterAttrSigBits,
  parameter int VaryingSigBits   = fxr_config_pkg::RasterVaryingSigBits,
  parameter int RecipOutSigBits  = fxr_config_pkg::RecipOutSigBits,
  parameter int RecipExpBits     = fxr_config_pkg::RecipExpBits,
  // derived (model/stages/setup.hpp, model/unit/record.hpp)
  localparam bit Attr       = AttrSubpixelBits > SubpixelBits,   // attribute planes (attr_planes)
  localparam int G          = SubpixelBits > 0 ? SubpixelBits : 1,
  localparam int XB         = WindowIntBits + SubpixelBits,      // snapped position
  localparam int AXB        = WindowIntBits + AttrSubpixelBits,  // attribute position
  localparam int ZB         = ZFracBits + 1,
  localparam int CB         = WindowIntBits + G,                 // coord_bits
  localparam int ECB        = CB + 1,                            // edge_coef_bits
  localparam int EVB        = 2 * CB + 2,                        // edge_value_bits
  localparam int RwSigBits  = Attr ? AttrSigBits : RecipOutSigBits,
  localparam int VwSigBits  = Attr ? AttrSigBits : VaryingSigBits,
  // fx_exp_field_bits: max(recip.exp_bits, float32 exponent bits + 1) + 2
  localparam int F32ExpBits = 8,
  localparam int EB         = (RecipExpBits > F32ExpBits + 1 ? RecipExpBits : F32ExpBits + 1) + 2,
  localparam int PrimBits   = 32,                                // kPrimIdBits
  localparam int PB         = WindowIntBits                      // pixel index
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  input  logic                      in_valid_i,
  output logic                      in_ready_o,
  input  logic [PrimBits-1:0]       prim_i,
  /* verilator lint_off UNUSEDSIGNAL */
  input  logic [XB-1:0]             v0_x_i,
  input  logic [XB-1:0]             v0_y_i,
  input  logic [AXB-1:0]            v0_ax_i,
  input  logic [AXB-1:0]            v0_ay_i,
  input  logic [ZB-1:0]             v0_z_i,
  input  logic                      v0_rw_neg_i,
  input  logic [RwSigBits-1:0]      v0_rw_sig_i,
  input  logic [EB-1:0]             v0_rw_exp_i,
  input  logic                      v0_vw0_neg_i,
  input  logic [VwSigBits-1:0]      v0_vw0_sig_i,
  input  logic [EB-1:0]             v0_vw0_exp_i,
  input  logic                      v0_vw1_neg_i,
  input  logic [VwSigBits-1:0]      v0_vw1_sig_i,
  input  logic [EB-1:0]             v0_vw1_exp_i,
  input  logic [XB-1:0]             v1_x_i,
  input  logic [XB-1:0]             v1_y_i,
  input  logic [AXB-1:0]            v1_ax_i,
  input  logic [AXB-1:0]            v1_ay_i,
  input  logic [ZB-1:0]             v1_z_i,
  input  logic                      v1_rw_neg_i,
  input  logic [RwSigBits-1:0]      v1_rw_sig_i,
  input  logic [EB-1:0]             v1_rw_exp_i,
  input  logic                      v1_vw0_neg_i,
  input  logic [VwSigBits-1:0]      v1_vw0_sig_i,
  input  logic [EB-1:0]             v1_vw0_exp_i,
  input  logic                      v1_vw1_neg_i,
  input  logic [VwSigBits-1:0]      v1_vw1_sig_i,
  input  logic [EB-1:0]             v1_vw1_exp_i,
  input  logic [XB-1:0]             v2_x_i,
  input  logic [XB-1:0]             v2_y_i,
  input  logic [AXB-1:0]            v2_ax_i,
  input  logic [AXB-1:0]            v2_ay_i,
  input  logic [ZB-1:0]             v2_z_i,
  input  logic                      v2_rw_neg_i,
  input  logic [RwSigBits-1:0]      v2_rw_sig_i,
  input  logic [EB-1:0]             v2_rw_exp_i,
  input  logic                      v2_vw0_neg_i,
  input  logic [VwSigBits-1:0]      v2_vw0_sig_i,
  input  logic [EB-1:0]             v2_vw0_exp_i,
  input  logic                      v2_vw1_neg_i,
  input  logic [VwSigBits-1:0]      v2_vw1_sig_i,
  input  logic [EB-1:0]             v2_vw1_exp_i,
  input  logic                      interp_i,
  /* verilator lint_on UNUSEDSIGNAL */
  input  logic [WindowIntBits-1:0]  viewport_x_i,
  input  logic [WindowIntBits-1:0]  viewport_y_i,
  input  logic [WindowIntBits:0]    viewport_w_i,
  input  logic [WindowIntBits:0]    viewport_h_i,
  input  logic [WindowIntBits-1:0]  scissor_x_i,
  input  logic [WindowIntBits-1:0]  scissor_y_i,
  input  logic [WindowIntBits:0]    scissor_w_i,
  input  logic [WindowIntBits:0]    scissor_h_i,
  input  logic [1:0]                cull_i,
  input  logic                      front_ccw_i,
  output logic                      out_valid_o,
  input  logic                      out_ready_i,
  output logic [2:0]                outcome_o,
  output logic [PrimBits-1:0]       out_prim_o,
  output logic [ECB-1:0]            e0_a_o,
  output logic [ECB-1:0]            e0_b_o,
  output logic [EVB-1:0]            e0_c_o,
  output logic                      e0_bias_o,
  output logic [ECB-1:0]            e1_a_o,
  output logic [ECB-1:0]            e1_b_o,
  output logic [EVB-1:0]            e1_c_o,
  output logic                      e1_bias_o,
  output logic [ECB-1:0]            e2_a_o,
  output logic [ECB-1:0]            e2_b_o,
  output logic [EVB-1:0]            e2_c_o,
  output logic                      e2_bias_o,
  output logic [EVB-1:0]            area2_o,
  output logic                      front_o,
  output logic [PB-1:0]             x0_o,
  output logic [PB-1:0]             x1_o,
  output logic [PB-1:0]             y0_o,
  output logic [PB-1:0]             y1_o
);
  localparam int EdgeStages = 3;          // fxr_setup_edges
  localparam int Latency    = EdgeStages;
  localparam int Last       = Latency - 1;

  // ---- handshake: one global enable, the pipeline holds while the output is stalled --------
  logic [Latency-1:0] valid_q;
  logic               advance;
  assign advance     = out_ready_i | ~valid_q[Last];
  assign in_ready_o  = advance;
  assign out_valid_o = valid_q[Last];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= '0;
    end else if (advance) begin
      valid_q <= {valid_q[Last-1:0], in_valid_i};
    end
  end

  // ---- coverage: edges, 2A, culling, candidate rectangle ------------------------------------
  logic [2:0]          outcome;
  logic [3*ECB-1:0]    ea, eb;
  logic [3*EVB-1:0]    ec;
  logic [2:0]          ebias;
  logic [EVB-1:0]      area2;
  logic                front;
  logic [PB-1:0]       bx0, bx1, by0, by1;

  fxr_setup_edges #(
    .SubpixelBits (SubpixelBits),
    .WindowIntBits(WindowIntBits),
    .ZFracBits    (ZFracBits)
  ) u_edges (
    .clk_i       (clk_i),
    .en_i        (advance),
    .x_i         ({v2_x_i, v1_x_i, v0_x_i}),
    .y_i         ({v2_y_i, v1_y_i, v0_y_i}),
    .z_i         ({v2_z_i, v1_z_i, v0_z_i}),
    .viewport_x_i(viewport_x_i),
    .viewport_y_i(viewport_y_i),
    .viewport_w_i(viewport_w_i),
    .viewport_h_i(viewport_h_i),
    .scissor_x_i (scissor_x_i),
    .scissor_y_i (scissor_y_i),
    .scissor_w_i (scissor_w_i),
    .scissor_h_i (scissor_h_i),
    .cull_i      (cull_i),
    .front_ccw_i (front_ccw_i),
    .outcome_o   (outcome),
    .a_o         (ea),
    .b_o         (eb),
    .c_o         (ec),
    .bias_o      (ebias),
    .area2_o     (area2),
    .front_o     (front),
    .x0_o        (bx0),
    .x1_o        (bx1),
    .y0_o        (by0),
    .y1_o        (by1)
  );

  // prim travels beside the stages.
  logic [Latency*PrimBits-1:0] prim_q;
  always_ff @(posedge clk_i) begin
    if (advance) prim_q <= {prim_q[(Latency-1)*PrimBits-1:0], prim_i};
  end

  // ---- outputs: 0 unless the triangle is drawn ----------------------------------------------
  logic ok;
  assign ok        = outcome == 3'd0;  // fxr_setup_edges::OutcomeOk
  assign outcome_o  = outcome;
  assign out_prim_o = ok ? prim_q[Last*PrimBits +: PrimBits] : '0;
  assign e0_a_o     = ok ? ea[0*ECB +: ECB] : '0;
  assign e0_b_o     = ok ? eb[0*ECB +: ECB] : '0;
  assign e0_c_o     = ok ? ec[0*EVB +: EVB] : '0;
  assign e0_bias_o  = ok & ebias[0];
  assign e1_a_o     = ok ? ea[1*ECB +: ECB] : '0;
  assign e1_b_o     = ok ? eb[1*ECB +: ECB] : '0;
  assign e1_c_o     = ok ? ec[1*EVB +: EVB] : '0;
  assign e1_bias_o  = ok & ebias[1];
  assign e2_a_o     = ok ? ea[2*ECB +: ECB] : '0;
  assign e2_b_o     = ok ? eb[2*ECB +: ECB] : '0;
  assign e2_c_o     = ok ? ec[2*EVB +: EVB] : '0;
  assign e2_bias_o  = ok & ebias[2];
  assign area2_o    = ok ? area2 : '0;
  assign front_o    = ok & front;
  assign x0_o       = ok ? bx0 : '0;
  assign x1_o       = ok ? bx1 : '0;
  assign y0_o       = ok ? by0 : '0;
  assign y1_o       = ok ? by1 : '0;
endmodule
