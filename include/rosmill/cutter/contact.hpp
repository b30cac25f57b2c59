// Exact drop-cutter contacts of one cutter with a vertex, an edge and a facet (the kernels behind every drop).
//
// Every cutter here is one profile: a flat disc of radius R1 = R - r at the tip, then a quarter circle of radius
// r up to the full radius R (flat end: r = 0; ball: R1 = 0; bull nose: both > 0). With the axis at (x, y), a
// point at horizontal distance d <= R from the axis meets the cutter at height h(d) above the tip, so the
// lowest tip that does not go into a point p is p.z - h(d). h is convex and rising in d and d is convex along
// any line or plane, so p.z - h(d) is concave over a triangle: its maximum is at a vertex, on an edge at the
// one stationary point of a concave 1-D function, or inside the facet where the cutter's normal equals the
// facet's. Each function below returns -infinity when the feature is out of reach.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>

#include "rosmill/cutter/cutter.hpp"

namespace rosmill::core {

constexpr double kNoContact = -std::numeric_limits<double>::infinity();

// The cutter's profile numbers, computed once per query.
struct CutterProfile {
  double R = 0, R2 = 0;  // full radius and its square
  double r = 0;          // corner radius (0 flat, R ball)
  double R1 = 0;         // radius of the flat bottom (R - r)
  CutterType type = CutterType::FlatEnd;

  explicit CutterProfile(const Cutter& c)
      : R(c.radius()), R2(R * R),
        r(c.type == CutterType::FlatEnd ? 0.0 : c.type == CutterType::BallEnd ? R : c.corner_radius),
        R1(R - r), type(r <= 0 ? CutterType::FlatEnd : (R1 <= 0 ? CutterType::BallEnd : c.type)) {
    if (type == CutterType::BallEnd) R1 = 0, r = R;
  }

  // The squared reach of the cutter with its axis at (x, y): a feature at the rim's distance is touched, however
  // the last bit of its coordinates and of the axis's fell. Those are rounded to about eps times their size (a
  // grid at ymin - R lands a few ulps beyond R of ymin), so the rim is widened by a few such roundings, scaled to
  // the coordinates; the same rule for vertices, edges and the boxes that cull them. Touching is the safe side:
  // it lifts the cutter by the feature's height at the rim, where a miss can drop it into a wall.
  double reach_sq(double x, double y) const {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    const double reach = R + 8 * eps * (std::abs(x) + std::abs(y) + R);
    return reach * reach;
  }

