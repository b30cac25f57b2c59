// The in-process stock through several setups: a slot cut from above and one from below (the part turned over)
// compose; a pocket drilled into a side (-X) is seen from that side; the views and region queries answer from any
// setup; the exported surface is closed and holds the model's volume; the verifier and the stock agree on the
// material left on the bundled models (one removal kernel).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "bundled_models.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/stock/in_process_stock.hpp"
#include "rosmill/stock/stock_surface.hpp"
#include "rosmill/verify/verify.hpp"
#include "test_stock_programs.hpp"

using namespace stock_test;

namespace {

// A slot of a flat end along x at height z of the setup's frame, through y = y (entered and left outside x0..x1).
MachineProgram slot_along_x(double D, double x0, double x1, double y, double z, double clear) {
  return program_of(Cutter::flat(D), {{Vec3(x0, y, clear), Vec3(x0, y, z)}, {Vec3(x0, y, z), Vec3(x1, y, z)},
                                      {Vec3(x1, y, z), Vec3(x1, y, clear)}});
}

std::vector<Span> spans_at(const InProcessStock& s, double x, double y) {
  const GridSpec& g = s.grid();
  const size_t c = g.index(g.first_x(x), g.first_y(y));
  return {s.material().begin(c), s.material().end(c)};
}

}  // namespace

TEST(StockSetups, CuttingFromBelowRemovesTheUnderside) {
  InProcessStock stock = InProcessStock::box(Box3::between(Vec3(0, 0, 0), Vec3(40, 30, 20)), 0.5);
  // +Z: a 10 mm slot 3 mm deep through y 10..20.
  const RemovalReport top = stock.remove(slot_along_x(10, -10, 50, 15, 17, 30));
  EXPECT_NEAR(top.removed_mm3, 40.0 * 10 * 3, 1e-3);
  // -Z (turned over about x: workpiece (x, y, z) is (x, -y, -z)): a slot 2 mm into the underside through y 5..15.
  const SetupFrame below = named_setup("-Z");
  ASSERT_NEAR(below.to_setup_frame(Vec3(1, 2, 3)).y(), -2, 1e-12);
  const RemovalReport under = stock.remove(slot_along_x(10, -10, 50, -10, -2, 10), below);
  EXPECT_NEAR(under.removed_mm3, 40.0 * 10 * 2, 1e-3);
  EXPECT_NEAR(stock.volume(), 40.0 * 30 * 20 - 1200 - 800, 1e-3);
  // The workpiece's lines: under the bottom slot only, under both, under the top slot only.
  auto only_bottom = spans_at(stock, 20, 7), both = spans_at(stock, 20, 12), only_top = spans_at(stock, 20, 17);
  ASSERT_EQ(only_bottom.size(), 1u);
  EXPECT_FLOAT_EQ(only_bottom[0].lo, 2.0f);
  EXPECT_FLOAT_EQ(only_bottom[0].hi, 20.0f);
  ASSERT_EQ(both.size(), 1u);
  EXPECT_FLOAT_EQ(both[0].lo, 2.0f);
  EXPECT_FLOAT_EQ(both[0].hi, 17.0f);
  ASSERT_EQ(only_top.size(), 1u);
  EXPECT_FLOAT_EQ(only_top[0].lo, 0.0f);
  // Seen from below, the slot of the underside is 2 mm down; from above, the top slot 3 mm down.
  const HeightField from_below = stock.view(below), from_above = stock.view();
  const GridSpec& gb = from_below.grid;
  EXPECT_FLOAT_EQ(from_below.top[gb.index(gb.first_x(20), gb.first_y(-10.2))], -2.0f);
  EXPECT_NEAR(from_below.top[gb.index(gb.first_x(20), gb.first_y(-25.2))], 0.0, 1e-9);  // the turn rounds
  const GridSpec& ga = from_above.grid;
  EXPECT_FLOAT_EQ(from_above.top[ga.index(ga.first_x(20), ga.first_y(15.2))], 17.0f);
  // Region queries in each frame.
  EXPECT_FALSE(stock.material_in(Vec2(5, 11), Vec2(35, 19), 17.5));
  EXPECT_TRUE(stock.material_in(Vec2(5, 11), Vec2(35, 19), 16.5));
  EXPECT_FALSE(stock.material_in(Vec2(5, -14), Vec2(35, -6), -1.5, below));
  EXPECT_TRUE(stock.material_in(Vec2(5, -14), Vec2(35, -6), -2.5, below));
  // The same slots again cut nothing, in either setup.
  EXPECT_EQ(stock.remove(slot_along_x(10, -10, 50, 15, 17, 30)).cut_cells, 0u);
  EXPECT_EQ(stock.remove(slot_along_x(10, -10, 50, -10, -2, 10), below).cut_cells, 0u);
}

