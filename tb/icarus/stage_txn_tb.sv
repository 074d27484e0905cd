// stage_txn_tb: plain SystemVerilog testbench of one stage with record ports — fxr_clip,
// fxr_recip_stage (stage 3), fxr_viewport, fxr_setup, fxr_traverse, fxr_interp, fxr_depth or fxr_divide — driven by a transaction dump's S.in.hex and
// checked against its S.out.hex (docs/vectors.md, "Transaction vectors"), for Icarus 11: the
// `$readmemh` counterpart of tb/txn_harness.hpp. tb/icarus/run_stage_txn.cmake writes
// stage_txn_gen.svh (which stage, widths, counts, header offsets, the record of a line, the draw
// state) from the manifests and copies the RTL into the form Icarus 11 reads (docs/rtl.md).
//
// Rows of S.in are offered in order with random input gaps (interp: ctx_i = the record of the
// row's `ctx` line of setup.out, with the same handshake); outputs see random back-pressure; the
// i-th output must equal row i of S.out (the whole record; interp: out_last_o = the row's `last`),
// never before the input it came from (its txn) was accepted, none missing, none extra.
// fxr_setup: the cull pulses, fxr_recip_stage: err_o, fxr_viewport: rej_range_o must count the rows
// with n_out = 0; fxr_clip: out_last_o must be the row's `last`.
// fxr_depth: a memory behind its
// port (cleared to the maximum code, in-order responses after a random latency of 1..MaxLat,
// random request stalls; WritePort from the driver), and the final buffer must hold, at each pixel,
// the code of the last passing sample of S.out (depth write on) or the cleared code.
// +corrupt=N flips bit 0 of expected row N (from 1; the record's last field): exactly that
// MISMATCH and FAILED must follow.
//
// Plusargs: +in=<abs path> +out=<abs path> +ctx=<abs path of setup.out.hex> [+seed=N] [+corrupt=N]
`timescale 1ns / 1ps
module stage_txn_tb;
  parameter int GapPct        = 25;
  parameter int StallPct      = 25;
  parameter int MemStallPct   = 15;
  parameter int MaxLat        = 6;
  parameter int TimeoutCycles = 20000;

  `include "stage_txn_gen.svh"

  localparam int IdBits = 32;  // transaction ids and counts (model/vectors/scene_dump.hpp kTxnIdBits)
  localparam int PB     = fxr_config_pkg::RasterWindowIntBits;
