// An off-screen picture drawn with cairo: a white RGB image surface and its drawing context, written as PNG by
// cairo. Every picture of the core (the setup sheet's, the deviation and inspection maps) is drawn on one.
#pragma once
#include <cairo.h>

#include <memory>
#include <string>
#include <vector>

#include "rosmill/picture/rgb.hpp"

namespace rosmill::core::picture {

class Canvas {
 public:
  // `what` names the picture in errors ("setup picture", "deviation map"). Throws Error when cairo cannot make a
  // `width` x `height` image (a side not positive or beyond cairo's 32767 pixels, no memory).
  Canvas(int width, int height, const std::string& what);

  cairo_t* cr() const { return context_.get(); }
  int width() const { return width_; }
  int height() const { return height_; }
  // The colour of a pixel (x right, y down), for tests that look at what was drawn; throws outside the picture.
  Rgb pixel(int x, int y) const;

  // Throws Error naming the picture when a drawing call failed (cairo keeps the first error in the context).
  void check() const;
  // The picture as PNG bytes.
  std::vector<unsigned char> png() const;
  // Writes the PNG; throws Error naming `path` when it cannot be written.
  void write_png(const std::string& path) const;

 private:
  std::string what_;
  int width_, height_;
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface_;
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> context_;
};

void set_colour(cairo_t* cr, Rgb colour);
// A pixel of a cairo RGB24 or (opaque) ARGB32 image: a native-endian 32-bit word, the top byte alpha or unused,
// then red, green, blue.
inline Rgb rgb_of_pixel(uint32_t v) { return Rgb{uint8_t(v >> 16 & 0xff), uint8_t(v >> 8 & 0xff), uint8_t(v & 0xff)}; }

}  // namespace rosmill::core::picture
