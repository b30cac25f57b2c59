#include "rosmill/stock/fixture_collision.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rosmill/geometry/segment_distance.hpp"
#include "rosmill/number_text.hpp"
#include "rosmill/toolpath/canon_arc.hpp"

namespace rosmill::core::stock {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double point_rect_distance(const Vec2& p, const Vec2& lo, const Vec2& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(Vec2::Zero()).norm();
}

// Whether the segment a-b crosses the rectangle (Liang and Barsky's clipping of the segment's parameter).
bool segment_meets_rect(const Vec2& a, const Vec2& b, const Vec2& lo, const Vec2& hi) {
  double t0 = 0, t1 = 1;
  const Vec2 d = b - a;
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - a[k]) / d[k], tb = (hi[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

double segment_rect_distance(const Vec2& a, const Vec2& b, const Vec2& lo, const Vec2& hi) {
  if (segment_meets_rect(a, b, lo, hi)) return 0.0;
  double d = std::min(point_rect_distance(a, lo, hi), point_rect_distance(b, lo, hi));
  for (int c = 0; c < 4; ++c)
    d = std::min(d, segment_distance(Vec2(c & 1 ? hi.x() : lo.x(), c & 2 ? hi.y() : lo.y()), a, b));
  return d;
}

// An arc as everything over its XY bounding box between its end heights: more than it sweeps.
bool arc_sweeps_into(const CanonMove& m, double radius, double from, double to, const Box3& box) {
  Vec2 lo, hi;
  move_xy_bounds(m, lo, hi);
  const double eps = kFixtureClearance;
  const double zlo = std::min(m.from.z(), m.to.z()), zhi = std::max(m.from.z(), m.to.z());
  if (!(zlo + from < box.max.z() - eps && zhi + to > box.min.z() + eps)) return false;
  const Vec2 gap = (box.min.head<2>() - hi).cwiseMax(lo - box.max.head<2>()).cwiseMax(Vec2::Zero());
  return gap.norm() < radius - eps;
}

}  // namespace

ToolBody tool_body(const Tool& tool) {
  const Cutter& c = tool.cutter;
  const double stick_out = tool.stick_out_mm();
  return {ToolBodyPart{"cutter", c.radius(), 0.0, c.flute_length},
          ToolBodyPart{"shank", 0.5 * c.shank_diameter, c.flute_length, stick_out},
          ToolBodyPart{"holder", 0.5 * tool.holder_mm(), stick_out, kInf}};
}

bool sweeps_into(const Vec3& a, const Vec3& b, double radius, double from, double to, const Box3& box) {
  const double eps = kFixtureClearance;
  // Tip heights at which the cylinder's height range goes more than eps into the box's.
  const double lo_z = box.min.z() + eps - to, hi_z = box.max.z() - eps - from;
  double t0 = 0, t1 = 1;
  const double dz = b.z() - a.z();
  if (std::abs(dz) < 1e-12) {
    if (!(a.z() > lo_z && a.z() < hi_z)) return false;
  } else {
    double ta = (lo_z - a.z()) / dz, tb = (hi_z - a.z()) / dz;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (!(t0 < t1)) return false;
  }
  const Vec2 p = a.head<2>() + t0 * (b.head<2>() - a.head<2>()), q = a.head<2>() + t1 * (b.head<2>() - a.head<2>());
  return segment_rect_distance(p, q, box.min.head<2>(), box.max.head<2>()) < radius - eps;
}

std::string FixtureCollision::message() const {
  const auto point = [](const Vec3& p) {
    return "(" + decimal_text(p.x(), 3) + ", " + decimal_text(p.y(), 3) + ", " + decimal_text(p.z(), 3) + ")";
  };
  return "the " + part + " enters the fixture's " + box + " at move " + std::to_string(source) + " (a " +
         (rapid ? "rapid" : "feed") + " from " + point(from) + " to " + point(to) + " mm)";
}

std::optional<FixtureCollision> first_fixture_collision(const MachineProgram& program,
                                                        const fixture::Fixture& fixture) {
  if (fixture.empty()) return std::nullopt;
  std::vector<ToolBody> bodies;
  for (const Tool& t : program.tools) bodies.push_back(tool_body(t));
  const Box3 all = fixture.bounds();
  for (size_t k = 0; k < program.moves.size(); ++k) {
    const CanonMove& m = program.moves[k];
    if (m.tool >= bodies.size()) continue;
    for (const ToolBodyPart& part : bodies[m.tool]) {
      if (!(part.radius > 0)) continue;
      // The whole fixture first: most moves are nowhere near it.
      const auto meets = [&](const Box3& box) {
        return m.is_arc() ? arc_sweeps_into(m, part.radius, part.from, part.to, box)
                          : sweeps_into(m.from, m.to, part.radius, part.from, part.to, box);
      };
      if (!meets(all)) continue;
      for (const fixture::FixtureBox& b : fixture.boxes)
        if (meets(b.box)) return FixtureCollision{k, m.source, m.rapid, part.name, b.name, m.from, m.to};
    }
  }
  return std::nullopt;
}

}  // namespace rosmill::core::stock
