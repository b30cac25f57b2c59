// One free-form part finished three ways (issue 42): a dome of radius 15 on a plate, from the stock the dome grown
// by 0.3 mm, with a ball of 6 at 1 mm stepover. 3-axis: one raster from +Z. 3+2: five rasters, from +Z and from
// four sides tilted 45 degrees, each planned in its turned frame and cut with its fixed tool axis. 5-axis: the
// five-axis finish, lead 10 degrees, within a cone of 40. Every way is cut into the same in-process stock and read
// by the same verifier over the whole surface (verify/multi_axis.hpp), which shares no code with the planners.
// Per way: moves, cutting length, machining time as the post writes it and LinuxCNC's planner would run it
// (gcode/cycle_time.hpp; the 3+2 rasters each in its own frame, the indexing between them not counted), the most
// and the mean material left on the dome's cap down to 75 degrees from its top, the share of that cap within the
// tolerance plus the ball's scallop on a flat (0.042 mm), the deepest gouge, the largest change of the tool axis per
// mm, and the share of the cap's cutting done near the ball's tip (its axis within 5 degrees of the surface's
// normal: zero cutting speed there). Usage: bench_three_ways
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../test/core/multi_axis_parts.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/cycle_time.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/plan/five_axis_finish.hpp"
#include "rosmill/planner/plan_request.hpp"
#include "rosmill/seconds_since.hpp"
#include "rosmill/stock/multi_axis_program.hpp"
#include "rosmill/verify/multi_axis.hpp"

using namespace rosmill::core;

namespace {

constexpr double kR = 15, kDeg = M_PI / 180;

struct Way {
  std::string name;
  Job job;             // workpiece frame, the tool axis at every move
  double seconds = 0;  // machining, estimated
  double plan_seconds = 0;
  double axis_rate = 0;  // degrees per mm
};

PlanParams ball_finish() {
  PlanParams p;
  p.tool.id = 5;
  p.tool.cutter = Cutter::ball(6);
  p.tool.cutter.flute_length = 24;
  p.tool.feed = 1000;
  p.tool.plunge_feed = 300;
  p.stepover = 1.0;
  p.tolerance = 0.002;
  p.tool_axis.cone_deg = 40;
  return p;
}

// A raster planned in the frame of a setup, turned back into the workpiece frame with its fixed tool axis.
Job raster_from(const Mesh& part, const Vec3& direction, double& estimate, const gcode::MachineLimits& mill) {
  PlanningRequest r;
  r.input.mesh = &part;
  r.input.setup = direction_setup(direction);
  r.strategy = "raster";
  r.params = ball_finish();
  Job job = plan(r);
  gcode::PostOptions post;
  estimate += gcode::estimate_cycle_time(job, post, mill.trajectory).seconds;
  const SetupFrame& s = r.input.setup;
  for (Toolpath& tp : job) {
    tp.start = s.to_workpiece_frame(tp.start);
    for (ToolpathPass& pass : tp.passes) {
      pass.axes.assign(pass.moves.size(), s.tool_axis);
      for (Move& m : pass.moves) m.to = s.to_workpiece_frame(m.to);
    }
  }
  return job;
}

double tcp_seconds(const Job& job, const gcode::MachineLimits& tcp) {
  gcode::PostOptions o = gcode::with_tool_centre_point({}, tcp, "bench");
  o.work_offset = gcode::WorkOffset{};
  gcode::ProgramChecks checks;
  checks.machine = tcp;
  checks.limits.stock_top = kR + 0.3;
  return gcode::estimate_cycle_time(gcode::prepare_program(job, o, checks).program.lines, tcp.trajectory).seconds;
}

void report(const Way& w, const Mesh& part, const Mesh& grown) {
  verify::StockSpec stock;
  stock.kind = verify::StockSpec::Kind::Mesh;
  stock.mesh = &grown;
  verify::VerifyOptions o;
  o.resolution = 0.25;
  const verify::MultiAxisVerifyResult v =
      verify::verify_multi_axis(part, stock::multi_axis_program_from_job(w.job), stock, o, 1.0);
  double cap = 0, within = 0, rest_area = 0, most = 0;
  for (size_t k = 0; k < v.samples; ++k) {
    const Vec3& q = v.surface.points[k];
    if (std::abs(q.norm() - kR) > 0.05 || q.z() < kR * std::cos(75 * kDeg)) continue;
    const double a = v.surface.weights[k];
    cap += a;
    rest_area += a * v.rest[k];
    most = std::max(most, double(v.rest[k]));
    if (v.rest[k] <= v.limit_mm) within += a;
  }
  // Cutting near the tip: each cutting move's axis against the sphere's normal under its ball.
  double near_tip = 0, on_cap = 0;
  for (const Toolpath& tp : w.job)
    for (const ToolpathPass& pass : tp.passes)
      for (size_t k = 1; k < pass.moves.size(); ++k) {
        if (pass.moves[k].type == MoveType::Rapid) continue;
        const Vec3 centre = pass.moves[k].to + 3.0 * pass.axes[k];
        if (std::abs(centre.norm() - kR - 3) > 0.05 || centre.z() < (kR + 3) * std::cos(75 * kDeg)) continue;
        const double len = (pass.moves[k].to - pass.moves[k - 1].to).norm();
        on_cap += len;
        if (std::acos(std::clamp(pass.axes[k].dot(centre.normalized()), -1.0, 1.0)) < 5 * kDeg) near_tip += len;
      }
  double feed = 0;
  size_t moves = 0;
  for (const Toolpath& tp : w.job)
    for (const ToolpathPass& pass : tp.passes)
      for (size_t k = 0; k < pass.moves.size(); ++k) {
        ++moves;
        if (pass.moves[k].type != MoveType::Rapid && k > 0) feed += (pass.moves[k].to - pass.moves[k - 1].to).norm();
      }
  std::printf("%-6s %7zu %9.0f %9.0f %8.4f %8.4f %7.1f %9.4f %9.2f %8.1f %7.2f %7.2f\n", w.name.c_str(), moves, feed,
              w.seconds, most, cap > 0 ? rest_area / cap : 0, cap > 0 ? 100 * within / cap : 0, v.max_gouge_mm,
              w.axis_rate, on_cap > 0 ? 100 * near_tip / on_cap : 0, w.plan_seconds, v.seconds);
}

}  // namespace

