// vec_layout.svh — the vector-line layout rule (docs/vectors.md), for the testbenches' offsets:
// a field of w bits occupies pad(w) bits of the line (whole hex digits), the last field sits at
// bit 0, and each earlier field starts where the next one's padding ends.
  function automatic int pad(input int w);
    return 4 * ((w + 3) / 4);
  endfunction
