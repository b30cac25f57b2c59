// cell_checker: a rostest test node that passes, or fails with the reason, on what a cell run did. It waits
// for cell_sequencer's `cell_run` (rosmill/CellRun) to end within ~time_limit s of wall time and checks it against
// the expectations given as parameters; each expectation is a test case of its own, so rostest's XML (and
// catkin_test_results) names the one that failed and why. Every program the run wrote is read again by LinuxCNC's
// own interpreter (rs274), a check that shares no code with rosmill's post.
//
// Expectations (an unset bound is not checked; lengths in mm, angles in degrees, times in s):
//   ~registered (true)   the design found in the fused scan; ~ambiguous_ok (false) an ambiguous pose accepted
//   ~max_rms_mm, ~max_translation_sigma_mm, ~max_rotation_sigma_deg           the fit and its stated uncertainty
//   ~expected_xyz ([x, y, z] m) ~expected_rpy ([r, p, y] rad) ~pose_tolerance_mm ~pose_tolerance_deg
//                                                                 where the part should be (fixed frame)
//   ~setups ([+Z, -X, ...])  the setups the job chose, in order
//   ~gouge_tolerance_mm (0.01) how far below the design the job's stock may be cut, and the verifier's sweep of
//                         the written programs may reach
//   ~every_face_finished (true)  no face the job finishes left above allowance + tolerance + scallop
//   ~max_cycle_time_s     the job's estimated machining time
//   ~programs_run (true)  every program the job wrote ran to its end on the controller, and rs274 accepts it
//   ~time_limit (600)     wall time from the checker's start to the run's end
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <ros/ros.h>

#include <Eigen/Geometry>
#include <cmath>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "rosmill/CellRun.h"
#include "rosmill/gcode/post.hpp"
#include "rosmill/gcode/rs274_check.hpp"
#include "rosmill/ros/namespaces.hpp"

namespace {

namespace msg = ::rosmill;
constexpr double kDeg = M_PI / 180;

ros::NodeHandle& private_nh() {
  static ros::NodeHandle pnh("~");
  return pnh;
}

// A bound parameter: NaN when it is not set (not checked).
double bound(const std::string& name) {
  double v = NAN;
  private_nh().param(name, v, static_cast<double>(NAN));
  return v;
}

bool flag(const std::string& name, bool fallback) {
  bool v = fallback;
  private_nh().param(name, v, fallback);
  return v;
}

// The run's last CellRun once it has ended (done or failed), or its last state when ~time_limit passes first.
class CellRunWatch {
 public:
  static CellRunWatch& get() {
    static CellRunWatch w;
    return w;
  }
  const msg::CellRun& run() const { return run_; }
  bool heard() const { return heard_; }
  bool ended() const { return run_.done || run_.failed; }
  double waited() const { return waited_; }
  double time_limit() const { return time_limit_; }

  // Why the run is not there to be checked ("" when it ended): for the failure messages of every check.
  std::string where() const {
    if (!heard_) return "no cell_run message came within " + std::to_string(time_limit_) + " s";
    std::string s = "the run " + std::string(run_.done ? "ended" : run_.failed ? "stopped" : "was still") +
                    " at step '" + run_.step + "': " + run_.message;
    if (!ended()) s += " (after " + std::to_string(time_limit_) + " s)";
    return s;
  }

