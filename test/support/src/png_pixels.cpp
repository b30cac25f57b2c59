#include "rosmill/testing/png_pixels.hpp"

#include <cairo.h>

#include <memory>

#include "rosmill/error.hpp"
#include "rosmill/picture/canvas.hpp"

namespace rosmill::testing {

size_t PngPixels::count(rosmill::core::picture::Rgb c) const {
  size_t n = 0;
  for (const auto& p : pixels) n += p.r == c.r && p.g == c.g && p.b == c.b;
  return n;
}

PngPixels read_png_pixels(const std::string& path) {
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> s(cairo_image_surface_create_from_png(path.c_str()),
                                                                        cairo_surface_destroy);
  if (cairo_surface_status(s.get()) != CAIRO_STATUS_SUCCESS)
    throw rosmill::core::Error(path, std::string("not a PNG cairo reads: ") +
                                         cairo_status_to_string(cairo_surface_status(s.get())));
  const cairo_format_t format = cairo_image_surface_get_format(s.get());
  if (format != CAIRO_FORMAT_RGB24 && format != CAIRO_FORMAT_ARGB32)
    throw rosmill::core::Error(path, "not an RGB picture");
  PngPixels png;
  png.width = cairo_image_surface_get_width(s.get());
  png.height = cairo_image_surface_get_height(s.get());
  const unsigned char* data = cairo_image_surface_get_data(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      png.pixels.push_back(rosmill::core::picture::rgb_of_pixel(reinterpret_cast<const uint32_t*>(data + size_t(y) * stride)[x]));
    }
  return png;
}

}  // namespace rosmill::testing
