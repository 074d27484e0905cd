// frontend/texture.hpp — textures for the shaded output image and PNG images.
//
// Data flow: the scene front end builds a Texture (procedural checker or PNG); the render
// command shades each fragment through the texture address unit (model/stages/texaddr.hpp) and
// the texel filter (model/stages/texfilter.hpp) on the FxFloat codes the raster unit emits, in
// integer arithmetic; filter and wrap mode are the configuration's tex_addr.filter / .wrap
// (docs/texaddr.md). The double reference image samples with reference/texture_ref.hpp.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/config/param.hpp"  // ConfigError

namespace fxr {

// RGBA8 image, row 0 at the BOTTOM (the raster unit's y-up window convention); write_png
// flips it so the file shows row 0 at the bottom as a viewer expects.
struct Image {
  int width = 0, height = 0;
  std::vector<uint32_t> rgba;  // 0xAABBGGRR (byte order R, G, B, A in memory on little endian)
  Image() = default;
  Image(int w, int h, uint32_t fill) : width(w), height(h), rgba((size_t)w * h, fill) {}
  uint32_t& at(int x, int y) { return rgba[(size_t)y * width + x]; }
  uint32_t at(int x, int y) const { return rgba[(size_t)y * width + x]; }
};

// Packs 8-bit channels into Image's pixel layout (alpha 255 unless given).
inline uint32_t pack_rgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a = 255) {
  return r | (g << 8) | (b << 16) | (a << 24);
}

// A texture: an image plus its border colour. Texel (0, 0) is at u = v = 0 (bottom left).
struct Texture {
  Image image;
  uint32_t border = pack_rgba(0, 0, 0);  // the colour of texels outside (tex_addr.wrap clamp_to_border)
  std::string description;  // e.g. "checker 64x64, 8x8 squares" or the PNG path
};

// Procedural checkerboard: size×size texels, squares×squares squares, colour a at texel (0, 0).
// Throws ConfigError if squares does not divide size or either is < 1.
Texture make_checker(int size, int squares, uint32_t color_a, uint32_t color_b);

// Loads a PNG (any channel count, converted to RGBA8) with stb_image; the file's top row
// becomes the texture's top row (v = 1). Throws ConfigError(path: reason) on failure.
Texture load_png_texture(const std::string& path);

// Writes an RGBA8 image as PNG (row 0 at the bottom of the picture). Throws on I/O error.
void write_png(const std::string& path, const Image& img);

// "#rrggbb" → packed RGBA (alpha 255); returns false when malformed (uppercase digits included:
// the format is lowercase hex, docs/scene-format.md).
bool parse_hex_color(const std::string& s, uint32_t* out);

}  // namespace fxr