  // Height of the cutter surface above the tip at horizontal distance d (d <= R; the rim's height just beyond).
  double height(double d) const {
    if (d <= R1) return 0.0;
    const double e = std::min(d - R1, r);
    return r - std::sqrt(std::max(0.0, r * r - e * e));
  }
  // The same from d^2, with one square root less for the two common shapes.
  double height_sq(double d2) const {
    if (type == CutterType::FlatEnd) return 0.0;
    if (type == CutterType::BallEnd) return r - std::sqrt(std::max(0.0, r * r - d2));
    return height(std::sqrt(d2));
  }
};

// A triangle prepared for contacts: corners, the plane z = a x + b y + c, the upward unit normal.
struct ContactTriangle {
  double p[3][3];      // corners
  double a, b, c;      // plane as a height field (valid when nz > 0)
  double ux, uy;       // horizontal direction of the upward normal (unit), 0 when the facet is level
  double nxy, nz;      // horizontal and vertical parts of the upward unit normal; nz = 0: vertical or degenerate
  double zmax;         // highest corner
  double xmin, xmax, ymin, ymax;
  unsigned char own;   // bits 0-2: this triangle tests corner i; bits 3-5: it tests edge i (corner i to i+1)
};

// Builds the record; `own` says which corners and edges this triangle is responsible for.
ContactTriangle make_contact_triangle(const double* p0, const double* p1, const double* p2, unsigned char own);

inline double vertex_contact(const CutterProfile& cp, double x, double y, const double* v) {
  const double dx = v[0] - x, dy = v[1] - y, d2 = dx * dx + dy * dy;
  if (d2 > cp.reach_sq(x, y)) return kNoContact;
  return v[2] - cp.height_sq(std::min(d2, cp.R2));
}

// Facet interior: the cutter point whose normal is the facet's lies at a fixed offset from the axis.
inline double facet_contact(const CutterProfile& cp, double x, double y, const ContactTriangle& t) {
  if (t.nz <= 1e-12) return kNoContact;
  const double k = cp.R1 + cp.r * t.nxy;
  const double cx = x - k * t.ux, cy = y - k * t.uy;
  // Inside the triangle's XY projection: the three edge cross products share a sign.
  double s[3];
  for (int i = 0; i < 3; ++i) {
    const double* A = t.p[i];
    const double* B = t.p[(i + 1) % 3];
    s[i] = (B[0] - A[0]) * (cy - A[1]) - (B[1] - A[1]) * (cx - A[0]);
  }
  const bool inside = (s[0] >= 0 && s[1] >= 0 && s[2] >= 0) || (s[0] <= 0 && s[1] <= 0 && s[2] <= 0);
  if (!inside) return kNoContact;
  return t.a * cx + t.b * cy + t.c - cp.r * (1.0 - t.nz);
}

// Maximum over w >= w_lo of g(w) = m w - h(sqrt(d0^2 + w^2)) for m > 0 (the torus part of a bull nose meeting a
// line): g is concave, so the root of g' is found by bisection safeguarded Newton in [w_lo, w_hi].
double torus_line_argmax(const CutterProfile& cp, double d0sq, double m, double w_lo, double w_hi);

// Edge from P to Q (interior points only: the corners are vertex contacts).
inline double edge_contact(const CutterProfile& cp, double x, double y, const double* P, const double* Q) {
  const double ex = Q[0] - P[0], ey = Q[1] - P[1];
  const double L2 = ex * ex + ey * ey;
  if (L2 < 1e-24) return kNoContact;  // vertical edge: its top corner is the contact
  const double px = x - P[0], py = y - P[1];
  const double t0 = (px * ex + py * ey) / L2;  // foot of the axis on the edge's line
  // Squared distance of the axis from the line by the cross product: no cancellation when the axis is at the
  // rim's distance (|p|^2 - t0^2 L^2 loses the digits that the chord's half length, a square root, needs).
  const double cross = px * ey - py * ex;
  double d0sq = cross * cross / L2;
  const double L = std::sqrt(L2);
  if (d0sq > cp.R2) {
    // An edge at the rim's distance (within its rounding, CutterProfile::reach_sq) is tangent to the cutter.
    if (d0sq > cp.reach_sq(x, y)) return kNoContact;
    d0sq = cp.R2;
  }
  const double half = std::sqrt(cp.R2 - d0sq) / L;  // half the chord of the footprint, in t
  const double lo = std::max(0.0, t0 - half), hi = std::min(1.0, t0 + half);
  if (lo > hi) return kNoContact;
  const double dz = Q[2] - P[2];
  switch (cp.type) {
    case CutterType::FlatEnd: {
      // z is linear along the chord: the highest chord end.
      return P[2] + dz * (dz > 0 ? hi : lo);
    }
    case CutterType::BallEnd: {
      // In the edge's vertical plane the ball is a circle of radius s; tangent point of a line of slope m.
      const double s = std::sqrt(cp.R2 - d0sq), m = dz / L;
      const double q = 1.0 / std::sqrt(1.0 + m * m);
      const double t = t0 + s * m * q / L;
      if (t < 0.0 || t > 1.0) return kNoContact;
      return P[2] + dz * t - cp.R + s * q;
    }
    case CutterType::BullNose: {
      double m = dz / L;
      const double sign = m >= 0 ? 1.0 : -1.0;
      m *= sign;
      const double w_lo = std::sqrt(std::max(0.0, cp.R1 * cp.R1 - d0sq));
      const double w_hi = std::sqrt(cp.R2 - d0sq);
      const double w = m == 0 ? 0.0 : torus_line_argmax(cp, d0sq, m, w_lo, w_hi);
      const double t = t0 + sign * w / L;
      if (t < 0.0 || t > 1.0) return kNoContact;
      return P[2] + dz * t - cp.height(std::sqrt(d0sq + w * w));
    }
  }
  return kNoContact;
}

// Highest tip over one triangle's owned corners, owned edges and facet.
inline double triangle_contact(const CutterProfile& cp, double x, double y, const ContactTriangle& t) {
  double z = facet_contact(cp, x, y, t);
  for (int i = 0; i < 3; ++i) {
    if (t.own & (1u << i)) z = std::max(z, vertex_contact(cp, x, y, t.p[i]));
    if (t.own & (8u << i)) z = std::max(z, edge_contact(cp, x, y, t.p[i], t.p[(i + 1) % 3]));
  }
  return z;
}

}  // namespace rosmill::core
