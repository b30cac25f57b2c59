// A PNG file read back with cairo (its own PNG reader, libpng's), as the pixels a test looks at.
#pragma once
#include <string>
#include <vector>

#include "rosmill/picture/rgb.hpp"

namespace rosmill::testing {

struct PngPixels {
  int width = 0, height = 0;
  std::vector<rosmill::core::picture::Rgb> pixels;  // rows top to bottom

  rosmill::core::picture::Rgb at(int x, int y) const { return pixels[size_t(y) * width + x]; }
  // How many pixels are exactly this colour.
  size_t count(rosmill::core::picture::Rgb c) const;
};

// Throws Error naming the path when cairo cannot read it as a PNG.
PngPixels read_png_pixels(const std::string& path);

}  // namespace rosmill::testing
