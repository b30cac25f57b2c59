// The account of the whole surface after a job (job/surface_account.hpp): on parts made for the trial with features on
// every side, every face the job was to finish is within its limit or listed above it with the reason, and the
// report's figures agree with an independent sweep of the written programs over the design's surface (LinuxCNC's
// rs274 reads the programs; testing/program_sweep.hpp shares no code with the stock model).
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "job_test_options.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/job/run_job.hpp"
#include "rosmill/testing/program_sweep.hpp"
#include "rosmill/testing/sanitized.hpp"

using namespace rosmill::core;
using namespace rosmill::core::job;

namespace {

std::string part_file(const std::string& name) { return std::string(ROSMILL_TEST_DATA) + "/parts/" + name; }

// The written programs as the independent sweep reads them: each setup's, through its frame, with its tools.
std::vector<SweptProgram> written_programs(const JobReport& r) {
  std::vector<SweptProgram> out;
  for (const SetupReport& s : r.setups) {
    if (s.program.empty()) continue;
    SweptProgram p;
    p.path = s.program;
    p.workpiece_to_program = s.frame.placement.pose;
    for (const size_t k : s.operations) {
      const Tool& t = r.operations[k].tool_used;
      const double corner = t.cutter.type == CutterType::BallEnd ? t.cutter.radius() : t.cutter.corner_radius;
      p.tools[t.id] = {t.cutter.type, t.cutter.radius(), corner};
    }
    out.push_back(p);
  }
  return out;
}

// Per face of the account, what the sweep found on its facets: the most left, and the area above the face's limit.
struct SweptFace {
  double area = 0, above = 0, most = -INFINITY, least = INFINITY;
};

std::vector<SweptFace> swept_faces(const SurfaceAccount& a, const SweepCheck& check, size_t facets) {
  std::vector<int> face_of(facets, -1);
  for (const FaceLeft& f : a.faces)
    for (const uint32_t facet : f.facets) face_of[facet] = int(f.face);
  std::vector<SweptFace> out(a.faces.size());
  for (const SweepSample& s : check.samples) {
    const int f = face_of[s.facet];
    if (f < 0) continue;
    SweptFace& face = out[size_t(f)];
    face.area += s.area;
    face.most = std::max(face.most, s.left);
    face.least = std::min(face.least, s.left);
    if (s.left > a.faces[size_t(f)].limit + 1e-6) face.above += s.area;
  }
  return out;
}

}  // namespace

// Known answers on a 40 x 30 x 10 mm block from a box 3 mm larger sideways and on top, in one +Z setup: roughed
// only, no face is to be finished, and its top keeps the 0.5 mm allowance exactly (the level at its height plus the
// allowance); finished by a flat end mill's waterline and raster, its top and its four walls are within the limit
// (0.01 mm) and the job passes; by the raster alone, the walls along its lines keep up to its stepover's share of
// the margin ("strategy left it") and the job fails.
TEST(JobSurface, ABlockRoughedFinishedAndHalfFinished) {
  const std::string dir = job_test::scratch("job_surface_block");
  write_stl(dir + "/block.stl", build_mesh(box_corners(Box3::between(Vec3(0, 0, 0), Vec3(40, 30, 10)))));
  const std::string head = "part: block.stl\nstock: {box: {margin: 3}}\noperations:\n"
                           "  - {name: rough, strategy: rough, tool: 1, stepover: 4, stepdown: 4, allowance: 0.5}\n";
  const auto run = [&](const std::string& more) {
    return run_job(parse_job(head + more, "block.yaml", dir), job_test::options());
  };
  const JobReport rough = run("");
  EXPECT_EQ(rough.surface.asked_faces, 0u);
  EXPECT_FALSE(rough.unfinished());
  for (const FaceLeft& f : rough.surface.faces)
    if (f.normal.z() > 0.999) {
      EXPECT_EQ(f.verdict, FaceVerdict::NotAsked);
      EXPECT_NEAR(f.min_left_mm, 0.5, 1e-3);
      EXPECT_NEAR(f.max_left_mm, 0.5, 1e-3);
    }
  const JobReport finished = run("  - {name: walls, strategy: waterline, tool: 5, stepdown: 2}\n"
                                 "  - {name: top, strategy: raster, tool: 5, stepover: 2}\n");
  EXPECT_EQ(finished.surface.asked_faces, 5u);  // the top and the walls: the bottom stands on the table
  EXPECT_EQ(finished.surface.unfinished_faces, 0u) << finished.surface.max_left_mm;
  EXPECT_LE(finished.max_left_mm, 0.01);
  EXPECT_GE(finished.min_left_mm, -0.001);
  const JobReport half = run("  - {name: top, strategy: raster, tool: 5, stepover: 2}\n");
  EXPECT_TRUE(half.unfinished());
  size_t along = 0;
  for (const FaceLeft& f : half.surface.faces) {
    if (f.verdict != FaceVerdict::Above) continue;
    EXPECT_EQ(f.main_reason(), LeftReason::StrategyLeftIt) << f.face;
    EXPECT_LE(f.max_left_mm, 3.5 + 1e-6) << f.face;  // no more than the margin and the allowance
    along += std::abs(f.normal.y()) > 0.999;
  }
  EXPECT_EQ(along, 2u);  // the walls along the raster's lines (angle 0: along x)
  std::filesystem::remove_all(dir);
}

