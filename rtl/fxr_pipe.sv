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
  end else if (Stages == 1) begin : g_reg
    logic [Width-1:0] q_l;
    always_ff @(posedge clk_i) begin
      if (en_i && v_i[0]) q_l <= d_i;
    end
    assign q_o = q_l;
  end else begin : g_regs
    // Stages 0 … Stages − 2 as one unpacked array written with blocking assignments in
    // descending order (each element is read, the register's value, before the stage below
    // overwrites it: the shift register of nonblocking assignments without a simulator's
    // delayed-assignment copy of every element; the array is read nowhere else), the last stage,
    // read by q_o, a nonblocking register. The form of fxr_viewport_lane (docs/rtl.md,
    // "Co-simulation speed", sessions 8 and 9); Yosys makes each element a register (mem2reg).
    (* mem2reg *) logic [Width-1:0] q [Stages-1];
    logic [Width-1:0] q_l;
    /* verilator lint_off BLKSEQ */
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        if (v_i[Stages-1]) q_l <= q[Stages-2];
        for (int s = Stages - 2; s >= 1; s--) if (v_i[s]) q[s] = q[s-1];
        if (v_i[0]) q[0] = d_i;
      end
    end
    /* verilator lint_on BLKSEQ */
    assign q_o = q_l;
  end
endmodule
