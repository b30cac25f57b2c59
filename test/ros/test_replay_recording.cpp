// rostest node for test/ros/replay/recording.test: one recording made for the test (make_cell_recording.py)
// replayed by launch/replay.launch, and what the replay must give: the run's end (done, or the step it stops at and
// the words of its reason), the scans it fused, and for a done run the part where the recording put it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <sstream>

#include "rosmill/CellRun.h"
#include "rostest_support.hpp"

using rosmill::rostest::Latest;

namespace {

TEST(Replay, GivesWhatTheRecordingHolds) {
  ros::NodeHandle nh("/rosmill"), pnh("~");
  Latest<rosmill::CellRun> runs(nh, "cell_run");
  const double limit = pnh.param("time_limit", 150.0);
  boost::shared_ptr<const rosmill::CellRun> run;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(limit);
  size_t seen = 0;
  while (ros::ok() && ros::WallTime::now() < end) {
    run = runs.wait(1.0, seen);
    if (run) {
      seen = runs.count();
      if (run->done || run->failed) break;
    }
  }
  ASSERT_TRUE(run) << "no cell_run within " << limit << " s";
  ASSERT_TRUE(run->done || run->failed) << "still at '" << run->step << "' after " << limit << " s: " << run->message;

  const bool expect_done = pnh.param("expect_done", true);
  const std::string step = pnh.param<std::string>("expect_step", "done");
  const std::string words = pnh.param<std::string>("expect_message", "");
  EXPECT_EQ(run->done, expect_done) << "the run " << (run->done ? "ended" : "stopped") << " at '" << run->step
                                    << "': " << run->message;
  EXPECT_EQ(run->step, step) << run->message;
  // The words the reason must hold, joined by '+' (an argument of a rostest has no spaces).
  std::stringstream list(words);
  for (std::string word; std::getline(list, word, '+');) {
    if (!word.empty()) {
      EXPECT_NE(run->message.find(word), std::string::npos) << "no '" << word << "' in the reason: " << run->message;
    }
  }
  const int views = pnh.param("expect_views", -1);
  if (views >= 0) {
    EXPECT_EQ(run->views, static_cast<uint32_t>(views)) << run->fusion;
  }
  if (!run->done) return;

  // Where make_cell_recording.py placed the part: its origin at (0.1, 0.05, 0) m, turned 30 degrees about z.
  const auto& t = run->pose.transform;
  const Eigen::Vector3d found(t.translation.x, t.translation.y, t.translation.z);
  EXPECT_LT((found - Eigen::Vector3d(0.1, 0.05, 0)).norm(), 0.1e-3) << "found at " << found.transpose() << " m";
  const Eigen::Quaterniond q(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z);
  const Eigen::Quaterniond truth(Eigen::AngleAxisd(30 * M_PI / 180, Eigen::Vector3d::UnitZ()));
  EXPECT_LT(q.angularDistance(truth) * 180 / M_PI, 0.1);
  EXPECT_FALSE(run->ambiguous) << run->ambiguity;
  // The stated 1-sigma uncertainty covers the true error (3 sigma, and 1 um for the float32 points' rounding).
  const double error_mm = (found - Eigen::Vector3d(0.1, 0.05, 0)).norm() * 1e3;
  EXPECT_LE(error_mm, 3 * run->translation_sigma * 1e3 + 1e-3) << "1-sigma " << run->translation_sigma * 1e3 << " mm";
  EXPECT_LE(q.angularDistance(truth), 3 * run->rotation_sigma + 1e-5) << "1-sigma " << run->rotation_sigma << " rad";
}

}  // namespace

int main(int argc, char** argv) { return rosmill::rostest::run_all(argc, argv, "test_replay_recording"); }
