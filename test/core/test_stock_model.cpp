// The in-process stock: raw stock from a box, a closed mesh and a scanned cloud; material removed by programs with
// known volumes (a roughing pass over the cube primitive, a slot, a ball's plunge); a second identical pass
// removes nothing; a rapid through material is reported with its line; refusals before allocating.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rosmill/error.hpp"
#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/stock/in_process_stock.hpp"
#include "test_stock_programs.hpp"

using namespace stock_test;

TEST(StockModel, BoxStockMinusOneRoughingPassOverTheCube) {
  // Stock: the cube's footprint from the table to 5 mm above its top (cells of 0.7 mm do not fall on its sides).
  // Roughing clears every level down to the cube's top over its whole footprint and never enters the cube, so it
  // removes the 60 x 60 x 5 mm slab above it.
  const Mesh cube = make_primitive("cube");
  PlanningRequest request;
  request.input.mesh = &cube;
  request.strategy = "rough";
  request.params.tool.cutter = Cutter::flat(10);
  request.params.stepover = 4;
  request.params.stepdown = 2.5;
  const MachineProgram program = program_from_job(plan(request));
  Box3 box;
  box.add(Vec3(0, 0, 0));
  box.add(Vec3(60, 60, 65));
  const double cell = 0.7;
  InProcessStock stock = InProcessStock::box(box, cell);
  // A box of dexels errs only along its outline (cells whose centre is inside count whole).
  EXPECT_NEAR(stock.volume(), 60.0 * 60 * 65, outline_error(240, 65, cell));
  const double before = stock.volume();
  const RemovalReport first = stock.remove(program);
  EXPECT_NEAR(first.removed_mm3, 60.0 * 60 * 5, outline_error(240, 5, cell));
  EXPECT_NEAR(first.removed_mm3, before - stock.volume(), 1e-6 * before);
  EXPECT_NEAR(stock.volume(), 60.0 * 60 * 60, outline_error(240, 60, cell));
  EXPECT_GT(first.cut_cells, 0u);
  EXPECT_FALSE(first.collided()) << "line " << first.first_rapid_source;
  // Roughing from the cube's bounding box grown by 5 mm cuts air over most of its path in this stock.
  EXPECT_GT(first.air_cut_share(), 0.3);
  EXPECT_LT(first.air_cut_share(), 1.0);
  // The same program again cuts only air.
  const RemovalReport second = stock.remove(program);
  EXPECT_EQ(second.removed_mm3, 0.0);
  EXPECT_EQ(second.cut_cells, 0u);
  EXPECT_EQ(second.air_cut_share(), 1.0);
  EXPECT_FALSE(second.collided());
}

TEST(StockModel, SlotAndPlungeRemoveTheirAnalyticVolumes) {
  Box3 box;
  box.add(Vec3(0, 0, 0));
  box.add(Vec3(80, 40, 20));
  const double cell = 0.25;
  InProcessStock stock = InProcessStock::box(box, cell);
  // A 10 mm flat end 3 mm deep along 40 mm: a stadium of 40 x 10 plus a disc of radius 5, 3 mm deep.
  const RemovalReport slot =
      stock.remove(program_of(Cutter::flat(10), {{Vec3(20, 20, 30), Vec3(20, 20, 17)}, {Vec3(20, 20, 17),
                                                  Vec3(60, 20, 17)}, {Vec3(60, 20, 17), Vec3(60, 20, 30)}}));
  EXPECT_NEAR(slot.removed_mm3, (400 + M_PI * 25) * 3, outline_error(80 + 2 * M_PI * 5, 3, cell));
  // A 6 mm ball plunged 2 mm: a spherical cap, pi h^2 (3R - h) / 3.
  const RemovalReport cap =
      stock.remove(program_of(Cutter::ball(6), {{Vec3(10, 10, 25), Vec3(10, 10, 18)}}));
  const double cap_radius = std::sqrt(2 * 3 * 2 - 4);
  EXPECT_NEAR(cap.removed_mm3, M_PI * 4 * (9 - 2) / 3, outline_error(2 * M_PI * cap_radius, 2, cell));
  EXPECT_NEAR(stock.volume(), 80.0 * 40 * 20 - slot.removed_mm3 - cap.removed_mm3, 1e-3);
}

