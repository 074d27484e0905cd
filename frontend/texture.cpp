// Textures and PNG I/O (see frontend/texture.hpp).
#include "frontend/texture.hpp"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "model/config/param.hpp"

namespace fxr {

Texture make_checker(int size, int squares, uint32_t color_a, uint32_t color_b) {
  if (size < 1 || squares < 1 || size % squares != 0)
    throw ConfigError("checker texture: size " + std::to_string(size) + " must be a positive multiple of squares " +
                      std::to_string(squares));
  Texture t;
  t.image = Image(size, size, color_a);
  const int cell = size / squares;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) t.image.at(x, y) = ((x / cell + y / cell) % 2) ? color_b : color_a;
  t.description = "checker " + std::to_string(size) + "x" + std::to_string(size) + " texels, " +
                  std::to_string(squares) + "x" + std::to_string(squares) + " squares";
  return t;
}

Texture load_png_texture(const std::string& path) {
  int w = 0, h = 0, n = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &n, 4);
  if (!data) {
    const char* why = stbi_failure_reason();
    throw ConfigError(path + ": cannot load the PNG texture: " + (why ? why : "unknown error"));
  }
  Texture t;
  t.image = Image(w, h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const stbi_uc* p = data + 4 * ((size_t)(h - 1 - y) * w + x);  // file row 0 is the top
      t.image.at(x, y) = pack_rgba(p[0], p[1], p[2], p[3]);
    }
  stbi_image_free(data);
  t.description = path + " (" + std::to_string(w) + "x" + std::to_string(h) + ")";
  return t;
}

void write_png(const std::string& path, const Image& img) {
  std::vector<uint8_t> bytes((size_t)img.width * img.height * 4);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const uint32_t c = img.at(x, y);
      uint8_t* p = &bytes[4 * ((size_t)(img.height - 1 - y) * img.width + x)];  // file row 0 = top
      p[0] = c & 0xff;
      p[1] = (c >> 8) & 0xff;
      p[2] = (c >> 16) & 0xff;
      p[3] = (c >> 24) & 0xff;
    }
  if (!stbi_write_png(path.c_str(), img.width, img.height, 4, bytes.data(), img.width * 4))
    throw std::runtime_error(path + ": cannot write the PNG image");
}

bool parse_hex_color(const std::string& s, uint32_t* out) {
  if (s.size() != 7 || s[0] != '#') return false;
  uint32_t v = 0;
  for (size_t i = 1; i < 7; ++i) {
    const char c = s[i];
    int d;
    if (c >= '0' && c <= '9') d = c - '0';
    else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
    else return false;
    v = v * 16 + d;
  }
  *out = pack_rgba(v >> 16, (v >> 8) & 0xff, v & 0xff);
  return true;
}

}  // namespace fxr