int main() {
  try {
    const Mesh part = test_parts::dome_on_plate(kR, 22, 4, 96, 32);
    const Mesh grown = test_parts::dome_on_plate(kR + 0.3, 22, 4, 96, 32);
    const std::string config = std::string(ROSMILL_SOURCE_DIR) + "/config/";
    const gcode::MachineLimits mill = gcode::load_machine_limits(config + "machine_xyzac.yaml");
    const gcode::MachineLimits tcp = gcode::load_machine_limits(config + "machine_xyzac_tcp.yaml");
    std::vector<Way> ways(3);
    auto t0 = std::chrono::steady_clock::now();
    ways[0].name = "3-axis";
    ways[0].job = raster_from(part, Vec3::UnitZ(), ways[0].seconds, mill);
    ways[0].plan_seconds = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    ways[1].name = "3+2";
    const double s = std::sqrt(0.5);
    for (const Vec3& d : {Vec3(0, 0, 1), Vec3(s, 0, s), Vec3(-s, 0, s), Vec3(0, s, s), Vec3(0, -s, s)})
      for (Toolpath& tp : raster_from(part, d, ways[1].seconds, mill)) ways[1].job.push_back(std::move(tp));
    ways[1].plan_seconds = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    ways[2].name = "5-axis";
    PlanReport rep;
    ways[2].job = five_axis_finish(part, ball_finish(), {}, &rep);
    ways[2].plan_seconds = seconds_since(t0);
    ways[2].axis_rate = rep.max_axis_rate_deg_per_mm;
    ways[2].seconds = tcp_seconds(ways[2].job, tcp);
    std::printf(
        "dome R %g on a plate, stock grown 0.3 mm, ball 6 at 1 mm stepover; the cap: down to 75 deg from the top\n",
        kR);
    std::printf("%-6s %7s %9s %9s %8s %8s %7s %9s %9s %8s %7s %7s\n", "way", "moves", "feed mm", "est. s", "most mm",
                "mean mm", "within%", "gouge mm", "deg/mm", "tip%", "plan s", "check s");
    for (const Way& w : ways) report(w, part, grown);
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_three_ways: %s\n", e.what());
    return 1;
  }
  return 0;
}