TEST(StockModel, RapidThroughMaterialIsACollisionWithItsLine) {
  Box3 box;
  box.add(Vec3(0, 0, 0));
  box.add(Vec3(40, 40, 20));
  InProcessStock stock = InProcessStock::box(box, 0.5);
  const MachineProgram p = program_of(Cutter::flat(10), {{Vec3(-10, 20, 30), Vec3(-10, 20, 10), false},
                                                         {Vec3(-10, 20, 10), Vec3(50, 20, 10), true},
                                                         {Vec3(50, 20, 10), Vec3(50, 20, 30), true}},
                                      7);
  const RemovalReport r = stock.remove(p);
  EXPECT_TRUE(r.collided());
  EXPECT_EQ(r.first_rapid_source, 8u);  // the second move: lines 7, 8, 9
  EXPECT_NEAR(r.removed_mm3, 40.0 * 10 * 10, 1e-3);  // the crash took the slot out (cells fall on its sides)
  // The plunge beside the stock cut nothing: a feed into air is no collision and removes nothing.
  InProcessStock again = InProcessStock::box(box, 0.5);
  const RemovalReport air = again.remove(program_of(Cutter::flat(10), {{Vec3(-10, 20, 30), Vec3(-10, 20, 10)}}));
  EXPECT_EQ(air.cut_cells, 0u);
  EXPECT_EQ(air.removed_mm3, 0.0);
  EXPECT_DOUBLE_EQ(air.feed_mm, 20.0);
  EXPECT_DOUBLE_EQ(air.air_feed_mm, 20.0);
}

TEST(StockModel, ClosedMeshStockHoldsTheMeshVolume) {
  const double cell = 0.5;
  for (const char* name : {"cube", "cylinder", "dome", "cone", "cavity"}) {
    const Mesh m = make_primitive(name);
    const InProcessStock stock = InProcessStock::from_mesh(m, cell);
    const Vec3 size = m.bbox.size();
    // Walls are at most the part's height; the outline is at most the bounding box's perimeter times pi / 2.
    const double bound = outline_error(M_PI * (size.x() + size.y()), size.z(), cell);
    EXPECT_NEAR(stock.volume(), report(m).volume, bound) << name;
  }
  // A box with a closed void inside: the lines through the void hold two spans.
  std::vector<Vec3> corners = box_corners(Vec3(0, 0, 0), Vec3(30, 30, 30));
  const std::vector<Vec3> hole = box_corners(Vec3(10, 10, 10), Vec3(20, 20, 20), true);
  corners.insert(corners.end(), hole.begin(), hole.end());
  const InProcessStock hollow = InProcessStock::from_mesh(build_mesh(corners), cell);
  EXPECT_NEAR(hollow.volume(), 27000.0 - 1000.0, 1e-3);
  const Dexels& d = hollow.material();
  const size_t through = d.grid.index(d.grid.first_x(15), d.grid.first_y(15));
  ASSERT_EQ(d.end(through) - d.begin(through), 2);
  EXPECT_FLOAT_EQ(d.begin(through)[0].hi, 10.0f);
  EXPECT_FLOAT_EQ(d.begin(through)[1].lo, 20.0f);
  // An open mesh holds no material: refused.
  std::vector<Vec3> open = box_corners(Vec3(0, 0, 0), Vec3(1, 1, 1));
  open.resize(open.size() - 3);
  EXPECT_THROW(InProcessStock::from_mesh(build_mesh(open), cell), Error);
}