`ifdef FXR_STAGE_INTERP
  localparam bit HasLast = 1'b1;  // out_last_o: the span's last sample (the dump's `last`)
`elsif FXR_STAGE_CLIP
  localparam bit HasLast = 1'b1;  // out_last_o: the primitive's last piece (the dump's `last`)
`else
  localparam bit HasLast = 1'b0;  // no out_last_o (as the Verilator harness: last checked where the DUT has it)
`endif

  logic [InWordBits-1:0]  in_mem  [NIn > 0 ? NIn : 1];
  logic [OutWordBits-1:0] out_mem [NOut > 0 ? NOut : 1];
  logic [CtxWordBits-1:0] ctx_mem [NCtx > 0 ? NCtx : 1];

  logic clk = 1'b0, rst_n = 1'b0, in_valid = 1'b0, in_ready, out_valid, out_ready = 1'b0, out_last;
  logic [InRecBits-1:0]  in_r = '0;
  logic [CtxRecBits-1:0] ctx_r = '0;
  logic [OutRecBits-1:0] out_r;
  wire accepted = in_valid && in_ready;

  always #5 clk = ~clk;

`ifdef FXR_STAGE_SETUP
  logic cull_valid;
  logic [2:0] cull_outcome;
  fxr_setup dut (
    .clk_i(clk), .rst_ni(rst_n), .in_valid_i(in_valid), .in_ready_o(in_ready), .in_i(in_r),
    .viewport_x_i(PB'(Ds_viewport_x)), .viewport_y_i(PB'(Ds_viewport_y)),
    .viewport_w_i((PB + 1)'(Ds_viewport_w)), .viewport_h_i((PB + 1)'(Ds_viewport_h)),
    .scissor_x_i(PB'(Ds_scissor_x)), .scissor_y_i(PB'(Ds_scissor_y)),
    .scissor_w_i((PB + 1)'(Ds_scissor_w)), .scissor_h_i((PB + 1)'(Ds_scissor_h)),
    .cull_i(2'(Ds_cull)), .front_ccw_i(1'(Ds_front_ccw)), .interp_i(1'(Ds_interp)),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_o(out_r),
    .cull_valid_o(cull_valid), .cull_outcome_o(cull_outcome)
  );
  assign out_last = 1'b1;
`elsif FXR_STAGE_RECIP
  logic cull_valid;  // err_o: a triangle dropped (RecipError), one pulse per row with n_out = 0
  fxr_recip_stage dut (
    .clk_i(clk), .rst_ni(rst_n), .in_valid_i(in_valid), .in_ready_o(in_ready), .in_i(in_r),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_o(out_r), .err_o(cull_valid)
  );
  assign out_last = 1'b1;
`elsif FXR_STAGE_CLIP
  logic done;
  logic [fxr_rec_pkg::ClipOutcomeBits-1:0] done_outcome;
  logic [$clog2(fxr_rec_pkg::ClipMaxPolyVerts * fxr_rec_pkg::ClipNumPlanes + 1)-1:0] done_created;
  fxr_clip dut (
    .clk_i(clk), .rst_ni(rst_n),
    .viewport_x_i(PB'(Ds_viewport_x)), .viewport_y_i(PB'(Ds_viewport_y)),
    .viewport_w_i((PB + 1)'(Ds_viewport_w)), .viewport_h_i((PB + 1)'(Ds_viewport_h)),
    .in_valid_i(in_valid), .in_ready_o(in_ready), .in_i(in_r),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_o(out_r), .out_last_o(out_last),
    .done_o(done), .done_outcome_o(done_outcome), .done_created_o(done_created)
  );
`elsif FXR_STAGE_VIEWPORT
  logic cull_valid;  // rej_range_o: a triangle dropped (RejectedRange), one pulse per row with n_out = 0
  fxr_viewport dut (
    .clk_i(clk), .rst_ni(rst_n), .in_valid_i(in_valid), .in_ready_o(in_ready), .in_i(in_r),
    .viewport_x_i(PB'(Ds_viewport_x)), .viewport_y_i(PB'(Ds_viewport_y)),
    .viewport_w_i((PB + 1)'(Ds_viewport_w)), .viewport_h_i((PB + 1)'(Ds_viewport_h)), .interp_i(1'(Ds_interp)),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_o(out_r), .rej_range_o(cull_valid)
  );
  assign out_last = 1'b1;
`elsif FXR_STAGE_TRAVERSE
  fxr_traverse dut (
    .clk_i(clk), .rst_ni(rst_n), .in_valid_i(in_valid), .in_ready_o(in_ready), .in_i(in_r),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_o(out_r)
  );
  assign out_last = 1'b1;
`elsif FXR_STAGE_INTERP
  fxr_interp dut (
    .clk_i(clk), .rst_ni(rst_n), .in_valid_i(in_valid), .in_ready_o(in_ready), .in_i(in_r), .ctx_i(ctx_r),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_o(out_r), .out_last_o(out_last)
  );
`elsif FXR_STAGE_DIVIDE
  fxr_divide dut (
    .clk_i(clk), .rst_ni(rst_n), .in_valid_i(in_valid), .in_ready_o(in_ready), .in_i(in_r),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_o(out_r)
  );
  assign out_last = 1'b1;
`elsif FXR_STAGE_DEPTH
  localparam int Cells = Ds_viewport_w * Ds_viewport_h;
  localparam int Db = OutWDepth;
  logic req_valid, req_ready = 1'b0, req_write, rsp_valid = 1'b0, wr_valid, wr_ready = 1'b0;
  logic [2 * PB-1:0] req_addr, wr_addr;
  logic [Db-1:0] req_wdata, wr_data, rsp_data = '0;
  fxr_depth #(.WritePort(WritePort)) dut (
    .clk_i(clk), .rst_ni(rst_n), .depth_func_i(3'(Ds_depth_func)), .depth_test_i(1'(Ds_depth_test)),
    .depth_write_i(1'(Ds_depth_write)), .viewport_x_i(PB'(Ds_viewport_x)), .viewport_y_i(PB'(Ds_viewport_y)),
    .viewport_w_i((PB + 1)'(Ds_viewport_w)),
    .in_valid_i(in_valid), .in_ready_o(in_ready), .in_i(in_r),
    .out_valid_o(out_valid), .out_ready_i(out_ready), .out_o(out_r),
    .mem_req_valid_o(req_valid), .mem_req_ready_i(req_ready), .mem_req_write_o(req_write),
    .mem_req_addr_o(req_addr), .mem_req_wdata_o(req_wdata), .mem_rsp_valid_i(rsp_valid),
    .mem_rsp_rdata_i(rsp_data), .mem_wr_valid_o(wr_valid), .mem_wr_ready_i(wr_ready),
    .mem_wr_addr_o(wr_addr), .mem_wr_data_o(wr_data)
  );
  assign out_last = 1'b1;
  // The memory: cleared to the maximum code; a request is performed when accepted (a read's
  // data taken then), responses in order, each at least one clock and at most MaxLat after its
  // request; the write channel's write is performed before a read accepted in the same clock.
  logic [Db-1:0] dmem [Cells];
  logic [Db-1:0] rq_data [64];
  int rq_time [64];
  int lat, rq_head = 0, rq_tail = 0, last_time = 0, cyc = 0, bad_addr = 0, reads = 0, writes = 0;
  initial for (int i = 0; i < Cells; i++) dmem[i] = '1;
  always @(posedge clk) if (rst_n) begin
    if (rsp_valid) rq_head = (rq_head + 1) % 64;
    if (wr_valid && wr_ready) begin
      if (wr_addr >= Cells) bad_addr++;
      else dmem[wr_addr] = wr_data;
      writes++;
    end
    if (req_valid && req_ready) begin
      if (req_addr >= Cells) bad_addr++;
      else if (req_write) begin
        dmem[req_addr] = req_wdata;
        writes++;
      end else begin
        rq_data[rq_tail] = dmem[req_addr];
        lat = 1 + $urandom % MaxLat;
        if (cyc + lat > last_time) last_time = cyc + lat;
        rq_time[rq_tail] = last_time;
        rq_tail = (rq_tail + 1) % 64;
        reads++;
      end
    end
    cyc++;
  end
  always @(negedge clk) begin
    rsp_valid = rq_head != rq_tail && rq_time[rq_head] <= cyc;
    rsp_data = rsp_valid ? rq_data[rq_head] : '0;
    req_ready = rst_n && ($urandom % 100) >= MemStallPct;
    wr_ready = rst_n && ($urandom % 100) >= MemStallPct;
  end
`else
  initial $fatal(1, "stage_txn_tb: stage_txn_gen.svh names no stage");
`endif

  string fin, fout, fctx;
  int seed, corrupt, scratch, n_in, n_out, errors, idle, offered, culled, want_culled;
  logic [IdBits-1:0] want_txn;
  logic [OutRecBits-1:0] want;
  string field;

  initial begin
    if (!$value$plusargs("in=%s", fin)) $fatal(1, "stage_txn_tb: +in=<absolute path of S.in.hex> missing");
    if (!$value$plusargs("out=%s", fout)) $fatal(1, "stage_txn_tb: +out=<absolute path of S.out.hex> missing");
    if (!$value$plusargs("ctx=%s", fctx)) $fatal(1, "stage_txn_tb: +ctx=<absolute path of setup.out.hex> missing");
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    if (!$value$plusargs("corrupt=%d", corrupt)) corrupt = 0;
    if (NIn > 0) $readmemh(fin, in_mem, 0, NIn - 1);
    if (NOut > 0) $readmemh(fout, out_mem, 0, NOut - 1);
    if (NCtx > 0) $readmemh(fctx, ctx_mem, 0, NCtx - 1);
    // (^word is x when a bit is x or z: a truncated file leaves the last rows unset)
    if ((NIn > 0 && (^in_mem[NIn - 1]) === 1'bx) || (NOut > 0 && (^out_mem[NOut - 1]) === 1'bx) ||
        (NCtx > 0 && (^ctx_mem[NCtx - 1]) === 1'bx)) begin
      $display("stage_txn_tb: fewer rows than the manifests say (truncated file?)");
      $display("FAILED");
      $finish;
    end
    if (corrupt > 0) out_mem[corrupt - 1][0] = ~out_mem[corrupt - 1][0];
    want_culled = 0;
    for (int i = 0; i < NIn; i++) if (in_mem[i][InNOutOff +: IdBits] == 0) want_culled++;
    $display("stage_txn_tb %s: %0d inputs from %s, %0d outputs from %s", `FXR_STAGE_NAME, NIn, fin, NOut, fout);
    scratch = $urandom(seed);
    n_in = 0; n_out = 0; errors = 0; idle = 0; offered = -1; culled = 0;
    repeat (4) @(posedge clk);
    @(negedge clk) rst_n = 1'b1;
    wait ((n_out == NOut && n_in == NIn) || idle > TimeoutCycles);
    repeat (400) @(posedge clk);  // an output beyond the last row is an error; the depth queue drains
    if (n_out < NOut || n_in < NIn) begin
      $display("stage_txn_tb: TIMEOUT, %0d inputs not accepted, %0d outputs missing", NIn - n_in, NOut - n_out);
      errors += NOut - n_out + (n_in < NIn ? 1 : 0);
    end
`ifdef FXR_STAGE_SETUP
    if (culled != want_culled) begin
      errors++;
      $display("MISMATCH setup cull pulses: %0d, the rows with n_out = 0: %0d", culled, want_culled);
    end
`endif
`ifdef FXR_STAGE_RECIP
  `define FXR_STAGE_DROPS
`endif
`ifdef FXR_STAGE_VIEWPORT
  `define FXR_STAGE_DROPS
`endif
`ifdef FXR_STAGE_DROPS
    if (culled != want_culled) begin
      errors++;
      $display("MISMATCH %s drop pulses: %0d, the rows with n_out = 0: %0d", `FXR_STAGE_NAME, culled, want_culled);
    end
`endif
`ifdef FXR_STAGE_DEPTH
    begin : final_buffer
      logic [Db-1:0] exp_buf [Cells];
      int bad_cells, x, y, a;
      for (int i = 0; i < Cells; i++) exp_buf[i] = '1;
      if (Ds_depth_test != 0 && Ds_depth_write != 0)
        for (int r = 0; r < NOut; r++) begin
          want = out_rec(out_mem[r]);
          x = $signed(want[OutPosX +: OutWX]);
          y = $signed(want[OutPosY +: OutWX]);
          a = (y - Ds_viewport_y) * Ds_viewport_w + (x - Ds_viewport_x);
          exp_buf[a] = want[OutPosDepth +: Db];
        end
      bad_cells = 0;
      for (int i = 0; i < Cells; i++) if (dmem[i] !== exp_buf[i]) bad_cells++;
      if (bad_cells != 0 || bad_addr != 0) begin
        errors++;
        $display("MISMATCH depth final buffer: %0d cells differ, %0d addresses outside the buffer", bad_cells, bad_addr);
      end
      $display("depth: %0d reads, %0d writes, write port %0d", reads, writes, WritePort);
    end
`endif
    $display("%s: inputs=%0d checked=%0d culled=%0d errors=%0d", `FXR_STAGE_NAME, n_in, n_out, culled, errors);
    if (errors == 0 && n_out == NOut) $display("PASSED");
    else $display("FAILED");
    $finish;
  end

  always @(posedge clk) if (rst_n) begin
    idle++;
`ifdef FXR_STAGE_SETUP
    if (cull_valid) culled++;
`endif
`ifdef FXR_STAGE_DROPS
    if (cull_valid) culled++;
`endif
    if (out_valid && out_ready) begin
      if (n_out >= NOut) begin
        errors++;
        $display("MISMATCH %s row=%0d extra output", `FXR_STAGE_NAME, n_out + 1);
      end else begin
        want_txn = out_mem[n_out][OutTxnOff +: IdBits];
        want = out_rec(out_mem[n_out]);
        if (want_txn >= n_in) begin  // n_in: inputs accepted before this edge
          errors++;
          $display("MISMATCH %s row=%0d early: txn %0d not accepted yet", `FXR_STAGE_NAME, n_out + 1, want_txn);
        end else if (out_r !== want || (HasLast && out_last !== out_mem[n_out][OutLastOff])) begin
          errors++;
          if (out_r !== want) field = out_diff(out_r, want);
          else field = "last";
          if (errors <= 20) $display("MISMATCH %s row=%0d txn=%0d field '%s'", `FXR_STAGE_NAME, n_out + 1, want_txn, field);
        end
      end
      n_out++;
      idle = 0;
    end
    if (accepted) begin
      n_in++;
      idle = 0;
    end
  end

  // Next inputs at the falling edge: valid stays up until accepted; random gaps and stalls.
  always @(negedge clk) if (rst_n) begin
    if (in_valid && n_in > offered) in_valid = 1'b0;  // accepted at the last rising edge
    if (!in_valid && n_in < NIn && ($urandom % 100) >= GapPct) begin
      offered = n_in;
      in_r = in_rec(in_mem[n_in]);
      if (NCtx > 0) ctx_r = ctx_rec(ctx_mem[in_mem[n_in][InCtxOff +: IdBits]]);
      in_valid = 1'b1;
    end
    out_ready = ($urandom % 100) >= StallPct;
  end
endmodule
