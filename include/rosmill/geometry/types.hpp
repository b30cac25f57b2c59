// Basic geometric value types shared by every area of the core (millimetres unless a name says otherwise).
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>

namespace rosmill::core {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

// Axis-aligned bounding box; empty until something is added.
struct Box3 {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  // The box between two corners.
  static Box3 between(const Vec3& a, const Vec3& b) {
    Box3 box;
    box.add(a);
    box.add(b);
    return box;
  }
  bool empty() const { return min.x() > max.x(); }
  void add(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void add(const Box3& b) {
    min = min.cwiseMin(b.min);
    max = max.cwiseMax(b.max);
  }
  Vec3 size() const { return empty() ? Vec3::Zero() : Vec3(max - min); }
};

}  // namespace rosmill::core
