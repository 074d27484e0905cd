// vec_stream.svh — the part every plain-Verilog vector testbench shares (docs/vectors.md):
// load the vector file with $readmemh, drive the DUT's input handshake with random gaps, apply
// random output back-pressure, compare every output with the file in order, report.
//
// Included inside the testbench module after it has declared:
//   localparam Unit = "name";            the unit name for the report lines (a bit string)
//   localparam int WordBits;             bits of one vector line (manifest word_bits)
//   localparam int OutWordBits;          bits [OutWordBits-1:0] of a line are the outputs
//   logic [OutWordBits-1:0] got;         the DUT's outputs packed like a line (padding zero)
//   and instantiated the DUT on clk, rst_n, in_valid, in_ready, out_valid, out_ready and the
//   input fields of `cur` (the line on the input bus).
// Plusargs: +vectors=<ABSOLUTE path> ($readmemh resolves a relative path against the working
// directory of the simulator), +count=<manifest count> (a shorter file is an error), +seed=N.

  parameter int MaxVecs       = 1 << 16;
  parameter int GapPct        = 25;    // chance (%) that a new input waits one more cycle
  parameter int StallPct      = 25;    // chance (%) that out_ready is low
  parameter int TimeoutCycles = 2000;  // cycles without an output while one is owed

  logic [WordBits-1:0] mem [MaxVecs];
  logic clk = 1'b0, rst_n = 1'b0;
  logic in_valid = 1'b0, in_ready, out_valid, out_ready = 1'b0;
  logic [WordBits-1:0] cur = '0;

  always #5 clk = ~clk;

  string file;
  int count, loaded, seed, n_in, n_out, errors, idle, offered, scratch;

  initial begin
    if (!$value$plusargs("vectors=%s", file)) $fatal(1, "%s_tb: pass +vectors=<absolute path of the .hex>", Unit);
    if (!$value$plusargs("count=%d", count)) count = 0;
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    if (count > MaxVecs) $fatal(1, "%s_tb: %0d vectors, MaxVecs is %0d", Unit, count, MaxVecs);
    if (count > 0) $readmemh(file, mem, 0, count - 1);
    else $readmemh(file, mem);
    loaded = 0;
    while (loaded < MaxVecs && !$isunknown(mem[loaded])) loaded++;
    $display("%s_tb: %0d vectors of %0d bits from %s", Unit, loaded, WordBits, file);
    if (count > 0 && loaded != count) begin
      $display("%s_tb: %0d words loaded, the manifest says %0d (truncated file?)", Unit, loaded, count);
      $display("FAILED");
      $finish;
    end
    scratch = $urandom(seed);
    n_in = 0; n_out = 0; errors = 0; idle = 0; offered = -1;
    repeat (4) @(posedge clk);
    @(negedge clk) rst_n = 1'b1;
    wait (n_out == loaded || idle > TimeoutCycles);
    repeat (50) @(posedge clk);  // an output beyond the last vector is an error
    if (n_out < loaded) begin
      $display("%s_tb: TIMEOUT, %0d outputs missing", Unit, loaded - n_out);
      errors += loaded - n_out;
    end
    $display("%s: checked=%0d errors=%0d", Unit, n_out, errors);
    if (errors == 0 && n_out == loaded) $display("PASSED");
    else $display("FAILED");
    $finish;
  end

  // Transfers happen at the rising edge; the values were settled at the falling edge.
  always @(posedge clk) if (rst_n) begin
    idle++;
    if (in_valid && in_ready) n_in++;
    if (out_valid && out_ready) begin
      if (n_out >= loaded) begin
        errors++;
        $display("MISMATCH %s vec=%0d got=%h (extra output)", Unit, n_out, got);
      end else if (got !== mem[n_out][OutWordBits-1:0]) begin
        errors++;
        if (errors <= 20)
          $display("MISMATCH %s vec=%0d in=%h got=%h exp=%h", Unit, n_out, mem[n_out][WordBits-1:OutWordBits],
                   got, mem[n_out][OutWordBits-1:0]);
      end
      n_out++;
      idle = 0;
    end
  end

  // Next inputs at the falling edge: valid stays up until accepted; random gaps and stalls.
  always @(negedge clk) if (rst_n) begin
    if (in_valid && n_in > offered) in_valid = 1'b0;  // accepted at the last rising edge
    if (!in_valid && n_in < loaded && ($urandom % 100) >= GapPct) begin
      offered = n_in;
      cur = mem[n_in];
      in_valid = 1'b1;
    end
    out_ready = ($urandom % 100) >= StallPct;
  end