 private:
  CellRunWatch() {
    time_limit_ = 600;
    private_nh().param("time_limit", time_limit_, 600.0);
    ros::NodeHandle nh;
    std::mutex m;
    bool ended = false;
    const ros::WallTime start = ros::WallTime::now();
    ros::Subscriber sub = nh.subscribe<msg::CellRun>("cell_run", 4, [&](const msg::CellRun::ConstPtr& r) {
      std::lock_guard<std::mutex> lock(m);
      run_ = *r;
      heard_ = true;
      ended = r->done || r->failed;
    });
    while (ros::ok() && (ros::WallTime::now() - start).toSec() < time_limit_) {
      {
        std::lock_guard<std::mutex> lock(m);
        if (ended) break;
      }
      ros::WallDuration(0.05).sleep();
    }
    sub.shutdown();
    waited_ = (ros::WallTime::now() - start).toSec();
  }
  msg::CellRun run_;
  bool heard_ = false;
  double waited_ = 0, time_limit_ = 600;
};

const msg::CellRun& cell_run() { return CellRunWatch::get().run(); }
std::string where() { return CellRunWatch::get().where(); }

TEST(Cell, RanToItsEndWithinTheTimeLimit) {
  const CellRunWatch& w = CellRunWatch::get();
  EXPECT_TRUE(w.heard() && w.run().done) << where();
  EXPECT_LE(w.waited(), w.time_limit());
}

TEST(Registration, FoundThePart) {
  if (!flag("registered", true)) GTEST_SKIP() << "~registered is false";
  EXPECT_TRUE(cell_run().registered) << where();
}

// Whether the run came as far as asking for a registration.
bool registration_tried(const msg::CellRun& r) {
  return CellRunWatch::get().heard() && r.step != "views" && r.step != "fusion";
}

TEST(Registration, NotAmbiguous) {
  if (flag("ambiguous_ok", false)) GTEST_SKIP() << "~ambiguous_ok is true";
  ASSERT_TRUE(registration_tried(cell_run())) << "no registration to check: " << where();
  EXPECT_FALSE(cell_run().ambiguous) << "the pose is ambiguous: " << cell_run().ambiguity;
}

void expect_at_most(double value, const std::string& bound_name, const std::string& what) {
  const double b = bound(bound_name);
  if (std::isnan(b)) return;
  EXPECT_LE(value, b) << what << " " << value << " is above ~" << bound_name << " " << b << "; " << where();
}

TEST(Registration, FitAndUncertaintyWithinBounds) {
  const msg::CellRun& r = cell_run();
  if (!r.registered) {
    ADD_FAILURE() << "no registration to check: " << where();
    return;
  }
  expect_at_most(r.rms * 1e3, "max_rms_mm", "the fit's RMS (mm)");
  expect_at_most(r.translation_sigma * 1e3, "max_translation_sigma_mm", "the stated 1-sigma translation (mm)");
  expect_at_most(r.rotation_sigma / kDeg, "max_rotation_sigma_deg", "the stated 1-sigma rotation (degrees)");
}

bool vector_param(const std::string& name, Eigen::Vector3d& v) {
  std::vector<double> values;
  if (!private_nh().getParam(name, values)) return false;
  if (values.size() != 3) {
    ADD_FAILURE() << "~" << name << " must be a list of 3 numbers";
    return false;
  }
  v = Eigen::Vector3d(values[0], values[1], values[2]);
  return true;
}

TEST(Registration, PartWhereExpected) {
  Eigen::Vector3d xyz, rpy = Eigen::Vector3d::Zero();
  if (!vector_param("expected_xyz", xyz)) GTEST_SKIP() << "no ~expected_xyz";
  vector_param("expected_rpy", rpy);
  const msg::CellRun& r = cell_run();
  if (!r.registered) {
    ADD_FAILURE() << "no registration to check: " << where();
    return;
  }
  const auto& t = r.pose.transform;
  const Eigen::Vector3d found(t.translation.x, t.translation.y, t.translation.z);
  const Eigen::Quaterniond q_found(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z);
  const Eigen::Quaterniond q_expected = Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                                        Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                                        Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX());
  double tol_mm = bound("pose_tolerance_mm"), tol_deg = bound("pose_tolerance_deg");
  if (std::isnan(tol_mm)) tol_mm = 0.1;
  if (std::isnan(tol_deg)) tol_deg = 0.1;
  EXPECT_LE((found - xyz).norm() * 1e3, tol_mm) << "the part was found " << (found - xyz).norm() * 1e3
                                                << " mm from where it is expected";
  EXPECT_LE(q_found.angularDistance(q_expected) / kDeg, tol_deg)
      << "the part was found turned " << q_found.angularDistance(q_expected) / kDeg << " degrees from as expected";
}

TEST(Job, Succeeded) {
  EXPECT_TRUE(cell_run().job_done && cell_run().job.success) << where();
}

