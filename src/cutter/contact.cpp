#include "rosmill/cutter/contact.hpp"

#include <algorithm>

#include "rosmill/error.hpp"

namespace rosmill::core {

ContactTriangle make_contact_triangle(const double* p0, const double* p1, const double* p2, unsigned char own) {
  ContactTriangle t{};
  const double* P[3] = {p0, p1, p2};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) t.p[i][k] = P[i][k];
  const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (len > 0) {
    // The drop only sees the upper side: the facet's orientation in the file does not matter.
    const double s = (n[2] < 0 ? -1.0 : 1.0) / len;
    for (double& v : n) v *= s;
    t.nz = n[2];
    t.nxy = std::sqrt(n[0] * n[0] + n[1] * n[1]);
    if (t.nxy > 0) t.ux = n[0] / t.nxy, t.uy = n[1] / t.nxy;
    if (t.nz > 1e-12) {
      t.a = -n[0] / n[2];
      t.b = -n[1] / n[2];
      t.c = p0[2] - t.a * p0[0] - t.b * p0[1];
    }
  }
  t.zmax = std::max({p0[2], p1[2], p2[2]});
  t.xmin = std::min({p0[0], p1[0], p2[0]});
  t.xmax = std::max({p0[0], p1[0], p2[0]});
  t.ymin = std::min({p0[1], p1[1], p2[1]});
  t.ymax = std::max({p0[1], p1[1], p2[1]});
  t.own = own;
  return t;
}

double torus_line_argmax(const CutterProfile& cp, double d0sq, double m, double w_lo, double w_hi) {
  // g'(w) = m - phi(w), phi(w) = h'(d) w / d rises from 0 (flat bottom) to infinity (rim): one root.
  const double r2 = cp.r * cp.r;
  auto phi = [&](double w, double* slope) {
    const double d = std::sqrt(d0sq + w * w);
    const double e = d - cp.R1;
    if (e <= 0 || d <= 0) {
      *slope = 0;
      return 0.0;
    }
    const double q = std::max(r2 - e * e, 1e-300);
    const double sq = std::sqrt(q);
    const double wd = w / d;
    *slope = r2 / (q * sq) * wd * wd + e / sq * d0sq / (d * d * d);
    return e / sq * wd;
  };
  double lo = w_lo, hi = w_hi, w = 0.5 * (lo + hi);
  for (int it = 0; it < 100 && hi - lo > 1e-12 * (1.0 + cp.R); ++it) {
    double slope;
    const double gp = m - phi(w, &slope);
    if (gp > 0) lo = w; else hi = w;
    double next = slope > 0 ? w + gp / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // Newton left the bracket: bisect
    if (std::abs(next - w) < 1e-14 * (1.0 + cp.R)) {
      w = next;
      break;
    }
    w = next;
  }
  return w;
}

}  // namespace rosmill::core
