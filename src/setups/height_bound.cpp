#include "height_bound.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace rosmill::core::setups {
namespace {

// out[i] = the largest of in[i - k .. i + k] (clamped to the row), for a row of n values `stride` apart: the van
// Herk / Gil-Werman running maximum, three comparisons a value whatever k.
void running_max(const float* in, float* out, int n, size_t stride, int k, std::vector<float>& left,
                 std::vector<float>& right) {
  const int w = 2 * k + 1;
  left.assign(n, -INFINITY);
  right.assign(n, -INFINITY);
  for (int s = 0; s < n; s += w) {
    const int e = std::min(n, s + w);
    left[s] = in[s * stride];
    for (int i = s + 1; i < e; ++i) left[i] = std::max(left[i - 1], in[i * stride]);
    right[e - 1] = in[(e - 1) * stride];
    for (int i = e - 2; i >= s; --i) right[i] = std::max(right[i + 1], in[i * stride]);
  }
  for (int i = 0; i < n; ++i) {
    const int a = std::max(0, i - k), b = std::min(n - 1, i + k);
    // The window [a, b] spans two blocks, or lies in one only where it is cut short by the row's ends: then it
    // starts at its block's start (left[b]) or ends at its block's end (right[a]).
    if (a / w != b / w) out[i * stride] = std::max(right[a], left[b]);
    else out[i * stride] = a % w == 0 ? left[b] : right[a];
  }
}

}  // namespace

HeightBound::HeightBound(const Mesh& mesh, double cell, double margin) {
  const Box3& b = mesh.bbox;
  cell_ = cell;
  // The margin around the bounds, and a cell more: a triangle's box rounds outwards into it.
  const int around = static_cast<int>(std::ceil(margin / cell_)) + 2;
  x0_ = b.min.x() - around * cell_;
  y0_ = b.min.y() - around * cell_;
  nx_ = static_cast<int>(std::ceil(b.size().x() / cell_)) + 2 * around + 1;
  ny_ = static_cast<int>(std::ceil(b.size().y() / cell_)) + 2 * around + 1;
  top_.assign(static_cast<size_t>(nx_) * ny_, -INFINITY);
  for (size_t f = 0; f < mesh.face_count(); ++f) add_triangle(mesh.corner(f, 0), mesh.corner(f, 1), mesh.corner(f, 2));
}

void HeightBound::add_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double zmax = std::max({a.z(), b.z(), c.z()}), zmin = std::min({a.z(), b.z(), c.z()});
  const int i0 = std::max(0, static_cast<int>(std::floor((std::min({a.x(), b.x(), c.x()}) - x0_) / cell_)));
  const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((std::max({a.x(), b.x(), c.x()}) - x0_) / cell_)));
  const int j0 = std::max(0, static_cast<int>(std::floor((std::min({a.y(), b.y(), c.y()}) - y0_) / cell_)));
  const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((std::max({a.y(), b.y(), c.y()}) - y0_) / cell_)));
  // The plane z = p + q x + r y when the triangle is not steep: its highest over a cell is at a corner.
  const Vec3 n = (b - a).cross(c - a);
  const bool steep = std::abs(n.z()) < 1e-9 * n.norm() || n.norm() == 0;
  const double q = steep ? 0 : -n.x() / n.z(), r = steep ? 0 : -n.y() / n.z();
  const double p = a.z() - q * a.x() - r * a.y();
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      double h = zmax;
      if (!steep) {
        const double x = x0_ + (q > 0 ? i + 1 : i) * cell_, y = y0_ + (r > 0 ? j + 1 : j) * cell_;
        h = std::clamp(p + q * x + r * y, zmin, zmax);
      }
      float& t = top_[static_cast<size_t>(j) * nx_ + i];
      t = std::max(t, static_cast<float>(h));
    }
}

std::vector<float> HeightBound::grown(double radius) const {
  const int k = static_cast<int>(std::ceil(radius / cell_)) + 1;
  std::vector<float> rows(top_.size()), out(top_.size());
  std::vector<float> left, right;
  for (int j = 0; j < ny_; ++j)
    running_max(top_.data() + static_cast<size_t>(j) * nx_, rows.data() + static_cast<size_t>(j) * nx_, nx_, 1, k,
                left, right);
  for (int i = 0; i < nx_; ++i) running_max(rows.data() + i, out.data() + i, ny_, nx_, k, left, right);
  return out;
}

}  // namespace rosmill::core::setups
