// The picture of a setup (setup_sheet.hpp), drawn with cairo on an off-screen image.
//
// The view: orthographic, of the setup frame (the tool axis +Z stays upright on screen), from in front (-Y, where
// the operator stands at a vertical mill), to the right (+X) and above (+Z): the direction (1, -1.3, 1.1) points
// towards the viewer, so a part's top, front and right side show. Everything drawn (the part, the fixture's boxes,
// the toolpaths with their rapids) is fitted into the picture inside a margin, centred, on white.
//
// The solids (the part and the fixture's boxes) are triangles: those facing away are left out, the rest painted far
// to near (painter's algorithm, by the depth of each triangle's centroid) in flat Lambert shading from a fixed light,
// the part light grey-blue, the fixture brown. A triangle large on screen is cut into pieces before sorting, else a
// vise body or a cube's face would be painted over what stands in front of it because its centroid lies nearer;
// where two solids touch, a piece can still come out of order by a pixel or two. The toolpaths are lines over the
// solids (hidden parts too: a machinist wants to see every cut), operation k of the setup in operation_colour(k):
// cuts (feeds and plunges) solid, rapids dashed, thin and lighter.
#include <cairo.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/picture/canvas.hpp"
#include "rosmill/sheet/setup_sheet.hpp"

namespace rosmill::core::sheet {
namespace {

constexpr int kMinSize = 16, kMaxSize = 4096;  // pixels, each side

const Vec3 kToViewer = Vec3(1.0, -1.3, 1.1).normalized();
// Towards the light: above, in front and a little to the right, so that of a box the top is brightest, the front
// next and the right side darkest: the three faces a viewer sees always differ.
const Vec3 kToLight = Vec3(0.35, -0.6, 1.0).normalized();
constexpr double kAmbient = 0.35;  // the share of its colour a face turned from the light keeps

struct Colour {
  double r, g, b;
};
const Colour kPartColour{0.72, 0.78, 0.88};     // light grey-blue
const Colour kFixtureColour{0.62, 0.44, 0.27};  // steel brown: a hue neither the part nor the palette has

// Operation colours: saturated, far apart, each dark enough to read on white paper and on the grey-blue part; no
// orange or brown (the fixture's hue). More operations than colours cycle through them again.
const std::array<const char*, 8> kPalette = {"#d62728", "#1f4fd6", "#2ca02c", "#8c8c00",
                                             "#9467bd", "#00a5b5", "#e040a0", "#303030"};

// Setup frame -> image pixels (x right, y down) and depth (larger: nearer the viewer).
struct Projection {
  Vec3 right, up, toward;  // the view's axes in the setup frame
  double scale = 1, x0 = 0, y0 = 0;

