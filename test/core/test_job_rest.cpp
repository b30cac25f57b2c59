// Planning that knows the stock, rest machining and the machining time (known answers):
// - one trapezoidal move (exact stop) against its closed form;
// - a box of stock over the cube roughed once removes the analytic slab; the same roughing again cuts nothing;
// - a pocket with 3 mm inner corner radii after a 10 mm end mill: the rest operation with a 3 mm ball cuts a small
//   fraction of a full finish's length and leaves, wherever the full finish gets the part within the threshold,
//   no more than the threshold either; nothing is ever cut below the design;
// - a stock scanned as a noisy cloud: roughing planned on it cuts less air than roughing planned on its bounding
//   box;
// - a re-scan with a bump: inspected, and a rest job on the scan cuts only there.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "pocket_part.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/job/run_job.hpp"
#include "rosmill/scan/inspection.hpp"
#include "rosmill/stock/in_process_stock.hpp"
#include "rosmill/scan/mesh_distance.hpp"
#include "rosmill/testing/synthetic_scan.hpp"
#include "rosmill/toolpath/toolpath_stats.hpp"
#include "rosmill/verify/verify.hpp"
#include "test_stock_programs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::job;

namespace {

// A folder of its own under the test's temporary folder, emptied.
std::string scratch(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "rosmill_job_rest_" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace

TEST(MachiningTime, TrapezoidalMoveHasTheClosedFormTime) {
  const Vec3 accel(508, 508, 508);  // LinuxCNC's sim (axis_mm.ini), mm/s^2
  // 100 mm along X at F1000 (16.667 mm/s): cruises, so 100 / v + v / a.
  const double v = 1000.0 / 60;
  EXPECT_NEAR(move_seconds(100, Vec3(1, 0, 0), 1000, accel), 100 / v + v / 508, 1e-12);
  EXPECT_NEAR(100 / v + v / 508, 6.0328, 1e-4);
  // 0.1 mm at F1828 never reaches the feed (v^2 / a = 1.83 mm): 2 sqrt(L / a).
  EXPECT_NEAR(move_seconds(0.1, Vec3(1, 0, 0), 1828, accel), 2 * std::sqrt(0.1 / 508), 1e-12);
  // Along the XY diagonal each axis carries 1/sqrt(2) of the path's acceleration: the path gets 508 sqrt(2).
  const Vec3 diagonal = Vec3(1, 1, 0).normalized();
  EXPECT_NEAR(move_seconds(100, diagonal, 1000, accel), 100 / v + v / (508 * std::sqrt(2.0)), 1e-12);
  // The slowest axis limits a move that uses it.
  EXPECT_NEAR(move_seconds(100, Vec3(0, 0, 1), 1000, Vec3(508, 508, 100)), 100 / v + v / 100, 1e-12);
  // No acceleration given: the time at the feed alone, as before.
  EXPECT_NEAR(move_seconds(100, Vec3(1, 0, 0), 1000, Vec3::Zero()), 6.0, 1e-12);
  // The machine file carries the sim's accelerations.
  const gcode::MachineLimits m = gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine.yaml");
  EXPECT_EQ(m.max_acceleration, accel);
}

// A box of stock 5 mm over the cube (the cube's own footprint): one roughing pass at allowance 0 takes exactly the
// 60 x 60 x 5 slab; a second identical pass finds nothing above the cube and cuts nothing.
TEST(StockAwareRough, BoxOverTheCubeRemovesTheSlabOnceAndThenNothing) {
  const std::string dir = scratch("slab");
  write_stl(dir + "/box.stl", build_mesh(stock_test::box_corners(Vec3(0, 0, 0), Vec3(60, 60, 65))));
  const std::string op = "  - {strategy: rough, tool: flat:10@1, stepover: 4, stepdown: 2.5, allowance: 0}\n";
  const std::string head = "part: primitive:cube\nresolution: 0.5\nstock: {mesh: box.stl}\noperations:\n";
  const JobSpec spec = parse_job(head + op + op, "job.yaml", dir);
  const JobReport r = run_job(spec, {});
  ASSERT_EQ(r.operations.size(), 2u);
  EXPECT_NEAR(r.stock_mm3, 60.0 * 60 * 65, 1e-6);
  // The cells fall on the cube's sides and the slab's floor is a level: the model is exact here.
  EXPECT_NEAR(r.operations[0].removed_mm3, 60.0 * 60 * 5, 60.0 * 60 * 0.01);
  EXPECT_NEAR(r.operations[0].min_left_mm, 0.0, 1e-3);
  EXPECT_NEAR(r.operations[0].max_left_mm, 0.0, 1e-3);
  // The levels start at the stock's top: none cuts air above it (65 - 2.5 and the cube's top at 60).
  EXPECT_LT(r.operations[0].air_cut_share, 0.1);
  EXPECT_EQ(r.operations[1].removed_mm3, 0.0);
  EXPECT_EQ(r.operations[1].cutting_mm - r.operations[1].air_feed_mm, 0.0) << "no feed move cuts material";
  EXPECT_EQ(r.operations[1].cutting_mm, 0.0) << "nothing is left above the cube: no level, no move";
  EXPECT_GE(r.min_left_mm, -0.001);
  std::filesystem::remove_all(dir);
}

namespace {

// The pocket job: a 10 mm end mill roughs the pocket and follows its walls (the walls' corners of radius 3 mm stay
// as the 5 mm radius left them), then `last` with the 3 mm ball. The stock is the block itself.
struct PocketRun {
  JobReport report;
  std::vector<float> left;  // material over the design per cell after the job (NaN: no material)
};

PocketRun run_pocket(const std::string& dir, const std::string& last) {
  const std::string jobs = "part: pocket.stl\nresolution: 0.5\nstock: {mesh: block.stl}\noperations:\n"
                           "  - {name: rough, strategy: rough, tool: flat:10@1, stepover: 4, stepdown: 2, allowance: 0}\n"
                           "  - {name: walls, strategy: waterline, tool: flat:10@1, stepdown: 2}\n" + last;
  const JobSpec spec = parse_job(jobs, "pocket.yaml", dir);
  const Mesh part = read_stl(dir + "/pocket.stl");
  PocketRun run;
  JobOptions options;
  options.operation_done = [&](const job::OperationView& v) { run.left = v.stock.material_above(part); };
  run.report = run_job(spec, options);
  return run;
}

}  // namespace

TEST(RestMachining, PocketCornersAfterATenMillimetreEndMill) {
  const std::string dir = scratch("pocket");
  write_stl(dir + "/pocket.stl", build_mesh(pocket_test::pocket_corners()));
  write_stl(dir + "/block.stl", build_mesh(stock_test::box_corners(Vec3(0, 0, 0), Vec3(50, 40, 20))));
  const std::string ball = "tool: ball:3@3, stepover: 0.5";
  const PocketRun rest = run_pocket(dir, "  - {name: rest, strategy: raster, " + ball + ", rest: true}\n");
  const PocketRun full = run_pocket(dir, "  - {name: finish, strategy: raster, " + ball + "}\n");
  ASSERT_EQ(rest.report.operations.size(), 3u);
  ASSERT_EQ(full.report.operations.size(), 3u);
  const OperationReport& r = rest.report.operations[2];
  const OperationReport& f = full.report.operations[2];
  std::printf("rest: %zu rest cells, cutting %.0f mm of the full finish's %.0f mm (%.1f %%), removed %.1f of %.1f mm3"
              ", time %.0f s of %.0f s\n", r.rest_cells, r.cutting_mm, f.cutting_mm, 100 * r.cutting_mm / f.cutting_mm,
              r.removed_mm3, f.removed_mm3, r.time_s, f.time_s);
  // The rest material is in the four corners: (5^2 - 3^2)(1 - pi/4) mm^2 each seen from above, 0.5 mm cells.
  EXPECT_GT(r.rest_cells, 4u);
  EXPECT_LT(r.rest_cells, 4 * 60u);
  EXPECT_LT(r.cutting_mm, 0.15 * f.cutting_mm);
  // The rest takes nearly all the full finish takes (the rest is what it leaves below the threshold).
  EXPECT_GT(r.removed_mm3, 0.9 * f.removed_mm3);
  // Wherever the full finish with the 3 mm ball gets the part within the threshold, the rest operation does too.
  ASSERT_EQ(rest.left.size(), full.left.size());
  size_t compared = 0;
  for (size_t c = 0; c < rest.left.size(); ++c) {
    if (std::isnan(full.left[c]) || full.left[c] > 0.1) continue;
    ++compared;
    ASSERT_LE(rest.left[c], 0.1 + 1e-3) << "cell " << c << " full finish leaves " << full.left[c];
  }
  EXPECT_GT(compared, rest.left.size() / 2);
  for (const JobReport* j : {&rest.report, &full.report}) EXPECT_GE(j->min_left_mm, -0.001);
  std::filesystem::remove_all(dir);
}

// The stock model and the verifier agree on the material left after a job of the stock-aware planners
// (stock-aware roughing, a waterline and a rest raster, three tools, on the pocket; the stock a box the part's
// size), cell for cell on the same grid within a thousandth of a millimetre. The stock removes each operation
// into its dexels and envelopes and is viewed after the last; the verifier sweeps the whole job's moves once over
// a fresh height field. Both sweep with the same kernel (stock::simulate): what this checks is the stock's
// bookkeeping across operations, not the sweep itself (test_stock_* and test_verify_* check that).
TEST(StockAndVerifier, AgreeOnTheMaterialLeftByAStockAwareJob) {
  const std::string dir = scratch("agree");
  write_stl(dir + "/pocket.stl", build_mesh(pocket_test::pocket_corners()));
  const std::string text = "part: pocket.stl\nresolution: 0.5\nstock: {box: {margin: 0}}\noperations:\n"
                           "  - {name: rough, strategy: rough, tool: flat:10@1, stepover: 4, stepdown: 2, allowance: 0}\n"
                           "  - {name: walls, strategy: waterline, tool: flat:10@1, stepdown: 2}\n"
                           "  - {name: rest, strategy: raster, tool: ball:3@3, stepover: 0.5, rest: true}\n";
  const JobSpec spec = parse_job(text, "agree.yaml", dir);
  const Mesh part = read_stl(dir + "/pocket.stl");
  std::vector<Toolpath> moves;  // every operation's toolpaths, in order (one setup, +Z)
  std::vector<float> left;
  JobOptions options;
  options.operation_done = [&](const job::OperationView& v) {
    moves.insert(moves.end(), v.toolpaths.begin(), v.toolpaths.end());
    left = v.stock.material_above(part);
  };
  const JobReport report = run_job(spec, options);
  ASSERT_EQ(report.operations.size(), 3u);
  verify::VerifyOptions vo;
  vo.resolution = 0.5;
  verify::StockSpec box;
  box.kind = verify::StockSpec::Kind::Box;
  box.box = part.bbox;
  const verify::VerifyResult v = verify::verify_program(part, stock::program_from_job(moves), box, vo);
  ASSERT_EQ(left.size(), v.grid.deviation.size());
  size_t compared = 0, cut = 0;
  double worst = 0;
  for (size_t c = 0; c < left.size(); ++c) {
    if (std::isnan(left[c])) continue;
    worst = std::max(worst, std::abs(double(left[c]) - v.grid.deviation[c]));
    ++compared;
    cut += v.grid.cut[c];
  }
  std::printf("stock and verifier after rough, waterline and rest: %zu cells compared (%zu cut), largest "
              "difference %.2e mm; the verifier's deepest gouge %.4f mm, the stock's least material left %.4f mm\n",
              compared, cut, worst, v.report.max_gouge_mm, report.min_left_mm);
  EXPECT_GT(compared, left.size() * 9 / 10);
  EXPECT_GT(cut, compared / 4);
  EXPECT_LT(worst, 1e-3);
  EXPECT_FALSE(v.report.gouged);
  EXPECT_EQ(report.gouge_mm, 0.0);
  std::filesystem::remove_all(dir);
}

TEST(RestMachining, FieldsAreChecked) {
  auto error_of = [](const std::string& ops) {
    try {
      parse_job("part: primitive:cube\noperations:\n" + ops, "job.yaml", ROSMILL_SOURCE_DIR);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string rough = "  - {strategy: rough, tool: flat:10@1}\n";
  EXPECT_EQ(error_of(rough + "  - {strategy: raster, tool: ball:3@3, rest: true, rest_threshold: 0.05}\n"), "");
  EXPECT_NE(error_of("  - {strategy: raster, tool: ball:3@3, rest: true}\n").find("job.yaml:3 operations[0].rest: the "
                                                                                  "first operation on a box stock"),
            std::string::npos);
  EXPECT_NE(error_of(rough + "  - {strategy: raster, tool: ball:3@3, rest: maybe}\n")
                .find("rest: expected true or false"),
            std::string::npos);
  EXPECT_NE(error_of(rough + "  - {strategy: raster, tool: ball:3@3, rest_threshold: 0.2}\n").find("only a rest"),
            std::string::npos);
  EXPECT_NE(error_of(rough + "  - {strategy: raster, tool: ball:3@3, rest: true, rest_threshold: -1}\n")
                .find("rest_threshold: must lie in"),
            std::string::npos);
}

namespace {

// The top of a dome 12 % larger than the part's (r 56), as a scanner sees it from above: points every 1 mm with
// 0.2 mm of noise, written as an ASCII PCD in millimetres.
void write_scan(const std::string& path) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.2);
  std::vector<Vec3> points;
  const double r = 56;
  for (double x = -r; x <= r; x += 1)
    for (double y = -r; y <= r; y += 1) {
      const double h2 = r * r - x * x - y * y;
      if (h2 < 0) continue;
      points.emplace_back(x, y, std::sqrt(h2) + noise(random));
    }
  std::ofstream out(path);
  out << "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " << points.size()
      << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points.size() << "\nDATA ascii\n";
  for (const Vec3& p : points) out << p.x() << " " << p.y() << " " << p.z() << "\n";
}

}  // namespace

TEST(StockAwareRough, ScannedStockCutsLessAirThanItsBoundingBox) {
  const std::string dir = scratch("scan");
  write_scan(dir + "/scan.pcd");
  const std::string op =
      "operations:\n  - {strategy: rough, tool: flat:10@1, stepover: 4, stepdown: 3, allowance: 0.5}\n";
  const JobSpec spec =
      parse_job("part: primitive:dome\nstock: {cloud: scan.pcd, units: mm, table_z: 0}\n" + op, "scan.yaml", dir);
  const JobReport scan = run_job(spec, {});
  // The same scanned stock roughed as if it were its bounding box (the dome's bounds grown by 5 mm): planning that
  // does not know the stock.
  JobOptions blind;
  blind.plan_on_stock = false;
  const JobReport box = run_job(spec, blind);
  std::printf("roughing the dome from the scanned stock: air-cutting share %.3f planned on the scan, %.3f planned on "
              "its bounding box\n", scan.operations[0].air_cut_share, box.operations[0].air_cut_share);
  EXPECT_NEAR(scan.stock_mm3, box.stock_mm3, 1e-6);
  EXPECT_LT(scan.operations[0].air_cut_share, 0.5 * box.operations[0].air_cut_share);
  EXPECT_LT(scan.operations[0].time_s, box.operations[0].time_s);
  // Both take the same material down to the allowance: the same volume within a few cells' worth.
  EXPECT_NEAR(scan.removed_mm3, box.removed_mm3, 0.02 * box.removed_mm3);
  EXPECT_GE(scan.min_left_mm, -0.001);
  EXPECT_GE(box.min_left_mm, -0.001);
  std::filesystem::remove_all(dir);
}

// The example job's pocket and casting (config/jobs/data) are the builder's: written here beside the test's files
// (where they were copied from) and compared with the shipped ones.
TEST(RestMachining, ExamplePocketIsTheTestPocket) {
  const std::string data = std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/data/";
  const std::vector<std::pair<std::string, Mesh>> built = {
      {"pocket.stl", build_mesh(pocket_test::pocket_corners())},
      {"pocket_casting.stl", build_mesh(stock_test::box_corners(Vec3(-2, -2, 0), Vec3(52, 42, 23)))}};
  for (const auto& [name, mesh] : built) {
    write_stl(::testing::TempDir() + "rosmill_built_" + name, mesh);
    const Mesh shipped = read_stl(data + name);
    ASSERT_EQ(shipped.faces.size(), mesh.faces.size()) << name;
    ASSERT_EQ(shipped.vertices.size(), mesh.vertices.size()) << name;
    EXPECT_LT((shipped.bbox.min - mesh.bbox.min).norm() + (shipped.bbox.max - mesh.bbox.max).norm(), 1e-4) << name;
    for (size_t v = 0; v < mesh.vertices.size(); ++v)
      ASSERT_LT((shipped.vertices[v] - mesh.vertices[v]).norm(), 1e-4) << name << " vertex " << v;
  }
}

// The machined dome scanned again from above with 1 mm of material left in a cosine cap of radius 6 mm: the
// inspection reports that bump's height and place, its scan in the workpiece frame becomes the stock, and a rest
// job on it (rest from the first operation) cuts only there: a few percent of a full finish's cutting length, the
// bump's volume removed, nothing below the design.
TEST(RestMachining, ARescanWithABumpIsInspectedAndMachinedOnlyThere) {
  const std::string dir = scratch("rescan");
  const Mesh dome = make_primitive("dome");
  // A scanner returns no points at grazing angles: the dome's flank steeper than 75 degrees is not seen (its
  // cells hold no scanned stock; a height field could not describe them within a cell anyway).
  std::vector<Vec3> points;
  for (const Vec3& p : synthetic::synthetic_scan(dome, {Vec3(0, 0, 1000)}, 400000, 0.005, 17).points)
    if (p.z() > std::cos(75 * M_PI / 180) * p.norm()) points.push_back(p);
  const scan::MeshDistance distance(dome);
  const Vec3 centre_xy(12, 8, 0);
  Vec3 at(0, 0, -1e9);
  for (const Vec3& p : points)
    if (std::hypot(p.x() - centre_xy.x(), p.y() - centre_xy.y()) < 0.3 && p.z() > at.z()) at = p;
  constexpr double kHeight = 1.0, kRadius = 6.0;
  for (Vec3& p : points) {
    const double r = (p - at).norm();
    if (r < kRadius) p += dome.normals[distance.query(p).face] * kHeight * 0.5 * (1 + std::cos(M_PI * r / kRadius));
  }
  scan::InspectionOptions io;
  io.tolerance = 0.05;
  const scan::InspectionReport inspection = scan::inspect_registered(dome, points, io);
  EXPECT_NEAR(inspection.largest_excess.distance, kHeight, 0.03);
  const Vec3 bump_top = at + dome.normals[distance.query(at).face] * kHeight;
  EXPECT_LT((inspection.largest_excess.place - bump_top).norm(), 0.5);
  PointCloud stock;
  stock.points = inspection.points;
  write_cloud(dir + "/rescan.pcd", stock, Units::Millimetre);

  const std::string head = "part: primitive:dome\nresolution: 0.5\nstock: {cloud: rescan.pcd, units: mm, table_z: 0}\n"
                           "operations:\n  - {name: last, strategy: raster, tool: ball:6@2, stepover: 0.5";
  // The material over the design per cell before the rest job (the stock as the job reads it) and after.
  CloudReadOptions in_mm;
  in_mm.units = Units::Millimetre;
  const std::vector<float> before = stock::InProcessStock::from_cloud(read_cloud(dir + "/rescan.pcd", in_mm), 0, 0.5)
                                        .material_above(dome);
  std::vector<float> after;
  JobOptions options;
  options.operation_done = [&](const job::OperationView& v) { after = v.stock.material_above(dome); };
  const JobReport rest = run_job(parse_job(head + ", rest: true, rest_threshold: 0.2}\n", "rest.yaml", dir), options);
  const JobReport full = run_job(parse_job(head + "}\n", "full.yaml", dir), {});
  const OperationReport& r = rest.operations.at(0);
  const OperationReport& f = full.operations.at(0);
  std::printf("rescan rest: %zu rest cells, cutting %.0f mm of the full finish's %.0f mm, removed %.1f mm3 (bump "
              "%.1f mm3), left %.3f..%.3f mm\n", r.rest_cells, r.cutting_mm, f.cutting_mm, r.removed_mm3,
              M_PI * kRadius * kRadius * kHeight * (0.5 - 2 / (M_PI * M_PI)), rest.min_left_mm, rest.max_left_mm);
  // The cap covers pi 6^2 = 113 mm^2 from above, 452 cells of 0.5 mm; above 0.2 mm of it stands a disc of ~4.7 mm.
  EXPECT_GT(r.rest_cells, 100u);
  EXPECT_LT(r.rest_cells, 600u);
  EXPECT_LT(r.cutting_mm, 0.1 * f.cutting_mm);
  const double bump_volume = M_PI * kRadius * kRadius * kHeight * (0.5 - 2 / (M_PI * M_PI));
  EXPECT_GT(r.removed_mm3, 0.5 * bump_volume);
  EXPECT_LT(r.removed_mm3, 1.3 * bump_volume);
  // Where the rest job cut, never below the design; around the bump, no more than the threshold is left.
  ASSERT_EQ(before.size(), after.size());
  const stock::GridSpec g = stock::InProcessStock::from_cloud(read_cloud(dir + "/rescan.pcd", in_mm), 0, 0.5).grid();
  size_t cut = 0, near_bump = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const size_t c = g.index(i, j);
      if (std::isnan(before[c]) || std::isnan(after[c])) continue;
      if (after[c] < before[c] - 1e-4) {
        ++cut;
        EXPECT_GE(after[c], -0.01) << "cell " << i << ", " << j << " cut below the design";
        EXPECT_LT(std::hypot(g.cx(i) - at.x(), g.cy(j) - at.y()), kRadius + 3.0 + 0.5)
            << "cell " << i << ", " << j << " cut away from the bump";
      }
      if (std::hypot(g.cx(i) - at.x(), g.cy(j) - at.y()) < kRadius) {
        ++near_bump;
        EXPECT_LE(after[c], 0.2 + 0.02) << "cell " << i << ", " << j << " keeps rest material";
      }
    }
  EXPECT_GT(cut, 100u);
  EXPECT_GT(near_bump, 300u);
  std::filesystem::remove_all(dir);
}
