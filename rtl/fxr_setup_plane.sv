// fxr_setup_plane: one plane P(i, j) = c + (i - i0)*dx + (j - j0)*dy of stage 5, two register
// stages, instantiated by fxr_setup for depth, 1/w and every v/w. Model: make_attr_plane
// (model/stages/attr.cpp) and make_plane (model/stages/setup.cpp): with per-edge a_k, b_k, C_k and
// the step shift s from fxr_setup_attr and the vertex values q_k,
//   c = sum C_k*q_k,  dx = (sum a_k*q_k) * 2^s,  dy = (sum b_k*q_k) * 2^s   (exact)
// and, when post_m_i (the depth plane on the snapped triangle, whose vertex values are
// z_k*(2^PostBits - 1)), every result times 2^PostBits - 1 as a shift and a subtraction:
// sum E_k*(z_k*M) = M*(sum E_k*z_k), so the products stay z_frac_bits + 1 bits wide.
// Results are exact in IW bits and fit OutBits (the plane field width, validate()'s bound).
//   P1  the 9 products a_k*q_k, b_k*q_k, C_k*q_k
//   P2  the three sums, the step shift, the optional multiply by 2^PostBits - 1
module fxr_setup_plane #(
  parameter int AB       = 42,  // signed a_k, b_k
  parameter int CWB      = 82,  // signed C_k
  parameter int SHB      = 5,   // step shift
  parameter int QB       = 42,  // signed vertex values q_k
  parameter int PostBits = 0,   // > 0: post_m_i multiplies by 2^PostBits - 1
  parameter int OutBits  = 125  // signed plane fields
) (
  input  logic               clk_i,
  input  logic               en_i,
  input  logic [1:0]         v_i,       // v_i[s]: stage s's input is valid (else skipped)
  input  logic [3*AB-1:0]    a_i,
  input  logic [3*AB-1:0]    b_i,
  input  logic [3*CWB-1:0]   c_i,
  input  logic [SHB-1:0]     shift_i,
  input  logic [3*QB-1:0]    q_i,
  input  logic               post_m_i,
  output logic [OutBits-1:0] c_o,
  output logic [OutBits-1:0] dx_o,
  output logic [OutBits-1:0] dy_o
);
  localparam int ShMax = (1 << SHB) - 1;
  localparam int Top   = CWB > AB + ShMax ? CWB : AB + ShMax;
  localparam int IW    = Top + QB + PostBits + 3;  // every intermediate, exact
  localparam int PAW   = AB + QB;                   // a_k*q_k, b_k*q_k
  localparam int PCW   = CWB + QB;                  // C_k*q_k

  // ---- P1: products ---------------------------------------------------------------------------
  logic [3*PAW-1:0] pa_d, pb_d;
  logic [3*PCW-1:0] pc_d;
  always_comb begin
    pa_d = '0;
    pb_d = '0;
    pc_d = '0;
    if (v_i[0]) begin
      for (int k = 0; k < 3; k++) begin
        pa_d[k*PAW +: PAW] = PAW'($signed(a_i[k*AB +: AB])) * PAW'($signed(q_i[k*QB +: QB]));
        pb_d[k*PAW +: PAW] = PAW'($signed(b_i[k*AB +: AB])) * PAW'($signed(q_i[k*QB +: QB]));
        pc_d[k*PCW +: PCW] = PCW'($signed(c_i[k*CWB +: CWB])) * PCW'($signed(q_i[k*QB +: QB]));
      end
    end
  end

  logic [3*PAW-1:0] pa_q, pb_q;
  logic [3*PCW-1:0] pc_q;
  logic [SHB-1:0]   shift_q;
  logic             post_q;
  always_ff @(posedge clk_i) begin
    if (en_i && v_i[0]) begin
      pa_q    <= pa_d;
      pb_q    <= pb_d;
      pc_q    <= pc_d;
      shift_q <= shift_i;
      post_q  <= post_m_i;
    end
  end

  // ---- P2: sums, step shift, times 2^PostBits - 1 -------------------------------------------
  logic signed [IW-1:0] sa, sb, sc;
  always_comb begin
    sa = '0;
    sb = '0;
    sc = '0;
    if (v_i[1]) begin
      for (int k = 0; k < 3; k++) begin
        sa = sa + IW'($signed(pa_q[k*PAW +: PAW]));
        sb = sb + IW'($signed(pb_q[k*PAW +: PAW]));
        sc = sc + IW'($signed(pc_q[k*PCW +: PCW]));
      end
      sa = sa <<< shift_q;
      sb = sb <<< shift_q;
      if (PostBits > 0 && post_q) begin
        sa = (sa <<< PostBits) - sa;
        sb = (sb <<< PostBits) - sb;
        sc = (sc <<< PostBits) - sc;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i && v_i[1]) begin
      c_o  <= OutBits'(sc);
      dx_o <= OutBits'(sa);
      dy_o <= OutBits'(sb);
    end
  end
endmodule
