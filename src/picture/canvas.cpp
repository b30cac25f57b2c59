#include "rosmill/picture/canvas.hpp"

#include "rosmill/error.hpp"

namespace rosmill::core::picture {
namespace {

cairo_status_t append_png(void* closure, const unsigned char* data, unsigned int length) {
  auto* out = static_cast<std::vector<unsigned char>*>(closure);
  out->insert(out->end(), data, data + length);
  return CAIRO_STATUS_SUCCESS;
}

std::string status_text(cairo_status_t status) { return cairo_status_to_string(status); }

}  // namespace

Canvas::Canvas(int width, int height, const std::string& what)
    : what_(what),
      width_(width),
      height_(height),
      surface_(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height), cairo_surface_destroy),
      context_(nullptr, cairo_destroy) {
  // cairo answers a bad size with a surface in an error state (never null), so the status says it all.
  if (cairo_surface_status(surface_.get()) != CAIRO_STATUS_SUCCESS || width <= 0 || height <= 0)
    throw Error(what_, "cannot create a " + std::to_string(width) + " x " + std::to_string(height) +
                           " image: " + status_text(cairo_surface_status(surface_.get())));
  context_.reset(cairo_create(surface_.get()));
  cairo_set_source_rgb(cr(), 1, 1, 1);
  cairo_paint(cr());
}

Rgb Canvas::pixel(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_)
    throw Error(what_, "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the " +
                           std::to_string(width_) + " x " + std::to_string(height_) + " picture");
  cairo_surface_flush(surface_.get());
  const unsigned char* row =
      cairo_image_surface_get_data(surface_.get()) + size_t(y) * cairo_image_surface_get_stride(surface_.get());
  return rgb_of_pixel(reinterpret_cast<const uint32_t*>(row)[x]);
}

void Canvas::check() const {
  if (cairo_status(cr()) != CAIRO_STATUS_SUCCESS)
    throw Error(what_, "drawing failed: " + status_text(cairo_status(cr())));
}

std::vector<unsigned char> Canvas::png() const {
  check();
  cairo_surface_flush(surface_.get());
  std::vector<unsigned char> out;
  const cairo_status_t status = cairo_surface_write_to_png_stream(surface_.get(), append_png, &out);
  if (status != CAIRO_STATUS_SUCCESS) throw Error(what_, "cannot encode the PNG: " + status_text(status));
  return out;
}

void Canvas::write_png(const std::string& path) const {
  check();
  cairo_surface_flush(surface_.get());
  const cairo_status_t status = cairo_surface_write_to_png(surface_.get(), path.c_str());
  if (status != CAIRO_STATUS_SUCCESS) throw Error(path, "cannot write the " + what_ + " PNG: " + status_text(status));
}

void set_colour(cairo_t* cr, Rgb c) { cairo_set_source_rgb(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0); }

}  // namespace rosmill::core::picture
