// Five-axis finishing's tool-axis planning beside FCL, the Flexible Collision Library (Debian's libfcl-dev), on the
// same tool and mesh. rosmill: cutter locations per second, each with the ball's exact contact along its axis, the
// axis turned to clear where the rule's is blocked, and the flutes, shank and holder swept clear
// (plan/ball_contact.hpp), best of `runs`. FCL: collision queries per second of the tool's ball, flutes, shank and
// holder (its sphere and cylinders against an OBBRSS tree of the mesh) at those cutter locations, one thread, after the
// tree is built. FCL's answers are also a check that shares no code with the planner: the tool shrunk by 0.01 mm at
// every cutter location (the ball touches the part there, grown by the allowance) meets nothing, counted per part.
// Usage: bench_five_axis [threads] [runs]
#include <fcl/fcl.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "../test/core/multi_axis_parts.hpp"
#include "cpu_time.hpp"
#include "rosmill/error.hpp"
#include "rosmill/heap_reuse.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/plan/five_axis_finish.hpp"
#include "rosmill/seconds_since.hpp"

using namespace rosmill::core;

namespace {

constexpr double kShrink = 0.01;  // mm the tool is made thinner for FCL: it touches the part at each location

struct Part {
  std::string name;
  Mesh mesh;
  PlanParams params;
};

PlanParams ball_params() {
  PlanParams p;
  p.tool.id = 5;
  p.tool.cutter = Cutter::ball(6);
  p.tool.feed = 1000;
  p.tool.plunge_feed = 300;
  p.tool.stepover = 1.0;
  p.tolerance = 0.002;
  return p;
}

// The dome between walls of the five-axis tests (test/core/multi_axis_parts.hpp).
Part dome_between_walls() {
  Part part{"dome between walls", test_parts::dome_between_walls(), ball_params()};
  part.params.stepover = 1;
  part.params.tool.stick_out = 26;
  part.params.tool.holder_diameter = 20;
  part.params.tool_axis.cone_deg = 45;
  return part;
}

// The block with features on five sides (test/data/parts/five_sided.stl), finished from above.
Part five_sided() {
  Part part{"five-sided block", read_stl(std::string(ROSMILL_SOURCE_DIR) + "/test/data/parts/five_sided.stl"),
            ball_params()};
  part.params.tolerance = 0.001;
  return part;
}

// The tool at one cutter location as FCL's primitives, each along the axis from the tip.
class FclTool {
 public:
  explicit FclTool(const Tool& tool, double allowance) {
    const double R = tool.cutter.radius() + allowance - kShrink, flutes = tool.cutter.flute_length;
    const double stick_out = tool.stick_out_mm(), holder = 0.5 * tool.holder_mm();
    const double centre = tool.cutter.radius();
    add(std::make_shared<fcl::Sphered>(R), centre);
    add_cylinder(R, centre, flutes);
    add_cylinder(0.5 * tool.cutter.shank_diameter + allowance - kShrink, flutes, stick_out);
    add_cylinder(holder + allowance - kShrink, stick_out, stick_out + 2 * holder);  // a collet nut
  }
  // Moves every part to the location (tip, unit axis).
  void place(const Vec3& tip, const Vec3& axis) {
    const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), axis);
    for (size_t k = 0; k < parts_.size(); ++k) {
      parts_[k]->setTranslation(tip + centre_[k] * axis);
      parts_[k]->setQuatRotation(turn);
      parts_[k]->computeAABB();
    }
  }
  const std::vector<std::unique_ptr<fcl::CollisionObjectd>>& parts() const { return parts_; }

 private:
  void add(std::shared_ptr<fcl::CollisionGeometryd> shape, double centre) {
    parts_.push_back(std::make_unique<fcl::CollisionObjectd>(std::move(shape)));
    centre_.push_back(centre);
  }
  void add_cylinder(double radius, double from, double to) {
    if (to - from > 1e-9 && radius > 0) add(std::make_shared<fcl::Cylinderd>(radius, to - from), 0.5 * (from + to));
  }
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> parts_;
  std::vector<double> centre_;  // each part's centre, mm up the axis from the tip
};

