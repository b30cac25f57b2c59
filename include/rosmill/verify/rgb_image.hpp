// An 8-bit RGB picture with the few drawing operations the verifier's deviation map needs, written as PNG
// (deflate by zlib, the rest of the format by hand).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rosmill/verify/deviation_map.hpp"

namespace rosmill::core::verify {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<uint8_t> pixels;  // rows top to bottom, 3 bytes a pixel

  RgbImage(int w, int h, Rgb background);
  // Pixels outside the picture are ignored by every operation.
  void set(int x, int y, Rgb c);
  Rgb at(int x, int y) const;
  void fill(int x, int y, int w, int h, Rgb c);
  void frame(int x, int y, int w, int h, Rgb c);  // a one-pixel outline
  void ring(int cx, int cy, double r0, double r1, Rgb c);  // pixels whose centre is between r0 and r1 from (cx, cy)
  // Text in the 5 x 9 font (descenders below 7 rows), each font pixel `scale` pixels; (x, y) is the top-left
  // corner. Returns the width.
  int text(int x, int y, const std::string& s, int scale, Rgb c);
  static int text_width(const std::string& s, int scale);
};

// Throws Error naming the path when it cannot be written.
void write_png(const std::string& path, const RgbImage& image);

}  // namespace rosmill::core::verify
