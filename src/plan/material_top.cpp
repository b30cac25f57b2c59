#include "rosmill/plan/material_top.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::core {

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

void MaterialTop::check(const std::string& where) const {
  if (!(cell > 0) || !std::isfinite(cell) || !std::isfinite(x0) || !std::isfinite(y0))
    throw Error(where, "the material grid needs a positive cell and a finite corner");
  const size_t cells = static_cast<size_t>(std::max(nx, 0)) * static_cast<size_t>(std::max(ny, 0));
  if (nx <= 0 || ny <= 0 || top.size() != cells)
    throw Error(where, "the material grid's heights (" + std::to_string(top.size()) + ") do not fill its " +
                           std::to_string(nx) + " x " + std::to_string(ny) + " cells");
  if (!rest.empty() && rest.size() != cells)
    throw Error(where, "the rest cells (" + std::to_string(rest.size()) + ") do not fill the material grid");
}

double MaterialTop::highest() const {
  double h = -INFINITY;
  for (float t : top) h = std::max(h, double(t));
  return h;
}

double MaterialTop::highest_along(const Vec2& a, const Vec2& b, double radius) const {
  double h = -INFINITY;
  cells_near(a, b, radius + cell, [&](size_t c, double) { h = std::max(h, double(top[c])); });
  return h;
}

bool MaterialTop::rest_near(const Vec2& p, double radius) const {
  bool found = false;
  if (rest.empty()) return false;
  cells_near(p, p, radius, [&](size_t c, double) { found = found || rest[c]; });
  return found;
}

}  // namespace rosmill::core