TEST(StockSetups, PocketInASideIsSeenFromThatSide) {
  InProcessStock stock = InProcessStock::box(Box3::between(Vec3(0, 0, 0), Vec3(40, 30, 20)), 0.25);
  // -X: the tool comes from x < 0; a 10 mm flat plunged 4 mm into the face x = 0 at y 15, z 10.
  const SetupFrame side = named_setup("-X");
  const Vec3 face = side.to_setup_frame(Vec3(0, 15, 10));
  ASSERT_NEAR(face.z(), 0, 1e-9);
  const Vec3 up = Vec3(face.x(), face.y(), 10), down = Vec3(face.x(), face.y(), -4);
  const RemovalReport r = stock.remove(program_of(Cutter::flat(10), {{up, down}, {down, up}}), side);
  // A cylinder of radius 5 and depth 4, its outline quantised on the side's grid and its depth on the stock's.
  const double cell = 0.25;
  EXPECT_NEAR(r.removed_mm3, M_PI * 25 * 4, outline_error(2 * M_PI * 5, 4, cell) + M_PI * 25 * cell);
  const HeightField v = stock.view(side);
  const GridSpec& g = v.grid;
  EXPECT_FLOAT_EQ(v.top[g.index(g.first_x(face.x() + 0.1), g.first_y(face.y() + 0.1))], -4.0f);
  EXPECT_NEAR(v.top[g.index(g.first_x(face.x() + 8), g.first_y(face.y() + 0.1))], 0.0, 1e-6);
  EXPECT_FALSE(stock.material_in(face.head<2>() - Vec2(3, 3), face.head<2>() + Vec2(3, 3), -3.5, side));
  EXPECT_TRUE(stock.material_in(face.head<2>() - Vec2(3, 3), face.head<2>() + Vec2(3, 3), -4.5, side));
  // From above nothing changed at the pocket's centre line: it is inside the block, under 10 mm of material.
  EXPECT_FLOAT_EQ(stock.view().top[stock.grid().index(stock.grid().first_x(1), stock.grid().first_y(15.1))], 20.0f);
  // The workpiece line through the pocket lost its middle.
  const auto through = spans_at(stock, 1, 15.1);
  ASSERT_EQ(through.size(), 2u);
  EXPECT_NEAR(through[0].hi, 5.0, cell);
  EXPECT_NEAR(through[1].lo, 15.0, cell);
}

TEST(StockSetups, MaterialAboveTheDesign) {
  // The cube primitive in a box 5 mm taller: 5 mm above the design over the cube, none elsewhere in this stock.
  const Mesh cube = make_primitive("cube");
  const InProcessStock stock = InProcessStock::box(Box3::between(Vec3(0, 0, 0), Vec3(60, 60, 65)), 1.0);
  const std::vector<float> above = stock.material_above(cube);
  for (float a : above) ASSERT_NEAR(a, 5.0, 1e-5);
  // From -X the box stands 0 mm beyond the cube's side x = 0 (the stock's side is the cube's).
  const std::vector<float> side = stock.material_above(cube, named_setup("-X"));
  const HeightField v = stock.view(named_setup("-X"));
  size_t compared = 0;
  for (size_t c = 0; c < side.size(); ++c)
    if (!std::isnan(side[c]) && v.top[c] != kNoMaterial && std::abs(v.top[c]) < 1e-6) {
      // Cells over the cube's side: no material above it, except the 5 mm the cube does not reach.
      EXPECT_GE(side[c], -1e-5);
      ++compared;
    }
  EXPECT_GT(compared, 3000u);
}

