// line_tb: plain Verilog testbench of fxr_line (a segment in, a pixel stream out) under Icarus,
// self-checking against a reference written in this file from the rules' definitions
// (docs/lines.md), not from the RTL: no decision variable, no stepping, no canonical frame.
//   midpoint:     per major-axis centre c in the endpoint range ([min, max) or [min, max]), the
//                 row j with j·u < b*(c) ≤ (j+1)·u, b*(c) the exact rational minor coordinate;
//   diamond exit: the segment meets the open diamond |x − x_f| + |y − y_f| < ½ (minimum of the
//                 convex L1 distance at t = 0, 1 and where x(t) or y(t) equals the centre's) and
//                 p_b is not inside it.
// The vector format is one output per input, so fxr_line (1 → n) has no vector file: segments
// are drawn here with a xorshift generator of its own (+seed=N), in classes (random, axis-aligned, 45°, sub-pixel,
// endpoints on centres, on ties), inputs with random gaps, outputs with random back-pressure.
// Every produced pixel must satisfy the rule, none twice, as many as the rule gives (counted
// over the candidate box); midpoint pixels must come in increasing major coordinate.
// +corrupt=1 moves one produced pixel: the bench must then report exactly one MISMATCH.
// Prints `line: checked=N pixels=P errors=M` and PASSED / FAILED.
//
//   iverilog -g2012 -s line_tb -y rtl -Y .sv build/gen/fxr_config_pkg.sv rtl/fxr_line.sv \
//            tb/icarus/line_tb.sv [-P line_tb.Rule=1] [-P line_tb.Endpoints=1]
//   vvp -n a.out [+seed=N] [+count=N] [+corrupt=1]
`timescale 1ns / 1ps
module line_tb;
  parameter int Rule      = fxr_config_pkg::LineRule;
  parameter int Endpoints = fxr_config_pkg::LineEndpoints;
  localparam int S  = fxr_config_pkg::RasterSubpixelBits;
  localparam int W  = fxr_config_pkg::RasterWindowIntBits;
  localparam int CB = W + S;
  localparam longint U = longint'(2) << S;  // one pixel, doubled units
  localparam longint H = longint'(1) << S;  // half a pixel
  localparam bit Midpoint = Rule == fxr_config_pkg::LineRuleMidpoint;
  localparam bit Closed   = Endpoints == fxr_config_pkg::LineEndpointsClosed;
  localparam int MaxPix   = 1024;

  logic clk = 0, rst_n = 0;
  always #5 clk = ~clk;

  logic in_valid = 0, in_ready, out_valid, out_ready = 0;
  logic signed [CB-1:0] x0, y0, x1, y1;
  logic signed [W-1:0] ox, oy;

  fxr_line #(.Rule(Rule), .Endpoints(Endpoints)) dut (
    .clk_i(clk), .rst_ni(rst_n),
    .in_valid_i(in_valid), .in_ready_o(in_ready),
    .in_x0_i(x0), .in_y0_i(y0), .in_x1_i(x1), .in_y1_i(y1),
    .out_valid_o(out_valid), .out_ready_i(out_ready),
    .out_x_o(ox), .out_y_o(oy));

  // ---- the reference ---------------------------------------------------------------------------
  function automatic longint fdiv(longint a, longint b);  // floor, b > 0
    longint q;
    q = a / b;
    if (a % b != 0 && a < 0) q = q - 1;
    return q;
  endfunction
  function automatic longint iabs(longint v);
    return v < 0 ? -v : v;
  endfunction

  longint X0, Y0, X1, Y1;  // doubled endpoints of the current segment
  bit ymaj;

  // Midpoint: is (i, j) the pixel of its major-axis centre?
  function automatic bit mid_produced(longint px, longint py);
    longint A0, B0, A1, B1, lo, hi, i, j, c, N, Q;
    A0 = ymaj ? Y0 : X0; B0 = ymaj ? X0 : Y0; A1 = ymaj ? Y1 : X1; B1 = ymaj ? X1 : Y1;
    i = ymaj ? py : px;
    j = ymaj ? px : py;
    lo = A0 < A1 ? A0 : A1;
    hi = A0 < A1 ? A1 : A0;
    c = i * U + H;
    if (c < lo || c > hi || (c == hi && !Closed)) return 0;
    if (A1 == A0) begin
      N = B0; Q = 1;
    end else begin
      Q = A1 - A0; N = B0 * Q + (c - A0) * (B1 - B0);
      if (Q < 0) begin Q = -Q; N = -N; end
    end
    return j == -fdiv(-N, U * Q) - 1;
  endfunction

  // q·L1(P(p/q), C) < h·q
  function automatic bit below(longint p, longint q, longint cx, longint cy);
    return iabs(q * (X0 - cx) + p * (X1 - X0)) + iabs(q * (Y0 - cy) + p * (Y1 - Y0)) < H * q;
  endfunction
  function automatic bit dia_produced(longint px, longint py);
    longint cx, cy, p, q;
    bit hit;
    cx = px * U + H;
    cy = py * U + H;
    hit = below(0, 1, cx, cy) || below(1, 1, cx, cy);
    if (!hit && X1 != X0) begin
      p = cx - X0; q = X1 - X0;
      if (q < 0) begin p = -p; q = -q; end
      if (p >= 0 && p <= q && below(p, q, cx, cy)) hit = 1;
    end
    if (!hit && Y1 != Y0) begin
      p = cy - Y0; q = Y1 - Y0;
      if (q < 0) begin p = -p; q = -q; end
      if (p >= 0 && p <= q && below(p, q, cx, cy)) hit = 1;
    end
    return hit && iabs(X1 - cx) + iabs(Y1 - cy) >= H;
  endfunction

  function automatic bit produced(longint px, longint py);
    return Midpoint ? mid_produced(px, py) : dia_produced(px, py);
  endfunction

  function automatic longint ref_count();
    longint n, i, j, ix0, ix1, iy0, iy1;
    n = 0;
    ix0 = fdiv(X0 < X1 ? X0 : X1, U) - 1; ix1 = fdiv(X0 < X1 ? X1 : X0, U) + 1;
    iy0 = fdiv(Y0 < Y1 ? Y0 : Y1, U) - 1; iy1 = fdiv(Y0 < Y1 ? Y1 : Y0, U) + 1;
    for (i = ix0; i <= ix1; i++)
      for (j = iy0; j <= iy1; j++)
        if (produced(i, j)) n++;
    return n;
  endfunction

  // ---- segments ------------------------------------------------------------------------------
  // xorshift64* (the bench's own generator: the same segments under every simulator).
  logic [63:0] state = 64'h9e3779b97f4a7c15 ^ 64'd1;
  function automatic logic [31:0] rnd32();
    logic [63:0] x;
    x = state;
    x = x ^ (x >> 12);
    x = x ^ (x << 25);
    x = x ^ (x >> 27);
    state = x;
    return 32'((x * 64'h2545F4914F6CDD1D) >> 32);
  endfunction
  function automatic longint smag(int bits);  // uniform in (−2^bits, 2^bits)
    longint m;
    m = longint'(rnd32()) & ((longint'(1) << bits) - 1);
    return (rnd32() & 1) ? -m : m;
  endfunction
  function automatic longint snap(longint v, bit centre);  // onto a pixel edge or centre
    return fdiv(v, longint'(1) << S) * (longint'(1) << S) + (centre ? (longint'(1) << (S - 1)) : 0);
  endfunction

  task automatic make_segment(int cls, output longint sx0, sy0, sx1, sy1);
    longint d;
    int unsigned m;
    sx0 = smag(S + 6); sy0 = smag(S + 6);
    case (cls)
      0: begin sx1 = sx0 + smag(S + 5); sy1 = sy0 + smag(S + 5); end
      1: if (rnd32() & 1) begin sx1 = sx0 + smag(S + 5); sy1 = sy0; end
         else begin sx1 = sx0; sy1 = sy0 + smag(S + 5); end
      2: begin d = smag(S + 5); sx1 = sx0 + d; sy1 = sy0 + ((rnd32() & 1) ? d : -d); end
      3: begin sx1 = sx0 + smag(S); sy1 = sy0 + smag(S); end
      default: begin  // 4: endpoints on centres, 5: on ties (edges, corners, 45° through them)
        m = rnd32();
        sx0 = snap(sx0, cls == 4 || m[0]); sy0 = snap(sy0, cls == 4 || m[1]);
        sx1 = snap(sx0 + smag(S + 4), cls == 4 || m[2]); sy1 = snap(sy0 + smag(S + 4), cls == 4 || m[3]);
        if (m[4]) sy1 = sy0 + (m[5] ? 1 : -1) * (sx1 - sx0);
      end
    endcase
  endtask

  // ---- the run -------------------------------------------------------------------------------
  int unsigned seed = 1, count = 3000, corrupt = 0;
  longint checked = 0, pixels = 0, errors = 0, shown = 0;
  longint gx[MaxPix], gy[MaxPix];
  int ng;

  task automatic mismatch(string what, longint px, longint py);
    errors++;
    if (shown < 20) begin
      shown++;
      $display("MISMATCH line seg=%0d in=(%0d,%0d)-(%0d,%0d) pixel=(%0d,%0d) %s", checked, X0 / 2, Y0 / 2, X1 / 2,
               Y1 / 2, px, py, what);
    end
  endtask

  initial begin
    longint sx0, sy0, sx1, sy1, n_ref, k, l, prev;
    bit bad, go;
    if ($value$plusargs("seed=%d", seed)) state = 64'h9e3779b97f4a7c15 ^ seed;
    if ($value$plusargs("count=%d", count)) ;
    if ($value$plusargs("corrupt=%d", corrupt)) ;
    repeat (3) @(posedge clk);
    rst_n = 1;
    for (int t = 0; t < count; t++) begin
      make_segment(t % 6, sx0, sy0, sx1, sy1);
      X0 = 2 * sx0; Y0 = 2 * sy0; X1 = 2 * sx1; Y1 = 2 * sy1;
      ymaj = iabs(Y1 - Y0) > iabs(X1 - X0);
      // Input with a random gap; outputs collected with random back-pressure until idle again.
      // Inputs change and outputs are sampled at the falling edge (stable for the rising one).
      repeat (rnd32() % 3) @(negedge clk);
      @(negedge clk);
      x0 = sx0; y0 = sy0; x1 = sx1; y1 = sy1;
      in_valid = 1;
      go = 0;
      while (!go) begin
        go = in_ready;
        @(posedge clk);
        @(negedge clk);
      end
      in_valid = 0;
      ng = 0;
      while (!(in_ready && !out_valid)) begin
        out_ready = (rnd32() % 4) != 0;
        if (out_valid && out_ready && ng < MaxPix) begin
          gx[ng] = ox; gy[ng] = oy; ng++;
        end
        @(posedge clk);
        @(negedge clk);
      end
      out_ready = 0;
      if (corrupt != 0 && t == 17 && ng > 0) gy[0] = gy[0] + 1;  // one moved pixel
      // Check: each pixel produced by the rule, no duplicates, midpoint in order, the count.
      bad = 0;
      for (k = 0; k < ng; k++) begin
        if (!produced(gx[k], gy[k])) begin mismatch("not produced by the rule", gx[k], gy[k]); bad = 1; end
        for (l = 0; l < k; l++)
          if (gx[l] == gx[k] && gy[l] == gy[k]) begin mismatch("twice", gx[k], gy[k]); bad = 1; end
        if (Midpoint && k > 0) begin
          prev = ymaj ? gy[k - 1] : gx[k - 1];
          if ((ymaj ? gy[k] : gx[k]) <= prev) begin mismatch("out of order", gx[k], gy[k]); bad = 1; end
        end
      end
      n_ref = ref_count();
      if (!bad && n_ref != ng) mismatch($sformatf("count %0d, expected %0d", ng, n_ref), 0, 0);
      checked++;
      pixels += ng;
    end
    if (Midpoint && Closed) $write("line: rule=midpoint endpoints=closed");
    else if (Midpoint) $write("line: rule=midpoint endpoints=half_open");
    else $write("line: rule=diamond_exit");
    $display(" checked=%0d pixels=%0d errors=%0d", checked, pixels, errors);
    if (errors == 0) $display("PASSED");
    else $display("FAILED");
    $finish;
  end
endmodule
