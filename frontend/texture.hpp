// frontend/texture.hpp — textures for the shaded output image, the texture address computation
// (docs/references.md#seed-002-lookup: texel = floor(u·W), wrap or clamp, nearest), and PNG
// images.
//
// Data flow: the scene front end builds a Texture (procedural checker or PNG); the render
// command looks each fragment's u, v up with texel_index(), which works on the FxFloat codes
// the raster unit emits, in integer arithmetic (it is the texture address unit to come). The
// double reference uses texel_index_ref() on its double u, v.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/arith/fxfloat.hpp"
#include "model/config/param.hpp"  // ConfigError

namespace fxr {

enum class WrapMode : uint8_t { Repeat, Clamp };

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

// A texture: an image plus its wrap mode. Texel (0, 0) is at u = v = 0 (bottom left).
struct Texture {
  Image image;
  WrapMode wrap = WrapMode::Repeat;
  std::string description;  // e.g. "checker 64x64, 8x8 squares" or the PNG path
};

// Procedural checkerboard: size×size texels, squares×squares squares, colour a at texel (0, 0).
// Throws ConfigError if squares does not divide size or either is < 1.
Texture make_checker(int size, int squares, uint32_t color_a, uint32_t color_b, WrapMode wrap);

// Loads a PNG (any channel count, converted to RGBA8) with stb_image; the file's top row
// becomes the texture's top row (v = 1). Throws ConfigError(path: reason) on failure.
Texture load_png_texture(const std::string& path, WrapMode wrap);

// Writes an RGBA8 image as PNG (row 0 at the bottom of the picture). Throws on I/O error.
void write_png(const std::string& path, const Image& img);

// Contract (texture address unit, nearest): texel index along one axis of `size` texels for
// the coordinate u given exactly as an FxFloat code (value (−1)^neg · sig · 2^exp):
//   i = floor(u · size), exactly (integer arithmetic, no rounding before the floor);
//   Repeat: i mod size (mathematical modulo, into [0, size)); Clamp: clamp(i, 0, size − 1).
// Formats: sig < 2^40, 1 ≤ size ≤ 2^20, any exp: the product sig·size < 2^60 fits int64;
// exp ≥ 0 makes u·size an integer multiple of size (repeat → 0) or huge (clamp saturates).
// Zero (sig = 0) maps to texel 0.
int texel_index(const FxFloat& u, int size, WrapMode wrap);

// The same address computation on a double coordinate (for the reference): floor(u · size),
// wrapped or clamped. NaN maps to 0.
int texel_index_ref(double u, int size, WrapMode wrap);

// Nearest lookup: texel (texel_index(u, W), texel_index(v, H)).
inline uint32_t texture_fetch(const Texture& t, int ix, int iy) { return t.image.at(ix, iy); }

// "#rrggbb" → packed RGBA (alpha 255); returns false when malformed.
bool parse_hex_color(const std::string& s, uint32_t* out);

}  // namespace fxr
