#include "rosmill/picture/map_plot.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/picture/nice_ticks.hpp"

namespace rosmill::core::picture {
namespace {

// Pixels. The left band holds the y numbers and the rotated "y (mm)", the bottom band the x numbers and "x (mm)".
constexpr double kMargin = 16, kTitleBand = 46, kLeftAxis = 76, kBottomAxis = 54, kGap = 28, kLegendWidth = 290;
constexpr double kLine = 20, kBandRow = 22, kBarWidth = 30, kTitleSize = 17, kTextSize = 13;
constexpr int kMinMap = 100, kMaxMap = 8000;
constexpr Rgb kInk{25, 25, 25};

enum class Align { Left, Centre, Right };

// Anti-aliased text with its baseline at y; cairo's own text API with the system's sans-serif face.
void text(cairo_t* cr, double x, double y, const std::string& s, double size, bool bold = false,
          Align align = Align::Left) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  const double shift = align == Align::Left ? 0 : align == Align::Centre ? e.x_advance / 2 : e.x_advance;
  set_colour(cr, kInk);
  cairo_move_to(cr, x - shift, y);
  cairo_show_text(cr, s.c_str());
}

}  // namespace

struct MapPlot::Layout {
  MapFrame frame;
  int width = 0, height = 0;
};

MapPlot::Layout MapPlot::layout(double x0, double y0, double x1, double y1, const MapLegend& legend, const std::string& what,
              int map_pixels) {
  if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1) || !(x1 > x0) ||
      !(y1 > y0))
    throw Error(what, "the map's region x " + std::to_string(x0) + " to " + std::to_string(x1) + ", y " +
                          std::to_string(y0) + " to " + std::to_string(y1) + " mm is empty or not finite");
  if (map_pixels < kMinMap || map_pixels > kMaxMap)
    throw Error(what, "map size " + std::to_string(map_pixels) + " pixels is outside [" + std::to_string(kMinMap) +
                          ", " + std::to_string(kMaxMap) + "]");
  MapPlot::Layout l;
  MapFrame& f = l.frame;
  f.x0 = x0;
  f.y1 = y1;
  f.scale = map_pixels / std::max(x1 - x0, y1 - y0);
  f.width = std::max(1, static_cast<int>(std::ceil((x1 - x0) * f.scale - 1e-6)));
  f.height = std::max(1, static_cast<int>(std::ceil((y1 - y0) * f.scale - 1e-6)));
  f.left = kLeftAxis;
  f.top = kTitleBand;
  const double legend_height = kTitleBand + kLine * legend.heading.size() + 8 + kBandRow * legend.bands.size() +
                               kLine + kLine * legend.figures.size() + kMargin;
  l.width = static_cast<int>(f.left + f.width + kGap + kLegendWidth + kMargin);
  l.height = static_cast<int>(std::max(f.top + f.height + kBottomAxis, legend_height));
  return l;
}

MapPlot::MapPlot(double x0, double y0, double x1, double y1, const MapCaption& caption, const MapLegend& legend,
                 const std::string& what, int map_pixels)
    : MapPlot(layout(x0, y0, x1, y1, legend, what, map_pixels), caption, legend, what) {}

MapPlot::MapPlot(const Layout& l, const MapCaption& caption, const MapLegend& legend, const std::string& what)
    : canvas_(l.width, l.height, what), frame_(l.frame) {
  draw_title(caption.title());
  draw_legend(legend, frame_.left + frame_.width + kGap, frame_.top);
  // The map's content stays inside the map; finish() lifts the clip for the axes.
  cairo_save(cr());
  cairo_rectangle(cr(), frame_.left, frame_.top, frame_.width, frame_.height);
  cairo_clip(cr());
}

void MapPlot::draw_title(const std::string& title) { text(cr(), kMargin, kTitleBand - 18, title, kTitleSize, true); }

void MapPlot::draw_legend(const MapLegend& legend, double x, double y) {
  cairo_t* c = cr();
  for (const std::string& line : legend.heading) {
    y += kLine;
    text(c, x, y - 6, line, kTextSize);
  }
  y += 8;
  const double bar_top = y;
  for (const ColourBand& band : legend.bands) {
    cairo_rectangle(c, x, y, kBarWidth, kBandRow);
    set_colour(c, band.colour);
    cairo_fill(c);
    text(c, x + kBarWidth + 10, y + kBandRow / 2 + 4.5, band.label, kTextSize);
    y += kBandRow;
  }
  if (!legend.bands.empty()) {  // the bar's outline, on the pixel grid so it stays one sharp pixel
    cairo_rectangle(c, std::round(x) - 0.5, std::round(bar_top) - 0.5, kBarWidth + 1, y - bar_top + 1);
    set_colour(c, kInk);
    cairo_set_line_width(c, 1);
    cairo_stroke(c);
  }
  y += kLine;
  for (const std::string& line : legend.figures) {
    y += kLine;
    text(c, x, y - 6, line, kTextSize);
  }
}

