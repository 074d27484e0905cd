// analysis/render_images.hpp — the images of a render report: the shaded image (texture
// lookup of the fragments' u, v: the model's on its integer codes, the reference's on doubles),
// the depth image, the error heat map and a side-by-side composition.
#pragma once

#include <cstdint>
#include <vector>

#include "frontend/scene.hpp"
#include "frontend/texture.hpp"
#include "model/unit/raster_unit.hpp"
#include "reference/reference.hpp"

namespace fxr {

// The shaded images. The model's: every fragment's FxFloat u, v through the texture address unit
// (model/stages/texaddr.hpp) and the texel filter (model/stages/texfilter.hpp) with the
// configuration's tex_addr (filter, wrap), in integer arithmetic; the reference's: the same rules
// on the double reference's u, v (reference/texture_ref.hpp). The last fragment that passed the
// depth test wins. No u, v: flat grey. The texture must fit tex_addr.size_bits (checked by
// render_with_report).
Image shade_model(const Scene& sc, const FrameOutput& fo);
Image shade_reference(const Scene& sc, const RefFrame& rf);

// The colour of one model fragment (shade_model's, for the texel report).
uint32_t shade_fragment(const Scene& sc, const FxFloat& u, const FxFloat& v);

// Depth codes → grey, normalised to the range of written codes (nearest = brightest, 255;
// farthest written = 48); never-written pixels (the cleared code) are black. Reports the range.
Image depth_image(const FrameOutput& fo, uint32_t clear_code, uint32_t* lo_out, uint32_t* hi_out);

// Error heat map: log10 of the per-pixel error (texels), 10^-6 (dark blue) … 1 (red), ≥ 1 white,
// negative (no fragment) black. heat is w × h, row 0 at the bottom.
Image heat_image(const std::vector<double>& heat, int w, int h);

// a and b next to each other with an 8-pixel white gap.
Image side_by_side(const Image& a, const Image& b);

}  // namespace fxr
