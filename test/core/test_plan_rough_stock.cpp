// Roughing from a stock mesh (plan/stock.hpp): a block tight around the part and a scaled copy of the part (an
// offset stock, as a casting or a previous stage leaves) give fewer cutting moves than the box, no cutting move
// lies further than the cutter's radius outside the stock's outline, and nothing gouges part + allowance (the
// independent reference of test_plan_check.hpp). A stock that is open or does not hold the part is refused, by
// the API and by `rosmill plan --stock`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli_run.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/plan/rough.hpp"
#include "rosmill/plan/stock.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/slice/slicer.hpp"
#include "rosmill/toolpath/toolpath_stats.hpp"
#include "test_plan_check.hpp"

using namespace rosmill::core;

namespace {

// The strategy table's rough on the part (it checks the stock mesh).
Job plan_rough(const Mesh& part, const PlanParams& p) {
  PlanningRequest r;
  r.input.mesh = &part;
  r.strategy = "rough";
  r.params = p;
  return plan(r);
}

}  // namespace
using namespace rosmill::core::test;

namespace {

// A closed box mesh, 12 triangles facing outwards.
Mesh block(const Vec3& lo, const Vec3& hi) {
  auto c = [&](int i) { return Vec3(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z()); };
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<Vec3> corners;
  for (const auto& q : quads)
    for (const int t : {1, 2}) corners.insert(corners.end(), {c(q[0]), c(q[t]), c(q[t + 1])});
  return build_mesh(corners);
}

// The mesh scaled by k about the origin.
Mesh scaled(const Mesh& m, double k) {
  std::vector<Vec3> corners;
  for (size_t f = 0; f < m.face_count(); ++f)
    for (int i = 0; i < 3; ++i) corners.push_back(k * m.corner(f, i));
  return build_mesh(corners);
}

size_t cutting_moves(const Toolpath& tp) {
  size_t n = 0;
  for (const ToolpathPass& pass : tp.passes)
    for (const Move& m : pass.moves) n += m.type != MoveType::Rapid;
  return n;
}

// Horizontal distance from p to the region bounded by closed contours (0 inside; even-odd rule).
double distance_to_section(const std::vector<Contour>& section, const Vec2& p) {
  bool inside = false;
  double best = 1e300;
  for (const Contour& c : section)
    for (size_t k = 0; k < c.points.size(); ++k) {
      const Vec2 &a = c.points[k], &b = c.points[(k + 1) % c.points.size()];
      if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()))
        inside = !inside;
      const Vec2 e = b - a;
      const double t = std::clamp((p - a).dot(e) / std::max(e.squaredNorm(), 1e-300), 0.0, 1.0);
      best = std::min(best, (a + t * e - p).norm());
    }
  return inside ? 0.0 : best;
}

// Every cutting move, sampled every 0.1 mm, lies within `reach` of the stock's section (slice/slicer) at its
// pass's level (ramps rise above the level, into the slab that level clears, whose widest section is the level's
// for the stocks here). Every straight plunge below the level cleared before ends in air: at least the cutter's
// radius less 0.01 mm from the section.
void expect_within_stock(const Toolpath& tp, const Mesh& stock, double radius, double top) {
  Vec3 at = tp.start;
  size_t outside = 0, checked = 0, air_plunges = 0;
  double above = top;
  for (const ToolpathPass& pass : tp.passes) {
    double level = 1e300;
    for (const Move& m : pass.moves)
      if (m.type != MoveType::Rapid) level = std::min(level, m.to.z());
    if (level == 1e300) continue;
    const std::vector<Contour> section = slice_mesh(stock, {level}).at(0).contours;
    for (const Move& m : pass.moves) {
      if (m.type == MoveType::Plunge && (m.to - at).head<2>().norm() < 1e-9 && m.to.z() < above - 1e-9) {
        ++air_plunges;
        EXPECT_GE(distance_to_section(section, m.to.head<2>()), radius - 0.01)
            << pass.name << ": a straight plunge into the stock at " << m.to.transpose();
      }
      if (m.type != MoveType::Rapid) {
        const int n = std::max(1, static_cast<int>(std::ceil((m.to - at).norm() / kAlongMoveStep)));
        for (int k = 0; k <= n; ++k) {
          const Vec3 p = at + (m.to - at) * (double(k) / n);
          ++checked;
          const double d = distance_to_section(section, p.head<2>());
          if (d > radius + 0.01) {
            ADD_FAILURE() << pass.name << ": cutting at " << p.transpose() << ", " << d << " mm from the stock";
            if (++outside > 5) return;
          }
        }
      }
      at = m.to;
    }
    above = level;
  }
  EXPECT_GT(checked, 100u);
  std::printf("  %zu points of cutting moves within the radius of the stock, %zu straight plunges in air\n", checked,
              air_plunges);
}

void compare_with_box(const std::string& name, const Mesh& part, const Mesh& stock, const Cutter& cutter,
                      double stepover, double stepdown, double allowance) {
  SCOPED_TRACE(name);
  PlanParams p;
  p.tool = default_tool(cutter);
  p.stepover = stepover;
  p.stepdown = stepdown;
  p.allowance = allowance;
  const Job box = plan_rough(part, p);
  p.stock_mesh = &stock;
  const Job mesh_stock = plan_rough(part, p);
  const size_t n_box = cutting_moves(box.at(0)), n_stock = cutting_moves(mesh_stock.at(0));
  std::printf("  %s: %zu cutting moves from the box, %zu from the stock mesh\n", name.c_str(), n_box, n_stock);
  EXPECT_LT(n_stock, n_box);
  const double cut_box = toolpath_stats(box.at(0)).cutting_length, cut_stock = toolpath_stats(mesh_stock.at(0)).cutting_length;
  std::printf("  cutting length %.0f mm from the box, %.0f mm from the stock mesh\n", cut_box, cut_stock);
  EXPECT_LT(cut_stock, cut_box);
  EXPECT_GT(n_stock, 0u);
  EXPECT_NEAR(mesh_stock.at(0).safe_z, stock.bbox.max.z() + p.safe_clearance, 1e-9);
  expect_within_stock(mesh_stock.at(0), stock, cutter.radius(), stock.bbox.max.z());
  expect_no_gouge(mesh_stock.at(0), part, allowance, name);
}

}  // namespace