TEST(StockSetups, ExportedSurfaceIsClosedWithTheModelVolume) {
  const double cell = 0.5;
  InProcessStock stock = InProcessStock::box(Box3::between(Vec3(0, 0, 0), Vec3(40, 30, 20)), cell);
  stock.remove(slot_along_x(10, -10, 50, 15, 17, 30));
  stock.remove(slot_along_x(10, -10, 50, -10, -2, 10), named_setup("-Z"));
  stock.remove(program_of(Cutter::ball(6), {{Vec3(10, 10, 30), Vec3(10, 10, 18)}}));
  const Mesh m = stock_surface(stock);
  const MeshReport r = report(m);
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.nonmanifold_edges, 0u);
  EXPECT_EQ(r.inconsistent_edges, 0u);
  // The surface stays within half a cell of the model's prisms (it cuts their edges and corners).
  EXPECT_NEAR(r.volume, stock.volume(), r.area * cell / 2);
  EXPECT_NEAR(r.volume, stock.volume(), 0.01 * stock.volume());
  EXPECT_NEAR(m.bbox.min.x(), 0, 1e-9);
  EXPECT_NEAR(m.bbox.max.y(), 30, 1e-9);
  EXPECT_NEAR(m.bbox.max.z(), 20, 1e-5);
  // Written through the io area's STL writer and read back.
  const std::string path = ::testing::TempDir() + "stock_surface.stl";
  write_stock_stl(path, stock);
  EXPECT_EQ(read_stl(path).face_count(), m.face_count());
  std::remove(path.c_str());
  // A lattice beyond the bound is refused, with the cell that fits.
  EXPECT_THROW(stock_surface(stock, 0.01), Error);
}

TEST(StockSetups, VerifierAndStockAgreeOnTheBundledModels) {
  for (const auto& model : test_data::kBundledModels) {
    if (!model.small) continue;
    StlReadOptions o;
    o.units = model.units;
    const Mesh design = read_stl(std::string(ROSMILL_TEST_DATA) + "/" + model.file, o);
    const Box3 b = design.bbox;
    const double cell = std::max(b.size().x(), b.size().y()) / 300;
    // A 6 mm ball raster half-way down the part, lines along x every 2 mm, entered and left outside the part.
    const double z = 0.5 * (b.min.z() + b.max.z());
    std::vector<Step> steps{{Vec3(b.min.x() - 5, b.min.y(), b.max.z() + 5), Vec3(b.min.x() - 5, b.min.y(), z), true}};
    for (double y = b.min.y(); y <= b.max.y(); y += 2) {
      const Vec3 at = steps.back().to;
      const Vec3 row(at.x(), y, z), end(at.x() < b.min.x() ? b.max.x() + 5 : b.min.x() - 5, y, z);
      steps.push_back({at, row});
      steps.push_back({row, end});
    }
    const MachineProgram program = program_of(Cutter::ball(6), steps);
    verify::VerifyOptions vo;
    vo.resolution = cell;
    const verify::VerifyResult v = verify::verify_program(design, program, verify::StockSpec{}, vo);
    InProcessStock stock = InProcessStock::box(b, cell);
    stock.remove(program);
    const std::vector<float> above = stock.material_above(design);
    ASSERT_EQ(above.size(), v.grid.deviation.size()) << model.file;
    size_t compared = 0;
    for (size_t c = 0; c < above.size(); ++c) {
      if (std::isnan(above[c])) continue;  // outside the box (the verifier's grid reaches a part of a cell beyond)
      ASSERT_NEAR(above[c], v.grid.deviation[c], 1e-4) << model.file << " cell " << c;
      ++compared;
    }
    EXPECT_GT(compared, above.size() / 2) << model.file;
  }
}
