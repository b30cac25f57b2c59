// Where vertical rays through the cell centres of a grid meet a mesh: the one rasteriser behind the design's top
// surface (the highest hit) and a closed mesh's solid (the hits paired by their facing, Z-dexels).
#pragma once
#include <algorithm>
#include <cmath>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/stock/height_field.hpp"

namespace rosmill::core::stock {

// Calls hit(cell index, z, facing_up) for every triangle a vertical ray through a cell centre (moved by `shift`)
// meets. A triangle is rasterised over the cells of its XY bounds only, so each cell meets only the triangles
// above or below it. Barycentric weights down to `eps` count as inside: a small negative eps makes a ray on a
// shared edge meet both triangles (a top surface wants that); a shift off the grid's lattice keeps rays off the
// edges and vertices altogether (the parity of a solid wants that). Vertical triangles are never met.
template <class Hit>
void for_each_vertical_hit(const Mesh& mesh, const GridSpec& g, const Vec2& shift, double eps, Hit&& hit) {
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const Vec3 &a = mesh.corner(f, 0), &b = mesh.corner(f, 1), &c = mesh.corner(f, 2);
    const double area2 = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(area2) < 1e-12) continue;
    const bool facing_up = area2 > 0;
    const int i0 = g.first_x(std::min({a.x(), b.x(), c.x()}) - shift.x());
    const int i1 = g.last_x(std::max({a.x(), b.x(), c.x()}) - shift.x());
    const int j0 = g.first_y(std::min({a.y(), b.y(), c.y()}) - shift.y());
    const int j1 = g.last_y(std::max({a.y(), b.y(), c.y()}) - shift.y());
    const double inv = 1.0 / area2;
    for (int j = j0; j <= j1; ++j) {
      const double y = g.cy(j) + shift.y();
      for (int i = i0; i <= i1; ++i) {
        const double x = g.cx(i) + shift.x();
        // Barycentric weights of (x, y) in the triangle's XY projection.
        const double wa = ((b.x() - x) * (c.y() - y) - (c.x() - x) * (b.y() - y)) * inv;
        const double wb = ((c.x() - x) * (a.y() - y) - (a.x() - x) * (c.y() - y)) * inv;
        const double wc = 1.0 - wa - wb;
        if (wa < eps || wb < eps || wc < eps) continue;
        hit(g.index(i, j), wa * a.z() + wb * b.z() + wc * c.z(), facing_up);
      }
    }
  }
}

}  // namespace rosmill::core::stock