std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> fcl_mesh(const Mesh& mesh) {
  std::vector<fcl::Vector3d> points(mesh.vertices.begin(), mesh.vertices.end());
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.face_count());
  for (const Mesh::Face& f : mesh.faces) triangles.emplace_back(f[0], f[1], f[2]);
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  model->beginModel();
  model->addSubModel(points, triangles);
  model->endModel();
  return model;
}

struct Location {
  Vec3 tip, axis;
};

// The cutting moves' ends with their axes: the cutter locations (approach and retract along the axis included).
std::vector<Location> cutter_locations(const Job& job) {
  std::vector<Location> out;
  for (const Toolpath& tp : job)
    for (const ToolpathPass& pass : tp.passes)
      for (size_t k = 0; k < pass.moves.size() && k < pass.axes.size(); ++k)
        if (pass.moves[k].type == MoveType::Feed) out.push_back({pass.moves[k].to, pass.axes[k]});
  return out;
}

void run(const Part& part, int runs) {
  double best = 1e300, cpu = 0;
  Job job;
  PlanReport report;
  for (int r = 0; r < runs; ++r) {
    const double cpu0 = cpu_seconds_used();
    const auto t0 = std::chrono::steady_clock::now();
    report = PlanReport{};
    job = five_axis_finish(part.mesh, part.params, {}, &report);
    const double s = seconds_since(t0);
    if (s < best) best = s, cpu = cpu_seconds_used() - cpu0;
  }
  const std::vector<Location> cls = cutter_locations(job);

  const auto t1 = std::chrono::steady_clock::now();
  const fcl::CollisionObjectd mesh_object(fcl_mesh(part.mesh));
  const double tree_s = seconds_since(t1);
  FclTool tool(part.params.tool, part.params.allowance);
  const fcl::CollisionRequestd request;
  // The locations at which some part of the tool meets the mesh, `down` mm lower than planned.
  const auto meeting = [&](double down) {
    size_t count = 0;
    for (const Location& cl : cls) {
      tool.place(cl.tip - Vec3(0, 0, down), cl.axis);
      bool met = false;
      for (const auto& piece : tool.parts()) {
        fcl::CollisionResultd result;
        fcl::collide(piece.get(), &mesh_object, request, result);
        met = met || result.isCollision();
      }
      count += met;
    }
    return count;
  };
  const auto t2 = std::chrono::steady_clock::now();
  const size_t met = meeting(0);
  const double fcl_s = seconds_since(t2);
  const double queries = double(tool.parts().size() * cls.size());
  // The check sees a gouge: 0.05 mm lower, the ball goes into every face it touches from above.
  const size_t met_lower = meeting(0.05);
  std::printf("%-20s %7zu %7zu %8.3f %7.2f %10.0f %8.3f %7.3f %10.0f %10.0f %7zu\n", part.name.c_str(),
              part.mesh.face_count(), cls.size(), best, cpu, cls.size() / best, tree_s, fcl_s, queries / fcl_s,
              cls.size() / fcl_s, met);
  std::printf(
      "%-20s axes turned to clear %zu, points no axis in the cone reaches %zu; FCL: %zu of the %zu "
      "locations meet the part 0.05 mm lower\n",
      "", size_t(report.axes_turned_to_clear), size_t(report.unreachable_points), met_lower, cls.size());
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
  const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::printf("threads %d (FCL: 1); ball 6; rosmill best of %d runs; FCL's tool %.2f mm thinner\n", threads, runs,
              kShrink);
  std::printf("%-20s %7s %7s %8s %7s %10s %8s %7s %10s %10s %7s\n", "part", "tris", "CLs", "plan s", "cpu s", "CL/s",
              "tree s", "FCL s", "FCL q/s", "FCL CL/s", "meets");
  try {
    run(dome_between_walls(), runs);
    run(five_sided(), runs);
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_five_axis: %s\n", e.what());
    return 1;
  }
  return 0;
}