TEST(PlanRoughStock, TightBlockAroundRelief) {
  const Mesh part = read_stl(ROSMILL_TEST_DATA "/mount_rush.stl");
  const Box3& b = part.bbox;
  const Mesh stock = block(Vec3(b.min.x() - 1, b.min.y() - 1, b.min.z()), Vec3(b.max.x() + 1, b.max.y() + 1, b.max.z() + 1));
  compare_with_box("mount_rush, block 1 mm around it, flat 10", part, stock, Cutter::flat(10), 8.0, 4.0, 0.5);
}

TEST(PlanRoughStock, OffsetOfThePart) {
  // The cone grown by 15 % about its base centre: a convex stock that holds it, 1.5 to 9 mm thick.
  const Mesh part = make_primitive("cone");
  const Mesh stock = scaled(part, 1.15);
  compare_with_box("cone, its copy scaled 1.15, flat 10", part, stock, Cutter::flat(10), 8.0, 6.0, 0.5);
}

TEST(PlanRoughStock, RefusesOpenOrTooSmallStock) {
  const Mesh part = make_primitive("cone");
  const Box3& b = part.bbox;
  PlanParams p;
  p.tool = default_tool(Cutter::flat(10));
  const Mesh open = read_stl(ROSMILL_TEST_DATA "/mount_rush.stl");
  ASSERT_FALSE(open.closed());
  p.stock_mesh = &open;
  try {
    plan_rough(part, p);
    ADD_FAILURE() << "an open stock was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not closed"), std::string::npos) << e.what();
  }
  // Lower than the part, and as high but missing its apex: both leave part of the cone outside.
  const Mesh low = block(b.min - Vec3(1, 1, 0), Vec3(b.max.x() + 1, b.max.y() + 1, 0.5 * b.max.z()));
  const Mesh scaled_down = scaled(part, 0.9);
  // Two blocks with a gap at x = 0: their bounding box holds the cone, the apex is in the gap.
  const Mesh left = block(b.min - Vec3(1, 1, 1), Vec3(-1, b.max.y() + 1, b.max.z() + 1));
  const Mesh right = block(Vec3(1, b.min.y() - 1, b.min.z() - 1), b.max + Vec3(1, 1, 1));
  std::vector<Vec3> both;
  for (const Mesh* m : {&left, &right})
    for (size_t f = 0; f < m->face_count(); ++f)
      for (int i = 0; i < 3; ++i) both.push_back(m->corner(f, i));
  const Mesh split = build_mesh(both);
  ASSERT_TRUE(split.closed());
  for (const Mesh* stock : {&low, &scaled_down, &split}) {
    p.stock_mesh = stock;
    try {
      plan_rough(part, p);
      ADD_FAILURE() << "a stock that does not hold the part was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("does not contain the part"), std::string::npos) << e.what();
    }
  }
}

TEST(PlanRoughStock, CommandLine) {
  const Mesh part = make_primitive("cone");
  const std::string dir = ::testing::TempDir();
  const std::string part_path = dir + "/rough_stock_part.stl", stock_path = dir + "/rough_stock_stock.stl",
                    small_path = dir + "/rough_stock_small.stl", open_path = ROSMILL_TEST_DATA "/mount_rush.stl";
  write_stl(part_path, part);
  write_stl(stock_path, scaled(part, 1.15));
  write_stl(small_path, scaled(part, 0.9));
  const std::string args = " --strategy rough --tool flat:10 --stepdown 6 --allowance 0.5 --json";
  const CliRun box = run_rosmill("plan " + part_path + args);
  const CliRun stock = run_rosmill("plan " + part_path + args + " --stock " + stock_path);
  ASSERT_EQ(box.status, 0) << box.err;
  ASSERT_EQ(stock.status, 0) << stock.err;
  const auto moves = [](const std::string& json) {
    const size_t at = json.find("\"moves\":");
    return at == std::string::npos ? -1L : std::stol(json.substr(at + 8));
  };
  EXPECT_GT(moves(stock.out), 0);
  EXPECT_LT(moves(stock.out), moves(box.out));
  const CliRun small = run_rosmill("plan " + part_path + args + " --stock " + small_path);
  EXPECT_NE(small.status, 0);
  EXPECT_NE(small.err.find("--stock"), std::string::npos) << small.err;
  EXPECT_NE(small.err.find("does not contain the part"), std::string::npos) << small.err;
  const CliRun open = run_rosmill("plan " + part_path + args + " --stock " + open_path);
  EXPECT_NE(open.status, 0);
  EXPECT_NE(open.err.find("not closed"), std::string::npos) << open.err;
  const CliRun raster = run_rosmill("plan " + part_path + " --strategy raster --stock " + stock_path);
  EXPECT_NE(raster.status, 0);
  EXPECT_NE(raster.err.find("rough and adaptive only"), std::string::npos) << raster.err;
  const CliRun missing = run_rosmill("plan " + part_path + args + " --stock " + dir + "/no_such_stock.stl");
  EXPECT_NE(missing.status, 0);
  EXPECT_NE(missing.err.find("no_such_stock.stl"), std::string::npos) << missing.err;
}