TEST(StockModel, ScannedCloudOfTheDomeGivesItsVolume) {
  // The dome primitive scanned from above: points on its upward faces, 8 a square millimetre, with 0.05 mm of
  // noise along z, on the table at z 0.
  const Mesh dome = make_primitive("dome");
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> noise(0, 0.05);
  PointCloud cloud;
  for (size_t f = 0; f < dome.face_count(); ++f) {
    if (dome.normals[f].z() <= 0) continue;
    const double horizontal = dome.areas[f] * dome.normals[f].z();
    for (int k = 0; k < static_cast<int>(std::ceil(8 * horizontal)); ++k) {
      double a = u(rng), b = u(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      const Vec3 &p0 = dome.corner(f, 0), &p1 = dome.corner(f, 1), &p2 = dome.corner(f, 2);
      Vec3 p = p0 + a * (p1 - p0) + b * (p2 - p0);
      p.z() += noise(rng);
      cloud.points.push_back(p);
    }
  }
  cloud.recompute_bbox();
  const double cell = 0.5;
  const InProcessStock stock = InProcessStock::from_cloud(cloud, 0.0, cell);
  // Each cell holds the highest point over it: between the lowest and the highest of the surface over the cell,
  // plus the noise. Over the whole dome the surface's rise across a cell integrates to at most cell times the
  // integral of its slope, pi^2 r^2 / 2 for a hemisphere; the noise adds at most 3 sigma over the footprint.
  const double r = 50, bound = cell * M_PI * M_PI * r * r / 2 + 3 * 0.05 * M_PI * r * r;
  EXPECT_NEAR(stock.volume(), report(dome).volume, bound);
  // No cell outside the scanned outline got material from the hole filling.
  const Dexels& d = stock.material();
  size_t outside = 0;
  for (int j = 0; j < d.grid.ny; ++j)
    for (int i = 0; i < d.grid.nx; ++i) {
      const size_t c = d.grid.index(i, j);
      outside += std::hypot(d.grid.cx(i), d.grid.cy(j)) > r + cell && d.begin(c) != d.end(c);
    }
  EXPECT_EQ(outside, 0u);
}

// A scanner's pitch coarser than the grid both ways (2 mm against 0.5 mm cells): most cells hold no point, and
// three of every four rows and columns hold none either. Every cell inside the scanned square is stock, at the
// scanned height; none outside it.
TEST(StockModel, ScanSparserThanTheGridBothWaysLeavesNoHoles) {
  PointCloud cloud;
  for (int j = 0; j <= 20; ++j)
    for (int i = 0; i <= 20; ++i) {
      const double x = -20 + 2.0 * i, y = -20 + 2.0 * j;
      cloud.points.emplace_back(x, y, 30 + 0.1 * x);  // a slope: 28 to 32 mm
    }
  cloud.recompute_bbox();
  const InProcessStock stock = InProcessStock::from_cloud(cloud, 0.0, 0.5);
  const Dexels& d = stock.material();
  size_t holes = 0, outside = 0;
  for (int j = 0; j < d.grid.ny; ++j)
    for (int i = 0; i < d.grid.nx; ++i) {
      const size_t c = d.grid.index(i, j);
      const bool in = std::abs(d.grid.cx(i)) < 20 && std::abs(d.grid.cy(j)) < 20;
      const bool stocked = d.begin(c) != d.end(c);
      holes += in && !stocked;
      outside += !in && std::max(std::abs(d.grid.cx(i)), std::abs(d.grid.cy(j))) > 20.5 && stocked;
      if (in && stocked) {
        EXPECT_NEAR(d.begin(c)->hi, 30 + 0.1 * d.grid.cx(i), 0.1) << d.grid.cx(i);
      }
    }
  EXPECT_EQ(holes, 0u);
  EXPECT_EQ(outside, 0u);
  // 40 x 40 mm at 30 mm on average, within the half cell the outline's cells may add or leave all round.
  EXPECT_NEAR(stock.volume(), 40.0 * 40.0 * 30.0, 4 * 40.0 * 0.5 * 32.0);
}

TEST(StockModel, RefusesGridsBeyondTheBoundBeforeAllocating) {
  Box3 box;
  box.add(Vec3(0, 0, 0));
  box.add(Vec3(3000, 3000, 100));
  try {
    InProcessStock::box(box, 0.1);
    FAIL() << "a 900 M cell grid was allocated";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("MB"), std::string::npos) << what;
    EXPECT_NE(what.find("use a cell of"), std::string::npos) << what;
  }
  EXPECT_THROW(InProcessStock::box(box, -1), Error);
  EXPECT_THROW(InProcessStock::box(box, NAN), Error);
  InProcessStock ok = InProcessStock::box(box, 10);
  MachineProgram bad = program_of(Cutter::flat(10), {{Vec3(0, 0, 0), Vec3(NAN, 0, 0)}});
  EXPECT_THROW(ok.remove(bad), Error);
  bad = program_of(Cutter::flat(10), {{Vec3(0, 0, 0), Vec3(1, 0, 0)}});
  bad.moves[0].tool = 3;
  EXPECT_THROW(ok.remove(bad), Error);
}