void MapPlot::fill_rect(double x0, double y0, double x1, double y1, Rgb colour) {
  const Vec2 a = frame_.pixel(x0, y1), b = frame_.pixel(x1, y0);
  cairo_set_antialias(cr(), CAIRO_ANTIALIAS_NONE);
  cairo_rectangle(cr(), a.x(), a.y(), b.x() - a.x(), b.y() - a.y());
  set_colour(cr(), colour);
  cairo_fill(cr());
  cairo_set_antialias(cr(), CAIRO_ANTIALIAS_DEFAULT);
}

void MapPlot::disc(double x, double y, double radius_mm, Rgb colour) {
  const Vec2 p = frame_.pixel(x, y);
  cairo_new_sub_path(cr());
  cairo_arc(cr(), p.x(), p.y(), std::max(0.5, radius_mm * frame_.scale), 0, 2 * M_PI);
  set_colour(cr(), colour);
  cairo_fill(cr());
}

void MapPlot::polyline(const std::vector<Vec2>& points, bool closed, Rgb colour, double width) {
  if (points.size() < 2) return;
  for (const Vec2& q : points) {
    const Vec2 p = frame_.pixel(q.x(), q.y());
    cairo_line_to(cr(), p.x(), p.y());  // the first line_to of a new path moves there
  }
  if (closed) cairo_close_path(cr());
  set_colour(cr(), colour);
  cairo_set_line_width(cr(), width);
  cairo_set_line_join(cr(), CAIRO_LINE_JOIN_ROUND);
  cairo_stroke(cr());
}

void MapPlot::ring(double x, double y) {
  const Vec2 p = frame_.pixel(x, y);
  cairo_new_sub_path(cr());
  cairo_arc(cr(), p.x(), p.y(), 10.5, 0, 2 * M_PI);
  set_colour(cr(), Rgb{0, 0, 0});
  cairo_set_line_width(cr(), 3);
  cairo_stroke(cr());
  cairo_new_sub_path(cr());
  cairo_arc(cr(), p.x(), p.y(), 8, 0, 2 * M_PI);
  set_colour(cr(), Rgb{255, 255, 255});
  cairo_set_line_width(cr(), 2);
  cairo_stroke(cr());
}

void MapPlot::draw_axes() {
  cairo_t* c = cr();
  const MapFrame& f = frame_;
  const double right = f.left + f.width, bottom = f.top + f.height;
  cairo_set_line_width(c, 1);
  set_colour(c, kInk);
  cairo_rectangle(c, f.left - 0.5, f.top - 0.5, f.width + 1, f.height + 1);
  cairo_stroke(c);
  // One step on both axes (they share a scale), about one label every 80 pixels.
  const double x1 = f.x0 + f.width / f.scale, y0 = f.y1 - f.height / f.scale;
  const double step = nice_step(std::max(x1 - f.x0, f.y1 - y0), std::max(2, std::max(f.width, f.height) / 80));
  for (const double t : ticks(f.x0, x1, step)) {
    const double px = std::round(f.pixel(t, 0).x()) + 0.5;
    cairo_move_to(c, px, bottom + 0.5);
    cairo_line_to(c, px, bottom + 6.5);
    cairo_stroke(c);
    text(c, px, bottom + 21, tick_label(t, step), kTextSize - 1, false, Align::Centre);
  }
  for (const double t : ticks(y0, f.y1, step)) {
    const double py = std::round(f.pixel(0, t).y()) + 0.5;
    set_colour(c, kInk);
    cairo_move_to(c, f.left - 0.5, py);
    cairo_line_to(c, f.left - 6.5, py);
    cairo_stroke(c);
    text(c, f.left - 9, py + 4.5, tick_label(t, step), kTextSize - 1, false, Align::Right);
  }
  text(c, (f.left + right) / 2, bottom + 42, "x (mm)", kTextSize, false, Align::Centre);
  cairo_save(c);
  cairo_translate(c, 18, (f.top + bottom) / 2);
  cairo_rotate(c, -M_PI / 2);
  text(c, 0, 0, "y (mm)", kTextSize, false, Align::Centre);
  cairo_restore(c);
}

MapPicture MapPlot::finish() {
  cairo_restore(cr());  // the map's clip
  draw_axes();
  canvas_.check();
  return MapPicture{std::move(canvas_), frame_};
}

}  // namespace rosmill::core::picture
