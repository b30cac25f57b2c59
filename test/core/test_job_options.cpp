// A job's options from the machine and the request (job_options.hpp): what `rosmill job` and the plan_job action
// both run with.
#include <gtest/gtest.h>

#include <string>

#include "error_of.hpp"
#include "rosmill/job/job_options.hpp"

using namespace rosmill::core;
using namespace rosmill::core::job;

namespace {

gcode::MachineLimits machine_with_clearance(double clearance) {
  gcode::MachineLimits m = gcode::load_machine_limits(std::string(ROSMILL_SOURCE_DIR) + "/config/machine.yaml");
  m.clearance_over_stock = clearance;
  return m;
}

// The machine checks the programs, times the moves and sets how high links keep over the stock.
TEST(JobOptions, TheMachineChecksTimesAndSetsTheLinkClearance) {
  JobRequest request;
  request.machine = machine_with_clearance(5);
  const JobOptions o = job_options(request);
  ASSERT_TRUE(o.checks.machine);
  EXPECT_EQ(o.checks.machine->name, "linuxcnc-sim-mm");
  EXPECT_EQ(o.link_clearance, 5.0);
  EXPECT_EQ(o.trajectory.max_linear_velocity, 53.34);  // config/machine.yaml's [TRAJ] MAX_LINEAR_VELOCITY
  EXPECT_TRUE(o.feeds_from_engagement);
  // A machine without a clearance over the stock (0) leaves the job's own, 2 mm.
  request.machine = machine_with_clearance(0);
  EXPECT_EQ(job_options(request).link_clearance, 2.0);
  // Without a machine: nothing checked, the time at the feeds alone, links at 2 mm.
  const JobOptions none = job_options(JobRequest{});
  EXPECT_FALSE(none.checks.machine);
  EXPECT_EQ(none.trajectory.max_linear_velocity, gcode::TrajectoryLimits{}.max_linear_velocity);
  EXPECT_EQ(none.link_clearance, 2.0);
}

// no_limits leaves the programs unchecked; the machine still times them and keeps its clearance.
TEST(JobOptions, NoLimitsStillTimesAndKeepsTheClearance) {
  JobRequest request;
  request.machine = machine_with_clearance(4);
  request.no_limits = true;
  request.out_dir = "/tmp/out";
  const JobOptions o = job_options(request);
  EXPECT_FALSE(o.checks.machine);
  EXPECT_EQ(o.link_clearance, 4.0);
  EXPECT_EQ(o.trajectory.max_linear_velocity, 53.34);
}

// The request's own fields pass through; table_feeds turns the feeds from the engagement off.
TEST(JobOptions, TheRequestPassesThrough) {
  JobRequest request;
  request.machine = machine_with_clearance(2);
  request.out_dir = "/tmp/programs";
  request.per_operation = true;
  request.dialect = "grbl";
  request.table_feeds = true;
  request.verify_rs274 = true;
  const Mesh part;
  request.part = &part;
  const JobOptions o = job_options(request);
  EXPECT_EQ(o.out_dir, "/tmp/programs");
  EXPECT_TRUE(o.per_operation);
  EXPECT_EQ(o.dialect, "grbl");
  EXPECT_FALSE(o.feeds_from_engagement);
  EXPECT_TRUE(o.checks.rs274);
  EXPECT_EQ(o.part, &part);
}

// The work offset is the written programs' G54: asked for only when programs are written.
TEST(JobOptions, TheWorkOffsetIsAskedOnlyForPrograms) {
  int asked = 0;
  JobRequest request;
  request.machine = machine_with_clearance(2);
  request.work_offset = [&asked] {
    ++asked;
    gcode::WorkOffset w;
    w.origin = Vec3(10, 20, -30);
    return std::optional<gcode::WorkOffset>(w);
  };
  EXPECT_FALSE(job_options(request).work_offset);
  EXPECT_EQ(asked, 0);
  request.out_dir = "/tmp/programs";
  const JobOptions o = job_options(request);
  ASSERT_TRUE(o.work_offset);
  EXPECT_EQ(o.work_offset->origin, Vec3(10, 20, -30));
  EXPECT_EQ(asked, 1);
}

TEST(JobOptions, RefusesProgramsWithoutAMachineAndUnknownDialects) {
  JobRequest request;
  request.out_dir = "/tmp/programs";
  EXPECT_EQ(error_of([&] { job_options(request); }).rfind("output folder: the programs are checked against the "
                                                           "machine's limits", 0),
            0u)
      << error_of([&] { job_options(request); });
  request.no_limits = true;
  EXPECT_EQ(error_of([&] { job_options(request); }), "");
  request.dialect = "fanuc";
  EXPECT_NE(error_of([&] { job_options(request); }).find("unknown dialect 'fanuc'"), std::string::npos);
}

}  // namespace
