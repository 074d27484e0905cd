// fxr_pipe: a value delayed by Stages enabled clocks (a shift register without reset; the
// enclosing pipeline's valid bits qualify it). Stages = 0 passes the value through.
module fxr_pipe #(
  parameter int Width  = 1,
  parameter int Stages = 1
) (
  input  logic             clk_i,
  input  logic             en_i,
  // v_i[s]: the data entering register s is valid; register s loads only then (held otherwise:
  // nothing reads an invalid stage, and the simulator skips the copy)
  input  logic [(Stages > 0 ? Stages : 1)-1:0] v_i,
  input  logic [Width-1:0] d_i,
  output logic [Width-1:0] q_o
);
  if (Stages == 0) begin : g_wire
    assign q_o = d_i;
    logic unused_v;
    assign unused_v = ^{clk_i, en_i, v_i};
  end else begin : g_regs
    logic [Width-1:0] q [Stages];
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        if (v_i[0]) q[0] <= d_i;
        for (int s = 1; s < Stages; s++) if (v_i[s]) q[s] <= q[s-1];
      end
    end
    assign q_o = q[Stages-1];
  end
endmodule
