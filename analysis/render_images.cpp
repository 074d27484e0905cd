// Images of the render report (analysis/render_images.hpp).
#include "analysis/render_images.hpp"

#include <algorithm>
#include <cmath>

#include "model/stages/texfilter.hpp"
#include "reference/texture_ref.hpp"

namespace fxr {

namespace {

// Paints fragments in draw order (the last one that passed the depth test wins); `colour(f)` is
// the shaded colour of fragment f.
template <class Frags, class Colour>
Image paint(const Scene& sc, const Frags& frags, Colour colour) {
  const DrawState& st = sc.state;
  Image img(st.viewport_w, st.viewport_h, sc.background);
  const bool textured = sc.u_varying >= 0 && sc.v_varying >= 0;
  for (const auto& f : frags) {
    const int x = f.x - st.viewport_x, y = f.y - st.viewport_y;
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
    if (f.prim >= sc.tris.size()) {  // a line segment (primitives after the triangles): flat colour
      img.at(x, y) = sc.line_color;
      continue;
    }
    img.at(x, y) = textured ? colour(f) : pack_rgba(192, 192, 192);  // no texture coordinates: flat grey
  }
  return img;
}

}  // namespace

uint32_t shade_fragment(const Scene& sc, const FxFloat& u, const FxFloat& v) {
  const Image& im = sc.texture.image;
  TexAddrIn in;
  in.u = u;
  in.v = v;
  in.width = (uint32_t)im.width;
  in.height = (uint32_t)im.height;
  const TexelView view{im.rgba.data(), (uint32_t)im.width, (uint32_t)im.height};
  return texfilter(sc.config.tex_addr, texaddr(sc.config.tex_addr, in), view, sc.texture.border);
}

Image shade_model(const Scene& sc, const FrameOutput& fo) {
  return paint(sc, fo.fragments,
               [&](const Fragment& f) { return shade_fragment(sc, f.var[sc.u_varying], f.var[sc.v_varying]); });
}

Image shade_reference(const Scene& sc, const RefFrame& rf) {
  const TexAddrConfig& c = sc.config.tex_addr;
  const Image& im = sc.texture.image;
  return paint(sc, rf.fragments, [&](const RefFragment& f) {
    return pack_blend(blend_ref(im, sc.texture.border, ref_tex_axis(c.filter, c.wrap, f.var[sc.u_varying], im.width),
                                ref_tex_axis(c.filter, c.wrap, f.var[sc.v_varying], im.height)));
  });
}

// Depth codes → grey, normalised to the range of written codes (nearest = brightest, 255;
// farthest written = 48); never-written pixels (the cleared maximum code) are black.
Image depth_image(const FrameOutput& fo, uint32_t clear_code, uint32_t* lo_out, uint32_t* hi_out) {
  Image img(fo.width, fo.height, pack_rgba(0, 0, 0));
  uint32_t lo = UINT32_MAX, hi = 0;
  for (uint32_t c : fo.depth)
    if (c != clear_code) lo = std::min(lo, c), hi = std::max(hi, c);
  *lo_out = lo;
  *hi_out = hi;
  for (int y = 0; y < fo.height; ++y)
    for (int x = 0; x < fo.width; ++x) {
      const uint32_t c = fo.depth[(size_t)y * fo.width + x];
      if (c == clear_code) continue;
      const double t = hi > lo ? (double)(hi - c) / (double)(hi - lo) : 1.0;
      const uint32_t g = 48 + (uint32_t)std::lround(t * 207);
      img.at(x, y) = pack_rgba(g, g, g);
    }
  return img;
}

// Error heat map: log10 of the texel error of the visible fragment, 10^-6 (dark blue) …
// 1 texel (red) and beyond (white); no fragment: black.
Image heat_image(const std::vector<double>& heat, int w, int h) {
  Image img(w, h, pack_rgba(0, 0, 0));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double e = heat[(size_t)y * w + x];
      if (e < 0) continue;
      if (e >= 1) {
        img.at(x, y) = pack_rgba(255, 255, 255);
        continue;
      }
      const double t = std::clamp((std::log10(std::max(e, 1e-12)) + 6.0) / 6.0, 0.0, 1.0);  // 0 … 1
      // blue → cyan → green → yellow → red
      const double r = std::clamp(4 * t - 2, 0.0, 1.0), g = t < 0.75 ? std::clamp(4 * t - 0.5, 0.0, 1.0) : 4 - 4 * t,
                   b = std::clamp(1.5 - 4 * t, 0.0, 1.0);
      img.at(x, y) = pack_rgba((uint32_t)std::lround(40 + 215 * r), (uint32_t)std::lround(40 + 215 * g),
                                    (uint32_t)std::lround(60 + 195 * b));
    }
  return img;
}

Image side_by_side(const Image& a, const Image& b) {
  const int gap = 8;
  Image img(a.width + gap + b.width, std::max(a.height, b.height), pack_rgba(255, 255, 255));
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) img.at(x, y) = a.at(x, y);
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x) img.at(a.width + gap + x, y) = b.at(x, y);
  return img;
}

}  // namespace fxr
