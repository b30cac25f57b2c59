// A map seen from above on a Canvas: a region of the XY plane in millimetres (x right, y up) drawn at one scale on
// both axes, with the title line over it, axes in mm below and left of it (ticks at nice steps), and beside it a
// legend: heading lines, a colour bar of bands with their labels, then lines of figures.
//
// Build it, draw the map's content with the calls below (clipped to the map), then take the Canvas with finish(),
// which draws the frame and the axes over the content.
#pragma once
#include <string>
#include <vector>

#include "rosmill/geometry/types.hpp"
#include "rosmill/picture/canvas.hpp"
#include "rosmill/picture/map_caption.hpp"
#include "rosmill/picture/rgb.hpp"

namespace rosmill::core::picture {

struct MapLegend {
  std::vector<std::string> heading;  // above the colour bar
  std::vector<ColourBand> bands;     // the colour bar, top to bottom
  std::vector<std::string> figures;  // below it
};

// From mm on the map to the picture's pixels (x right, y down; a pixel's centre at +0.5).
struct MapFrame {
  double x0 = 0, y1 = 0;            // the region's left and top edges, mm
  double left = 0, top = 0;         // where they are in the picture, pixels
  double scale = 1;                 // pixels a mm
  int width = 0, height = 0;        // the map's size, pixels
  Vec2 pixel(double x, double y) const { return Vec2(left + (x - x0) * scale, top + (y1 - y) * scale); }
};

// A finished map: the picture and where the map lies in it.
struct MapPicture {
  Canvas canvas;
  MapFrame frame;
};

class MapPlot {
 public:
  // The region [x0, x1] x [y0, y1] (mm, finite, x1 > x0, y1 > y0) at `map_pixels` on its longer side (>= 100).
  // Throws Error naming `what` for a region or size it cannot draw.
  MapPlot(double x0, double y0, double x1, double y1, const MapCaption& caption, const MapLegend& legend,
          const std::string& what, int map_pixels = 800);

  const MapFrame& frame() const { return frame_; }
  cairo_t* cr() const { return canvas_.cr(); }

  // A rectangle of the map (mm), without anti-aliasing so that neighbouring cells tile with no seam.
  void fill_rect(double x0, double y0, double x1, double y1, Rgb colour);
  // A disc at its size in mm, at least a pixel across so that a small one still shows.
  void disc(double x, double y, double radius_mm, Rgb colour);
  // A polyline in mm, `width` pixels wide; closed: back to its first point.
  void polyline(const std::vector<Vec2>& points, bool closed, Rgb colour, double width);
  // A mark around a spot (mm) that shows on every colour: a black ring outside a white one.
  void ring(double x, double y);

  // Draws the frame and the axes over the map and hands over the picture (the plot is spent).
  MapPicture finish();

 private:
  struct Layout;  // the picture's size and where the map lies in it
  static Layout layout(double x0, double y0, double x1, double y1, const MapLegend& legend, const std::string& what,
                       int map_pixels);
  MapPlot(const Layout& layout, const MapCaption& caption, const MapLegend& legend, const std::string& what);
  void draw_title(const std::string& title);
  void draw_legend(const MapLegend& legend, double x, double y);
  void draw_axes();

  Canvas canvas_;
  MapFrame frame_;
};

}  // namespace rosmill::core::picture