TEST(Job, SetupsAsExpected) {
  std::vector<std::string> expected;
  if (!private_nh().getParam("setups", expected)) GTEST_SKIP() << "no ~setups";
  std::vector<std::string> chosen;
  for (const auto& s : cell_run().job.setups) chosen.push_back(s.name);
  std::ostringstream a, b;
  for (const auto& s : expected) a << s << " ";
  for (const auto& s : chosen) b << s << " ";
  EXPECT_EQ(chosen, expected) << "the job chose the setups [ " << b.str() << "], expected [ " << a.str() << "]; "
                              << where();
}

TEST(Job, NoGouge) {
  const msg::CellRun& r = cell_run();
  if (!r.job_done) {
    ADD_FAILURE() << "no job to check: " << where();
    return;
  }
  double tol = bound("gouge_tolerance_mm");
  if (std::isnan(tol)) tol = 0.01;
  EXPECT_GE(r.job.min_left * 1e3, -tol) << "the job leaves " << r.job.min_left * 1e3
                                        << " mm on the part: a gouge deeper than ~gouge_tolerance_mm " << tol;
  // The verifier's own figure: the written programs swept through a stock of their own (report_json's gouge_mm).
  const nlohmann::json report = nlohmann::json::parse(r.job.report_json, nullptr, false);
  ASSERT_TRUE(report.is_object() && report.contains("gouge_mm")) << "the job's report has no gouge_mm";
  EXPECT_LE(report["gouge_mm"].get<double>(), tol)
      << "the verifier finds the programs " << report["gouge_mm"].get<double>() << " mm into the part";
}

TEST(Job, EveryFaceFinished) {
  if (!flag("every_face_finished", true)) GTEST_SKIP() << "~every_face_finished is false";
  const msg::CellRun& r = cell_run();
  if (!r.job_done) {
    ADD_FAILURE() << "no job to check: " << where();
    return;
  }
  EXPECT_EQ(r.job.unfinished_faces, 0u) << r.job.unfinished_faces << " of the " << r.job.faces_to_finish
                                        << " faces the job finishes are left above allowance + tolerance + scallop ("
                                        << r.job.unfinished_area * 1e6 << " mm2)";
}

TEST(Job, CycleTimeWithinBound) {
  if (std::isnan(bound("max_cycle_time_s"))) GTEST_SKIP() << "no ~max_cycle_time_s";
  if (!cell_run().job_done) {
    ADD_FAILURE() << "no job to check: " << where();
    return;
  }
  expect_at_most(cell_run().job.time, "max_cycle_time_s", "the job's estimated machining time (s)");
}

TEST(Programs, RanAndAcceptedByRs274) {
  if (!flag("programs_run", true)) GTEST_SKIP() << "~programs_run is false";
  const msg::CellRun& r = cell_run();
  ASSERT_TRUE(r.job_done) << "no job to check: " << where();
  ASSERT_FALSE(r.job.programs.empty()) << "the job wrote no program";
  EXPECT_EQ(r.runs.size(), r.job.programs.size()) << where();
  for (size_t k = 0; k < r.runs.size(); ++k) {
    const auto& run = r.runs[k];
    EXPECT_TRUE(run.success) << "program " << k + 1 << ": " << run.message;
    EXPECT_EQ(run.acknowledged_line, run.lines) << "program " << k + 1 << " ran to line " << run.acknowledged_line
                                                << " of " << run.lines;
    std::vector<std::string> lines;
    try {
      lines = rosmill::core::gcode::read_program_lines(run.program);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "program " << k + 1 << ": " << e.what();
      continue;
    }
    ASSERT_FALSE(lines.empty()) << "program " << k + 1 << ": nothing to read at " << run.program;
    const rosmill::core::gcode::Rs274Result rs = rosmill::core::gcode::run_rs274(lines);
    EXPECT_TRUE(rs.ok) << "rs274 refuses program " << k + 1 << " (" << run.program << ") at line " << rs.error_line
                       << ": " << rs.error;
    EXPECT_FALSE(rs.moves.empty()) << "rs274 reads no move in program " << k + 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "cell_checker");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  private_nh();
  return RUN_ALL_TESTS();
}