// A 70 x 50 x 35 mm block with a pocket and an island on top, a step, a slot 20 x 8 mm in -X (narrower than two
// diameters of the 6 mm end mill), two blind holes in +Y and a groove in +X exactly the end mill's width: `setups:
// auto` in a vise, roughing, waterline and raster. Its sharp inner corners keep the end mill out (rest
// material for a smaller one: "tool does not fit"), and the raster along the pocket's long walls leaves the foot
// the waterline did not reach ("strategy left it"). The job says so face by face, and fails (exit status 4 from the
// command line) unless it accepts that; what it says agrees with the written programs swept over the surface.
TEST(JobSurface, FiveSidedBlockAgreesWithTheWrittenProgramsSweptOverItsSurface) {
  const std::string dir = job_test::scratch("job_surface_five");
  const JobSpec spec = parse_job(
      "part: " + part_file("five_sided.stl") +
          "\nstock: {box: {margin: 3}}\nsetups: auto\nheld_face: -Z\n"
          "fixture: {vise: {jaw_width: 100, jaw_height: 25, opening: 120, grip: 4, clamp: y}}\n"
          "operations:\n"
          "  - {name: rough, strategy: rough, tool: 1, stepover: 4, stepdown: 4, allowance: 0.3}\n"
          "  - {name: walls, strategy: waterline, tool: 5, stepdown: 0.5}\n"
          "  - {name: floors, strategy: raster, tool: 5, stepover: 2}\n",
      "five_sided.yaml", dir);
  const JobOptions o = job_test::options(dir);
  const JobReport r = run_job(spec, o);
  ASSERT_TRUE(r.surface.done);
  ASSERT_EQ(r.setups.size(), 5u);
  const Mesh part = read_stl(part_file("five_sided.stl"));
  const SurfaceAccount& a = r.surface;
  // The report's least and most are over the faces it was to finish, not the last operation's view.
  EXPECT_NEAR(r.max_left_mm, 8.0, 0.01);
  EXPECT_EQ(r.max_left_mm, a.max_left_mm);
  EXPECT_GT(a.unfinished_faces, 0u);
  EXPECT_TRUE(r.unfinished());
  std::map<std::string, double> by_reason;
  for (const FaceLeft& f : a.faces) {
    if (f.verdict == FaceVerdict::NotAsked) {
      EXPECT_LT(f.normal.z(), -0.999) << "face " << f.face << ": only the held bottom is not asked";
      continue;
    }
    if (f.verdict == FaceVerdict::Within) {
      EXPECT_LE(f.max_left_mm, f.limit) << "face " << f.face;
    }
    if (f.verdict == FaceVerdict::Above) {
      EXPECT_GT(f.max_left_mm, f.limit) << "face " << f.face;
      EXPECT_GT(f.above_area, 0.0) << "face " << f.face;
      by_reason[reason_name(f.main_reason())] += f.above_area;
    }
  }
  // The slot's floor (normal -X at x = 8): its corners keep the end mill out, up to the slot's 8 mm depth.
  bool slot_floor = false;
  for (const FaceLeft& f : a.faces)
    if (f.normal.x() < -0.999 && std::abs(f.centroid.x() - 8.0) < 1e-6) {
      slot_floor = true;
      EXPECT_EQ(f.verdict, FaceVerdict::Above);
      EXPECT_EQ(f.main_reason(), LeftReason::ToolDoesNotFit);
      EXPECT_NEAR(f.max_left_mm, 8.0, 0.01);
    }
  EXPECT_TRUE(slot_floor);
  EXPECT_GT(by_reason["tool does not fit"], 0.0);
  EXPECT_GT(by_reason["strategy left it"], 0.0);

  // The written programs, read by rs274 and swept over fresh samples of the design's surface.
  // Under the sanitizers the samples lie 3 mm apart (each standing for about 9 mm2: an area above the limit is
  // found to within a few samples along its edge).
  const double spacing = rosmill::testing::kSanitized ? 3.0 : 1.0;
  const SweepCheck check = sweep_programs(part, r.stock_box, written_programs(r), spacing);
  ASSERT_GT(check.moves, 10000u);
  const std::vector<SweptFace> swept = swept_faces(a, check, part.face_count());
  double least = INFINITY, most = -INFINITY;
  for (const FaceLeft& f : a.faces) {
    const SweptFace& s = swept[f.face];
    if (f.verdict == FaceVerdict::NotAsked || s.area == 0) continue;
    least = std::min(least, s.least);
    most = std::max(most, s.most);
    // A face within its limit: no sample of the sweep holds more than the limit (with the sweep's own 0.1 um).
    if (f.verdict == FaceVerdict::Within) {
      EXPECT_LE(s.most, f.limit + 1e-4) << "face " << f.face;
    }
    // A face above it: the sweep finds material above the limit there too, over an area like the account's.
    if (f.verdict == FaceVerdict::Above) {
      EXPECT_GT(s.above, 0.0) << "face " << f.face;
      EXPECT_NEAR(s.above, f.above_area, 0.25 * f.above_area + 4.0 * spacing * spacing) << "face " << f.face;
    }
  }
  EXPECT_NEAR(most, a.max_left_mm, 0.05);
  EXPECT_NEAR(least, a.min_left_mm, 0.005);
  std::filesystem::remove_all(dir);
}
