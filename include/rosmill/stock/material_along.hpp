// Material along a line off a face of the design: how far it runs out from a point of the face along the face's
// normal, and how deep a cut went in under the point. What the account of the material left on a part and the
// verifier of a multi-axis program read from the in-process stock's exact point queries (StockProbe).
#pragma once
#include "rosmill/geometry/mesh_ray.hpp"
#include "rosmill/geometry/types.hpp"
#include "rosmill/stock/in_process_stock.hpp"

namespace rosmill::core::stock {

constexpr double kOffFace = 1e-5;        // mm: just off the face, where the material left on it begins
constexpr double kRunResolution = 1e-4;  // mm: how finely the end of a run is found
constexpr double kDeepestGouge = 20.0;   // mm: how far inside the part a gouge is followed at most

// How far from p along n `inside` holds, up to `end`: probed at `probe` first (a run shorter than that is found by
// halving alone), then followed out `step` at a time and halved.
template <class Inside>
double run_along(const Inside& inside, const Vec3& p, const Vec3& n, double probe, double end, double step) {
  if (end <= kOffFace || !inside(p + kOffFace * n)) return 0.0;
  double lo = kOffFace, hi = std::min(std::max(probe, kOffFace), end);
  if (inside(p + hi * n)) {
    lo = hi;
    for (;;) {
      hi = std::min(lo + step, end);
      if (!inside(p + hi * n)) break;
      if (hi >= end) return end;
      lo = hi;
    }
  }
  while (hi - lo > kRunResolution) {
    const double mid = 0.5 * (lo + hi);
    (inside(p + mid * n) ? lo : hi) = mid;
  }
  return hi;
}

// How deep a cut went into the part under p, n the face's outward normal (0: none beyond `tolerance`), followed in
// `step` at a time and halved.
inline double gouge_under(StockProbe& s, const Vec3& p, const Vec3& n, double tolerance, double step) {
  if (!s.removed_at(p - tolerance * n)) return 0.0;
  double lo = tolerance, hi = tolerance;
  while (hi < kDeepestGouge && s.removed_at(p - hi * n)) lo = hi, hi += step;
  while (hi - lo > kRunResolution) {
    const double mid = 0.5 * (lo + hi);
    (s.removed_at(p - mid * n) ? lo : hi) = mid;
  }
  return lo;
}

// How far the material runs from the face at p along n, up to where it must end (the raw stock's box, or the part
// met again: `part` the design's rays). More than `probe` counts only as far as the material is more than a sliver:
// along a ray that runs inside the few micrometres a cutter leaves in a facet's corner, the material is that
// sliver's width, not the ray's length.
inline double material_thickness(StockProbe& probe_stock, const InProcessStock& stock, const MeshRays& part,
                                 const Vec3& p, const Vec3& n, double probe, double step) {
  const double box = stock.raw_extent(p, n, 1e6);
  const double end = std::min(box, part.first_hit(p, n, kOffFace, box));
  const auto material = [&](const Vec3& q) { return probe_stock.material_at(q); };
  const double left = run_along(material, p, n, probe, end, step);
  if (left <= probe) return left;
  const auto solid = [&](const Vec3& q) { return probe_stock.solid_at(q); };
  return std::min(left, run_along(solid, p, n, 0.0, end, step) + stock.near_distance());
}

}  // namespace rosmill::core::stock
