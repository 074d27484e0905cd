// model/config/raster_config.hpp — number formats of the raster unit shared by the geometry stages
// (clipper, perspective divide, viewport snap) and the raster stages (setup, traversal,
// interpolators, depth, divider). docs/pipeline.md derives each default.
#pragma once

#include <cstdint>

namespace fxr {

enum class DepthFormat : uint8_t { D16, D24 };

struct RasterConfig {
  // Window x, y fraction bits. 8: D3D11 (16.8), Vulkan subPixelPrecisionBits in practice.
  int subpixel_bits = 8;
  // Signed integer bits of snapped window coordinates (guard band included):
  // 16 → ±32768 px, D3D11's 16.8 range. Edge coefficients need window_int_bits + subpixel_bits + 1
  // bits, edge values about twice that (docs/references.md#widths: 25 and 50 bits at 16.8).
  int window_int_bits = 16;
  // Significand bits of the clipper's new x_c, y_c, z_c and varyings (w_c uses recip.in_sig_bits).
  // 32: 8 bits beyond float32 so the ½-ulp rounding of a clipped x_c moves the window
  // coordinate by ≤ 2^15 px · 2^−32 ≪ one 2^−8 subpixel (docs/pipeline.md, stage 2).
  int clip_sig_bits = 32;
  // Fraction bits of the per-vertex depth z_c / w_c ∈ [0, 1] handed to setup.
  int z_frac_bits = 32;
  // Significand bits of the per-vertex v · (1/w) handed to setup.
  int varying_sig_bits = 24;
  // Significand bits of the perspective-correct varyings leaving the unit (float32: 24).
  int varying_out_sig_bits = 24;
  DepthFormat depth_format = DepthFormat::D24;
  // Width of the per-triangle block-aligned integers of 1/w and of each v/w (interpolators,
  // stage 7): the largest of the three vertex values has its msb at bit interp_block_bits − 1,
  // the others are shifted right to the same block exponent (RNE; exact while the three lead
  // exponents differ by at most interp_block_bits − significand bits, i.e. w ratios up to
  // 2^16 at the defaults 40 and 24). docs/pipeline.md, stage 7.
  int interp_block_bits = 40;
  // Fraction bits of the window x, y the depth and varying planes are set up from (issue 8;
  // docs/pipeline.md, "Attribute positions"). Coverage keeps the snapped subpixel_bits positions.
  // At most subpixel_bits: the planes use the snapped positions and z = RNE(z_c·rcp(w_c)), the
  // model before issue 8, bit for bit. Larger: x_c/w_c, y_c/w_c, z_c/w_c, 1/w_c and v/w_c are
  // divided exactly and rounded once (x, y to attr_subpixel_bits, z to z_frac_bits, 1/w and
  // v/w to attr_sig_bits). 24: docs/pipeline.md,
  // "Attribute positions" (position error ≤ 2^−25 px: ½ D24 LSB needs a depth gradient of a
  // whole depth range per pixel before it shows).
  int attr_subpixel_bits = 24;
  // Signed bits of the triangle-relative attribute coordinates (vertices and candidate pixel
  // centres relative to vertex 0): a triangle whose extent needs more drops fraction bits below
  // attr_subpixel_bits. Edge values of the attribute planes take 2·attr_coord_bits + 2 bits, the
  // 1/w and v/w planes 2·attr_coord_bits + interp_block_bits + 5 (125 at 40, within i128).
  int attr_coord_bits = 40;
  // Significand bits of the per-vertex 1/w and v/w of the attribute path (exact quotients rounded
  // once; the snapped path keeps recip.out_sig_bits and varying_sig_bits). A perspective-correct
  // varying mixes the three v/w: a result much smaller than the largest vertex term inherits
  // that term's rounding, so 8 bits beyond float32 keep it below an output ulp.
  int attr_sig_bits = 32;

  int depth_bits() const { return depth_format == DepthFormat::D16 ? 16 : 24; }

  template <class V>
  void visit(V& v) {
    v.integer("subpixel_bits", subpixel_bits, 0, 12, "fraction bits of snapped window x, y");
    v.integer("window_int_bits", window_int_bits, 8, 20, "signed integer bits of window x, y (guard band included)");
    v.integer("clip_sig_bits", clip_sig_bits, 16, 60, "significand bits of clipper-made x, y, z and varyings");
    v.integer("z_frac_bits", z_frac_bits, 16, 40, "fraction bits of per-vertex depth z/w in [0,1]");
    v.integer("varying_sig_bits", varying_sig_bits, 8, 40, "significand bits of per-vertex v/w");
    v.integer("varying_out_sig_bits", varying_out_sig_bits, 8, 32, "significand bits of output varyings");
    v.choice("depth_format", depth_format, {"d16", "d24"}, "depth buffer format (unorm)");
    v.integer("interp_block_bits", interp_block_bits, 16, 62, "width of block-aligned per-triangle 1/w and v/w integers");
    v.integer("attr_subpixel_bits", attr_subpixel_bits, 0, 40,
              "fraction bits of window x, y for depth / varying planes (= subpixel_bits: snapped positions)");
    v.integer("attr_coord_bits", attr_coord_bits, 16, 40, "signed bits of triangle-relative attribute-plane coordinates");
    v.integer("attr_sig_bits", attr_sig_bits, 8, 40, "significand bits of per-vertex 1/w and v/w on the attribute path");
  }
};

}  // namespace fxr