  Projection() : right(Vec3::UnitZ().cross(kToViewer).normalized()), toward(kToViewer) { up = toward.cross(right); }
  Vec2 view(const Vec3& p) const { return Vec2(p.dot(right), p.dot(up)); }
  Vec3 pixel(const Vec3& p) const { return Vec3(x0 + scale * p.dot(right), y0 - scale * p.dot(up), p.dot(toward)); }
};

bool finite(const Vec3& p) { return p.allFinite(); }

// The fixture's boxes as triangles (12 a box, outward normals).
struct Triangles {
  std::vector<Vec3> vertices;  // 3 a triangle
  std::vector<Mesh::Face> faces;
  std::vector<Vec3> normals;
};

Triangles fixture_triangles(const fixture::Fixture& fixture) {
  Triangles t;
  t.vertices = fixture::fixture_corners(fixture);
  for (uint32_t i = 0; i + 2 < t.vertices.size(); i += 3) {
    t.faces.push_back({i, i + 1, i + 2});
    const Vec3 n = (t.vertices[i + 1] - t.vertices[i]).cross(t.vertices[i + 2] - t.vertices[i]);
    t.normals.push_back(n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero());
  }
  return t;
}

// Calls f(from, to, type) for each move of the toolpath from its start, skipping moves from or to a point that is
// not finite.
template <typename F>
void for_each_move(const Toolpath& tp, F&& f) {
  Vec3 at = tp.start;
  for (const ToolpathPass& pass : tp.passes)
    for (const Move& m : pass.moves) {
      if (finite(at) && finite(m.to)) f(at, m.to, m.type);
      at = m.to;
    }
}

template <typename F>
void for_each_move(const std::vector<const Job*>& operations, size_t k, F&& f) {
  if (operations[k])
    for (const Toolpath& tp : *operations[k]) for_each_move(tp, f);
}

// Scale and offset that fit everything drawn into the picture inside a margin, centred.
void fit(Projection& p, const Mesh& part, const Triangles& fixture, const std::vector<const Job*>& operations,
         int width, int height) {
  Eigen::AlignedBox2d box;
  const auto add = [&](const Vec3& v) {
    if (finite(v)) box.extend(p.view(v));
  };
  for (const Vec3& v : part.vertices) add(v);
  for (const Vec3& v : fixture.vertices) add(v);
  for (size_t k = 0; k < operations.size(); ++k)
    for_each_move(operations, k, [&](const Vec3& a, const Vec3& b, MoveType) {
      add(a);
      add(b);
    });
  p.x0 = width / 2.0, p.y0 = height / 2.0;
  if (box.isEmpty()) return;
  const double margin = 4 + 0.04 * std::min(width, height);
  const Vec2 size = box.sizes(), centre = box.center();
  const double sx = size.x() > 0 ? (width - 2 * margin) / size.x() : INFINITY;
  const double sy = size.y() > 0 ? (height - 2 * margin) / size.y() : INFINITY;
  p.scale = std::isfinite(std::min(sx, sy)) ? std::min(sx, sy) : 1.0;  // a single point: any scale
  p.x0 -= p.scale * centre.x();
  p.y0 += p.scale * centre.y();
}

// A triangle ready to paint: its corners in pixels, its depth and its shaded colour (0xRRGGBB).
struct ScreenTriangle {
  std::array<float, 6> xy;
  float depth;
  uint32_t colour;
};

uint32_t shaded(const Colour& c, const Vec3& normal) {
  const double light = kAmbient + (1 - kAmbient) * std::max(0.0, normal.dot(kToLight));
  auto channel = [&](double v) { return static_cast<uint32_t>(std::lround(std::clamp(v * light, 0.0, 1.0) * 255)); };
  return channel(c.r) << 16 | channel(c.g) << 8 | channel(c.b);
}

// Adds the triangle (pixels and depth), halved across its longest side on screen while that exceeds `max_side`
// pixels (at most `levels` times), so that depth sorting works on pieces of about that size. Halving the longest
// side makes a long sliver (common on a CAD part's flat faces) a row of pieces, not a grid of them.
void add_triangle(std::vector<ScreenTriangle>& out, const Vec3& a, const Vec3& b, const Vec3& c, uint32_t colour,
                  double max_side, int levels) {
  const auto side = [](const Vec3& p, const Vec3& q) { return (p - q).head<2>().squaredNorm(); };
  const double ab = side(a, b), bc = side(b, c), ca = side(c, a);
  if (levels > 0 && std::max({ab, bc, ca}) > max_side * max_side) {
    // The corners turned so that the longest side runs from p to q; both halves keep the orientation.
    const bool first = ab >= bc && ab >= ca, second = !first && bc >= ca;
    const Vec3& p = first ? a : second ? b : c;
    const Vec3& q = first ? b : second ? c : a;
    const Vec3& r = first ? c : second ? a : b;
    const Vec3 m = (p + q) / 2;
    add_triangle(out, p, m, r, colour, max_side, levels - 1);
    add_triangle(out, m, q, r, colour, max_side, levels - 1);
    return;
  }
  const float depth = static_cast<float>((a.z() + b.z() + c.z()) / 3);
  out.push_back({{float(a.x()), float(a.y()), float(b.x()), float(b.y()), float(c.x()), float(c.y())}, depth, colour});
}

// The triangles of a solid that face the viewer, shaded.
void add_solid(std::vector<ScreenTriangle>& out, const Projection& p, const std::vector<Vec3>& vertices,
               const std::vector<Mesh::Face>& faces, const std::vector<Vec3>& normals, const Colour& colour,
               double max_side) {
  std::vector<Vec3> pixels(vertices.size());
  for (size_t i = 0; i < vertices.size(); ++i) pixels[i] = p.pixel(vertices[i]);
  for (size_t f = 0; f < faces.size() && f < normals.size(); ++f) {
    const Vec3& n = normals[f];
    if (!(n.dot(p.toward) > 0)) continue;  // facing away, edge-on, degenerate (zero normal) or NaN
    const Vec3 &a = pixels[faces[f][0]], &b = pixels[faces[f][1]], &c = pixels[faces[f][2]];
    if (finite(a) && finite(b) && finite(c)) add_triangle(out, a, b, c, shaded(colour, n), max_side, 16);
  }
}

void set_colour(cairo_t* cr, uint32_t rgb) {
  cairo_set_source_rgb(cr, (rgb >> 16 & 0xff) / 255.0, (rgb >> 8 & 0xff) / 255.0, (rgb & 0xff) / 255.0);
}

// Paints the triangles far to near. Without antialiasing, so that neighbouring triangles meet without a seam of the
// background between them; a run of triangles of one colour (a flat face in pieces) is filled as one path, which is
// what keeps a large mesh fast.
void paint_solids(cairo_t* cr, std::vector<ScreenTriangle>& triangles) {
  std::sort(triangles.begin(), triangles.end(),
            [](const ScreenTriangle& a, const ScreenTriangle& b) { return a.depth < b.depth; });
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  for (size_t i = 0; i < triangles.size();) {
    const uint32_t colour = triangles[i].colour;
    cairo_new_path(cr);
    for (; i < triangles.size() && triangles[i].colour == colour; ++i) {
      const auto& t = triangles[i].xy;
      cairo_move_to(cr, t[0], t[1]);
      cairo_line_to(cr, t[2], t[3]);
      cairo_line_to(cr, t[4], t[5]);
      cairo_close_path(cr);
    }
    set_colour(cr, colour);
    cairo_fill(cr);
  }
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
}

Colour operation_rgb(size_t k) {
  const unsigned long v = std::stoul(operation_colour(k).substr(1), nullptr, 16);
  return {(v >> 16 & 0xff) / 255.0, (v >> 8 & 0xff) / 255.0, (v & 0xff) / 255.0};
}

// Strokes each operation's rapids: thin, dashed and half-way to white (they cut nothing, but show where the tool
// travels fast, and up to what height).
void draw_rapids(cairo_t* cr, const Projection& p, const std::vector<const Job*>& operations, double line_width) {
  const double dash[] = {4.0, 3.0};
  cairo_set_dash(cr, dash, 2, 0);
  cairo_set_line_width(cr, line_width);
  for (size_t k = 0; k < operations.size(); ++k) {
    cairo_new_path(cr);
    for_each_move(operations, k, [&](const Vec3& a, const Vec3& b, MoveType type) {
      if (type != MoveType::Rapid) return;
      const Vec3 from = p.pixel(a), to = p.pixel(b);
      cairo_move_to(cr, from.x(), from.y());
      cairo_line_to(cr, to.x(), to.y());
    });
    const Colour c = operation_rgb(k);
    cairo_set_source_rgb(cr, (c.r + 1) / 2, (c.g + 1) / 2, (c.b + 1) / 2);
    cairo_stroke(cr);
  }
  cairo_set_dash(cr, nullptr, 0, 0);
}

// Strokes each operation's cuts (feeds and plunges) as polylines, leaving out a point within a fraction of a pixel
// of the last one drawn (a dense finishing path has many moves to a pixel: the line looks the same and costs far
// less), yet always the last point of a run of cuts.
void draw_cuts(cairo_t* cr, const Projection& p, const std::vector<const Job*>& operations, double line_width) {
  constexpr double kMinStep = 0.4;  // pixels
  cairo_set_line_width(cr, line_width);
  for (size_t k = 0; k < operations.size(); ++k) {
    cairo_new_path(cr);
    bool open = false;  // a run of cuts is being drawn
    Vec3 end, pending;  // the last point drawn; the last point left out (when `held`)
    bool held = false;
    const auto flush = [&] {
      if (held) cairo_line_to(cr, pending.x(), pending.y());
      held = open = false;
    };
    for_each_move(operations, k, [&](const Vec3& a, const Vec3& b, MoveType type) {
      if (type == MoveType::Rapid) return flush();
      const Vec3 from = p.pixel(a), to = p.pixel(b);
      if (!open || (from - (held ? pending : end)).head<2>().norm() > 1e-6) {
        flush();
        cairo_move_to(cr, from.x(), from.y());
        end = from;
        open = true;
      }
      if ((to - end).head<2>().norm() < kMinStep) {
        pending = to;
        held = true;
        return;
      }
      cairo_line_to(cr, to.x(), to.y());
      end = to;
      held = false;
    });
    flush();
    const Colour c = operation_rgb(k);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_stroke(cr);
  }
}

void check_size(const char* name, int pixels) {
  if (pixels < kMinSize || pixels > kMaxSize)
    throw Error("setup picture", std::string(name) + " " + std::to_string(pixels) + " is outside [" +
                                     std::to_string(kMinSize) + ", " + std::to_string(kMaxSize) + "] pixels");
}

}  // namespace

std::string operation_colour(size_t k) { return kPalette[k % kPalette.size()]; }

std::vector<unsigned char> setup_picture_png(const Mesh& part_in_setup, const fixture::Fixture& fixture,
                                             const std::vector<const Job*>& operations, int width, int height) {
  check_size("width", width);
  check_size("height", height);
  const Triangles fixture_mesh = fixture_triangles(fixture);
  Projection projection;
  fit(projection, part_in_setup, fixture_mesh, operations, width, height);

  // Pieces of about a 48th of the picture: where two solids touch (a part on a vise floor, against a jaw) a piece
  // painted out of order takes a pixel or two, not a visible wedge; a box's face becomes a few hundred pieces.
  const double max_side = std::max(width, height) / 48.0;
  std::vector<ScreenTriangle> triangles;
  triangles.reserve(part_in_setup.faces.size() / 2 + fixture_mesh.faces.size() * 64);
  add_solid(triangles, projection, part_in_setup.vertices, part_in_setup.faces, part_in_setup.normals, kPartColour,
            max_side);
  add_solid(triangles, projection, fixture_mesh.vertices, fixture_mesh.faces, fixture_mesh.normals, kFixtureColour,
            max_side);

  const picture::Canvas canvas(width, height, "setup picture");
  cairo_t* cr = canvas.cr();
  paint_solids(cr, triangles);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  const double line_width = std::max(1.5, std::min(width, height) / 300.0);  // 2 px in a 900 x 600 picture
  draw_rapids(cr, projection, operations, line_width / 2);
  draw_cuts(cr, projection, operations, line_width);
  return canvas.png();
}

}  // namespace rosmill::core::sheet
