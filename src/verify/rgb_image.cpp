#include "rosmill/verify/rgb_image.hpp"

#include <cmath>

#include "bitmap_font.hpp"

namespace rosmill::core::verify {

RgbImage::RgbImage(int w, int h, Rgb background) : width(w), height(h), pixels(static_cast<size_t>(w) * h * 3) {
  fill(0, 0, w, h, background);
}

void RgbImage::set(int x, int y, Rgb c) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  uint8_t* p = &pixels[(static_cast<size_t>(y) * width + x) * 3];
  p[0] = c.r;
  p[1] = c.g;
  p[2] = c.b;
}

Rgb RgbImage::at(int x, int y) const {
  if (x < 0 || y < 0 || x >= width || y >= height) return {};
  const uint8_t* p = &pixels[(static_cast<size_t>(y) * width + x) * 3];
  return {p[0], p[1], p[2]};
}

void RgbImage::fill(int x, int y, int w, int h, Rgb c) {
  for (int v = y; v < y + h; ++v)
    for (int u = x; u < x + w; ++u) set(u, v, c);
}

void RgbImage::frame(int x, int y, int w, int h, Rgb c) {
  fill(x, y, w, 1, c);
  fill(x, y + h - 1, w, 1, c);
  fill(x, y, 1, h, c);
  fill(x + w - 1, y, 1, h, c);
}

void RgbImage::ring(int cx, int cy, double r0, double r1, Rgb c) {
  const int R = static_cast<int>(std::ceil(r1));
  for (int v = -R; v <= R; ++v)
    for (int u = -R; u <= R; ++u) {
      const double d = std::hypot(u, v);
      if (d >= r0 && d <= r1) set(cx + u, cy + v, c);
    }
}

int RgbImage::text_width(const std::string& s, int scale) {
  return static_cast<int>(s.size()) * (kGlyphWidth + 1) * scale;
}

int RgbImage::text(int x, int y, const std::string& s, int scale, Rgb c) {
  int at_x = x;
  for (char ch : s) {
    if (const char* rows = glyph_rows(ch))
      for (int v = 0; v < kGlyphHeight; ++v)
        for (int u = 0; u < kGlyphWidth; ++u)
          if (rows[v * kGlyphWidth + u] == '#') fill(at_x + u * scale, y + v * scale, scale, scale, c);
    at_x += (kGlyphWidth + 1) * scale;
  }
  return at_x - x;
}

}  // namespace rosmill::core::verify
