#include "rosmill/geometry/sphere_sweep.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <limits>

namespace rosmill::core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The first t in [t_min, t_max] where the centre comes within r of corner v (t_min when it is already within).
double corner_contact(const Vec3& o, const Vec3& d, double r, const Vec3& v, double t_min, double t_max) {
  const Vec3 m = o + t_min * d - v;
  const double c = m.squaredNorm() - r * r;
  if (c <= 0) return t_min;
  const double b = m.dot(d);
  if (b >= 0) return kInf;  // moving away
  const double disc = b * b - c;
  if (disc < 0) return kInf;
  const double t = t_min + (-b - std::sqrt(disc));
  return t <= t_max ? t : kInf;
}

// The same for the edge from p to q, its ends left to the corners.
double edge_contact(const Vec3& o, const Vec3& d, double r, const Vec3& p, const Vec3& q, double t_min, double t_max) {
  const Vec3 e = q - p;
  const double len2 = e.squaredNorm();
  if (len2 == 0) return kInf;
  const Vec3 m = o + t_min * d - p;
  const double me = m.dot(e), de = d.dot(e);
  // Parts perpendicular to the edge, scaled by len2 to stay without a division.
  const Vec3 m_perp = m * len2 - e * me, d_perp = d * len2 - e * de;
  const double A = d_perp.squaredNorm(), B = m_perp.dot(d_perp), C = m_perp.squaredNorm() - r * r * len2 * len2;
  double t;
  if (C <= 0) {
    t = 0;  // already within r of the edge's line
  } else {
    if (A == 0 || B >= 0) return kInf;
    const double disc = B * B - A * C;
    if (disc < 0) return kInf;
    t = (-B - std::sqrt(disc)) / A;
  }
  const double along = me + t * de;  // the foot's place on the edge, times len2
  if (along < 0 || along > len2) return kInf;
  t += t_min;
  return t <= t_max ? t : kInf;
}

// The same for the face: the centre at distance r from its plane with the foot inside the triangle.
double face_contact(const Vec3& o, const Vec3& d, double r, const Vec3& a, const Vec3& b, const Vec3& c, double t_min,
                    double t_max) {
  Vec3 n = (b - a).cross(c - a);
  const double n_len = n.norm();
  if (n_len == 0) return kInf;
  n /= n_len;
  const Vec3 start = o + t_min * d;
  double s = n.dot(start - a);  // signed distance at t_min
  const double rate = n.dot(d);
  double t;
  if (std::abs(s) <= r) {
    t = 0;
  } else {
    // Approaching the side it is on: distance r is reached at (|s| - r) / closing speed.
    const double closing = s > 0 ? -rate : rate;
    if (closing <= 0) return kInf;
    t = (std::abs(s) - r) / closing;
    s = s > 0 ? r : -r;
  }
  const Vec3 foot = start + t * d - s * n;
  // Inside: the foot on the inner side of all three edges.
  const Vec3* corner[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    const Vec3& p = *corner[i];
    const Vec3& q = *corner[(i + 1) % 3];
    if ((q - p).cross(foot - p).dot(n) < 0) return kInf;
  }
  t += t_min;
  return t <= t_max ? t : kInf;
}

}  // namespace

double sphere_sweep_triangle(const Vec3& o, const Vec3& d, double r, const Vec3& a, const Vec3& b, const Vec3& c,
                             double t_min, double t_max) {
  double t = face_contact(o, d, r, a, b, c, t_min, t_max);
  if (t == t_min) return t;
  t = std::min(t, edge_contact(o, d, r, a, b, t_min, t_max));
  t = std::min(t, edge_contact(o, d, r, b, c, t_min, t_max));
  t = std::min(t, edge_contact(o, d, r, c, a, t_min, t_max));
  t = std::min(t, corner_contact(o, d, r, a, t_min, t_max));
  t = std::min(t, corner_contact(o, d, r, b, t_min, t_max));
  t = std::min(t, corner_contact(o, d, r, c, t_min, t_max));
  return t;
}

}  // namespace rosmill::core
