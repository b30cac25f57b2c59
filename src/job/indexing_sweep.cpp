// The part turning on a trunnion while the tool waits above it (job_setup.hpp: check_indexing).
#include <algorithm>
#include <cmath>

#include "job_setup.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/number_text.hpp"

namespace rosmill::core::job {
namespace {

constexpr double kStepDeg = 0.5;  // the turn is looked at every half degree

std::string number(double v) { return decimal_text(v, 3); }

}  // namespace

void check_indexing(const stock::InProcessStock& stock, const TableSetting& table, const machine::Index& from,
                    const machine::Index& to, double clearance, const std::string& where) {
  const machine::Trunnion& t = table.trunnion();
  // Everything that turns, in the table's frame: the material and the fixture.
  std::vector<Vec3> points = stock.material_corners();
  for (Vec3& p : points) p = table.workpiece_on_table.point(p);
  for (const fixture::FixtureBox& b : table.fixture.boxes)
    for (int k = 0; k < 8; ++k)
      points.emplace_back(k & 1 ? b.box.max.x() : b.box.min.x(), k & 2 ? b.box.max.y() : b.box.min.y(),
                          k & 4 ? b.box.max.z() : b.box.min.z());
  if (points.empty()) return;
  double reach = 0;  // the farthest a point is from the axes: how far it goes between two looks
  for (const Vec3& p : points) reach = std::max(reach, (p - t.centre).norm() + t.pivot.norm());
  const double turn = std::max(std::abs(to.a - from.a), std::abs(to.c - from.c));
  const int steps = std::max(1, static_cast<int>(std::ceil(turn / kStepDeg)));
  const double between = reach * (turn / steps) * M_PI / 180.0;
  // The lowest a tool's tip can hang with the spindle at the safe Z; the spindle's head beside the tool is
  // wider than any holder, so nothing may turn above it, wherever the tool stands.
  const double tip = t.safe_z - t.max_tool_length - clearance;
  for (int s = 0; s <= steps; ++s) {
    const double f = double(s) / steps;
    const double a = from.a + f * (to.a - from.a), c = from.c + f * (to.c - from.c);
    const Placement turned = t.table_in_machine(a, c);
    for (const Vec3& p : points) {
      const Vec3 m = turned.point(p);
      if (m.z() + between < tip) continue;
      throw Error(where, "indexing the part from A " + number(from.a) + " C " + number(from.c) + " to A " +
                             number(to.a) + " C " + number(to.c) + " (the indexing block " + gcode::index_block(to.a, to.c) + ") turns it into the spindle: at A " + number(a) + " C " + number(c) +
                             " the part or its fixture reaches machine z " + number(m.z()) + ", within " + number(clearance) +
                             " mm of the tip of a tool " + number(t.max_tool_length) + " mm long waiting at G53 Z" +
                             number(t.safe_z) + "; raise the machine file's rotary.safe_z");
    }
  }
}

}  // namespace rosmill::core::job
