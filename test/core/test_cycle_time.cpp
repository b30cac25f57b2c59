// The cycle-time estimator's known answers (closed forms of LinuxCNC's planner for simple programs), the machine
// file's planner limits, and `rosmill machine --from-ini`'s machine file from a LinuxCNC ini.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <unistd.h>

#include "rosmill/error.hpp"
#include "rosmill/gcode/cycle_time.hpp"
#include "rosmill/gcode/linuxcnc_ini.hpp"
#include "rosmill/gcode/linuxcnc_tool_table.hpp"
#include "rosmill/gcode/machine_from_ini.hpp"
#include "rosmill/gcode/machine_limits.hpp"

using namespace rosmill::core;
using namespace rosmill::core::gcode;

namespace {

// The sim's machine (axis_mm.ini): 30.48 mm/s and 508 mm/s^2 per axis, 53.34 mm/s along the path.
TrajectoryLimits sim() {
  TrajectoryLimits t;
  t.max_velocity = Vec3(30.48, 30.48, 30.48);
  t.max_acceleration = Vec3(508, 508, 508);
  t.max_linear_velocity = 53.34;
  t.max_linear_acceleration = 508;
  return t;
}

double seconds(const std::vector<std::string>& program, const TrajectoryLimits& t = sim()) {
  return estimate_cycle_time(program, t, "test").seconds;
}

// From rest to rest at speed v and acceleration a, long enough to cruise.
double rest_to_rest(double length, double v, double a) { return length / v + v / a; }

}  // namespace

TEST(CycleTime, AStraightMoveAcceleratesCruisesAndBrakes) {
  EXPECT_NEAR(seconds({"G21 G90 G64 P0.01", "G0 X0 Y0 Z0", "G1 X100 F1200"}), rest_to_rest(100, 20, 508), 1e-9);
  // Collinear moves are tangent: no slowing between them.
  EXPECT_NEAR(seconds({"G21 G90 G64 P0.01", "G0 X0 Y0 Z0", "G1 X50 F1200", "X100"}), rest_to_rest(100, 20, 508), 1e-9);
  // A feed above what the axis allows runs at the axis's limit.
  EXPECT_NEAR(seconds({"G21 G90", "G0 X0 Y0 Z0", "G1 X100 F6000"}), rest_to_rest(100, 30.48, 508), 1e-9);
}

TEST(CycleTime, RapidsRunAtTheAxesLimitsAlongTheirDirection) {
  // Along X alone: the X axis's 30.48 mm/s. Along the XY diagonal each axis carries 1/sqrt(2): 43.1 mm/s, under the
  // path's 53.34; the acceleration likewise 508 sqrt(2) (capped by the path's 508).
  EXPECT_NEAR(seconds({"G21 G90", "G0 X0 Y0 Z0", "G0 X100"}), rest_to_rest(100, 30.48, 508), 1e-9);
  EXPECT_NEAR(seconds({"G21 G90", "G0 X0 Y0 Z0", "G0 X100 Y100"}),
              rest_to_rest(100 * std::sqrt(2.0), 30.48 * std::sqrt(2.0), 508), 1e-9);
  // A retract in machine coordinates (G53, the G54 origin set by the program) and the way back down from it.
  EXPECT_NEAR(seconds({"G21 G90 G61", "G10 L2 P1 X0 Y0 Z-20", "G54 G0 X0 Y0 Z0", "G53 G0 Z80", "G0 Z0"}),
              2 * rest_to_rest(100, 30.48, 508), 1e-9);
}

// G43 makes the program's Z the tool's tip, its length below the spindle: a retract to a machine Z (G53, before a
// trunnion turns the part) runs from the spindle's height, the tip's plus that length, and so does the way back.
TEST(CycleTime, AMachineCoordinateRetractRunsFromTheSpindleOfTheToolInItsLengthOffset) {
  const std::vector<std::string> program = {"G21 G90 G61", "G10 L2 P1 X0 Y0 Z0", "G54 G0 X0 Y0 Z0", "T5 M6", "G43 H5",
                                            "G0 Z50",      "G53 G0 Z110",        "G0 Z60"};
  TrajectoryLimits t = sim();
  // Without the tool table: 60 mm up, 50 down. With tool 5 30 mm long: machine Z 80 up to 110 (the tip at program
  // Z 80), then 20 mm down to Z 60.
  EXPECT_NEAR(seconds(program, t),
              rest_to_rest(50, 30.48, 508) + rest_to_rest(60, 30.48, 508) + rest_to_rest(50, 30.48, 508), 1e-9);
  t.tool_lengths = {{5, 30.0}, {6, 12.0}};
  EXPECT_NEAR(seconds(program, t),
              rest_to_rest(50, 30.48, 508) + rest_to_rest(30, 30.48, 508) + rest_to_rest(20, 30.48, 508), 1e-9);
  // The reader loses Z at a G53 move; the estimate follows it: a move in X alone, then the way down from the
  // retract's height (before, the way down was taken as going nowhere: a short 3+2 program was estimated 3 s short).
  EXPECT_NEAR(seconds({"G21 G90 G61", "G10 L2 P1 X0 Y0 Z0", "G54 G0 X0 Y0 Z0", "G53 G0 Z60", "G0 X10", "G0 Z0"}),
              rest_to_rest(60, 30.48, 508) + rest_to_rest(10, 30.48, 508) + rest_to_rest(60, 30.48, 508), 1e-9);
  // G49 takes the offset off: machine Z is the program's again.
  std::vector<std::string> cancelled = program;
  cancelled.insert(cancelled.begin() + 6, "G49");
  t.tool_lengths = {{5, 30.0}};
  EXPECT_NEAR(seconds(cancelled, t),
              rest_to_rest(50, 30.48, 508) + rest_to_rest(60, 30.48, 508) + rest_to_rest(50, 30.48, 508), 1e-9);
}

TEST(CycleTime, ExactStopStopsAtTheCornerAndBlendingDoesNot) {
  const std::vector<std::string> corner = {"G0 X0 Y0 Z0", "G1 X50 F1200", "Y50"};
  std::vector<std::string> exact = {"G21 G90 G61"}, blended = {"G21 G90 G64 P0.01"};
  exact.insert(exact.end(), corner.begin(), corner.end());
  blended.insert(blended.end(), corner.begin(), corner.end());
  EXPECT_NEAR(seconds(exact), 2 * rest_to_rest(50, 20, 508), 1e-9);
  // The blend arc of a right angle within 0.01 mm: radius 0.024 mm, taken at sqrt(0.87 a r) = 3.3 mm/s; braking to
  // it and back costs a little less than a full stop.
  const double b = seconds(blended);
  EXPECT_LT(b, seconds(exact) - 0.002);
  EXPECT_GT(b, rest_to_rest(100, 20, 508));
  // Within 0.5 mm the arc (radius 1.2 mm) is taken at the feed: faster than the corner's 100 mm at the feed.
  blended[0] = "G21 G90 G64 P0.5";
  EXPECT_LT(seconds(blended), rest_to_rest(100, 20, 508) - 0.01);
}

TEST(CycleTime, TightArcsRunAtTheSpeedTheirNormalAccelerationAllows) {
  // A full circle of radius 1.5 at F1800 (30 mm/s): v^2 / r may use sqrt(1 - 0.5^2) of 508 mm/s^2, so 25.7 mm/s,
  // with half the acceleration left along the path.
  const double v = std::sqrt(std::sqrt(0.75) * 508 * 1.5), length = 2 * M_PI * 1.5;
  EXPECT_NEAR(seconds({"G21 G90 G17", "G0 X1.5 Y0 Z0", "G3 X1.5 Y0 I-1.5 J0 F1800"}), rest_to_rest(length, v, 254),
              1e-9);
  // A wide one runs at the feed, braking with what the normal acceleration at the axes' top speed leaves (the
  // planner sizes it for the machine's speed, not the feed's).
  const double a = 508 * std::sqrt(1 - std::pow(30.48 * 30.48 / 15 / 508, 2));
  EXPECT_NEAR(seconds({"G21 G90 G17", "G0 X15 Y0 Z0", "G3 X15 Y0 I-15 J0 F1200"}),
              rest_to_rest(2 * M_PI * 15, 20, a), 1e-9);
}

TEST(CycleTime, ToolChangesSpindleStartsAndDwellsStopTheMachineAndAddTheirTime) {
  TrajectoryLimits t = sim();
  t.tool_change_seconds = 4;
  t.spindle_start_seconds = 1.5;
  const std::vector<std::string> program = {"G21 G90 G64 P0.01", "G0 X0 Y0 Z0", "G1 X50 F1200", "T1 M6",
                                            "S1000 M3",          "G4 P2",       "G1 X100"};
  EXPECT_NEAR(seconds(program, t), 2 * rest_to_rest(50, 20, 508) + 4 + 1.5 + 2, 1e-9);
  EXPECT_EQ(estimate_cycle_time(program, t).stops, 2u);
}

TEST(CycleTime, TheLookAheadLimitsTheSpeedOverManyShortSegments) {
  // 400 collinear 0.01 mm segments: the planner may not pass 50 of them (0.5 mm) faster than it can stop within
  // them, sqrt(2 a 0.5) = 22.5 mm/s, nor a segment in less than a servo period (10 mm/s).
  std::vector<std::string> program = {"G21 G90 G64 P0.01", "G0 X0 Y0 Z0", "G1 F1800"};
  for (int k = 1; k <= 400; ++k) program.push_back("X" + std::to_string(0.01 * k));
  const double t = seconds(program);
  EXPECT_GT(t, 4.0 / 10.0);
  EXPECT_LT(t, 4.0 / 10.0 + 0.05);
}

TEST(CycleTime, TheMachineFileCarriesTheSimulatorsPlanner) {
  const MachineLimits m = load_machine_limits(ROSMILL_SOURCE_DIR "/config/machine.yaml");
  EXPECT_EQ(m.trajectory.max_velocity, Vec3(30.48, 30.48, 30.48));
  EXPECT_EQ(m.trajectory.max_acceleration, Vec3(508, 508, 508));
  EXPECT_DOUBLE_EQ(m.trajectory.max_linear_velocity, 53.34);
  EXPECT_DOUBLE_EQ(m.trajectory.servo_period, 0.001);
  EXPECT_EQ(m.trajectory.optimization_depth, 50);
  // The trunnion simulator's tool table (xyzac-trt.tbl).
  const MachineLimits x = load_machine_limits(ROSMILL_SOURCE_DIR "/config/machine_xyzac.yaml");
  EXPECT_DOUBLE_EQ(x.trajectory.tool_length(5), 30.0);
  EXPECT_DOUBLE_EQ(x.trajectory.tool_length(2), 15.0);
  EXPECT_DOUBLE_EQ(x.trajectory.tool_length(42), 0.0);
  const std::string base =
      "name: m\nenvelope: {x: [0, 1], y: [0, 1], z: [0, 1]}\ntable_z: 0\nmax_feed: 1\n"
      "max_spindle_rpm: 1\nclearance_over_stock: 0\n";
  auto error = [&](const std::string& trajectory) {
    try {
      parse_machine_limits(base + "trajectory:\n  " + trajectory + "\n", "m.yaml");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error("tool_lengths: {5: 30, 0: 2}").rfind("m.yaml:8 trajectory.tool_lengths: tool number '0'", 0), 0u)
      << error("tool_lengths: {5: 30, 0: 2}");
  EXPECT_EQ(error("tool_lengths: {5: long}"), "m.yaml:8 trajectory.tool_lengths: expected a length in mm, got 'long'");
  EXPECT_EQ(error("tool_lengths: [30]").rfind("m.yaml:8 trajectory.tool_lengths: must be {tool number", 0), 0u);
  try {
    parse_machine_limits("name: m\nenvelope: {x: [0, 1], y: [0, 1], z: [0, 1]}\ntable_z: 0\nmax_feed: 1\n"
                         "max_spindle_rpm: 1\nclearance_over_stock: 0\ntrajectory: {servo_period: -1}\n",
                         "m.yaml");
    ADD_FAILURE() << "a negative servo period was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("servo_period"), std::string::npos) << e.what();
  }
}

// The trunnion simulator's ini names its tool table: `rosmill machine --from-ini` writes each tool's length offset,
// the ones config/machine_xyzac.yaml holds.
TEST(MachineFromIni, TheToolTableTheIniNamesGivesEachToolsLength) {
  const std::string ini =
      "/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis/vismach/5axis/table-rotary-tilting/xyzac-trt.ini";
  if (::access(ini.c_str(), R_OK) != 0) GTEST_SKIP() << "LinuxCNC's sample configurations are not installed";
  const MachineLimits m = parse_machine_limits(machine_yaml_from_ini(LinuxcncIni::read(ini)), "from ini");
  const MachineLimits config = load_machine_limits(ROSMILL_SOURCE_DIR "/config/machine_xyzac.yaml");
  EXPECT_EQ(m.trajectory.tool_lengths, config.trajectory.tool_lengths);
  EXPECT_DOUBLE_EQ(m.trajectory.tool_length(5), 30.0);
  // The table's own errors name its file and line.
  EXPECT_THROW(tool_lengths_from_table("T1 P1 Z0\nT2 P2 Zlong\n", "t.tbl", 1), Error);
  try {
    tool_lengths_from_table("T1 P1 Z0 ;one\n\nT1 P2 Z3\n", "t.tbl", 1);
    ADD_FAILURE() << "a tool listed twice was taken";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "t.tbl:3: tool 1 is listed twice");
  }
  EXPECT_DOUBLE_EQ(tool_lengths_from_table("T3 P3 Z1 D2\n", "t.tbl", 25.4).at(3), 25.4);
}

TEST(MachineFromIni, TheSimulatorsIniGivesTheMachineFilesNumbersWithTheirSources) {
  const std::string ini_path = "/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis/axis_mm.ini";
  const std::string ini_text =
      "[EMC]\nMACHINE = LinuxCNC-HAL-SIM-AXIS\n[EMCIO]\nTOOL_CHANGE_POSITION = 0 0 50.8\n[DISPLAY]\nMAX_FEED_OVERRIDE = 1.2\n[EMCMOT]\nSERVO_PERIOD = 1000000\n"
      "[TRAJ]\nLINEAR_UNITS = mm\nMAX_LINEAR_VELOCITY = 53.34\nMAX_LINEAR_ACCELERATION = 508\n"
      "[AXIS_X]\nMAX_VELOCITY = 30.48\nMAX_ACCELERATION = 508\nMIN_LIMIT = -254\nMAX_LIMIT = 254\n"
      "[AXIS_Y]\nMAX_VELOCITY = 30.48\nMAX_ACCELERATION = 508\nMIN_LIMIT = -254\nMAX_LIMIT = 254\n"
      "# a comment\n[AXIS_Z]\nMAX_VELOCITY = 30.48\nMAX_ACCELERATION = 508\nMIN_LIMIT = -50.8\nMAX_LIMIT = 101.6\n";
  const std::string yaml = machine_yaml_from_ini(LinuxcncIni::parse(ini_text, ini_path));
  const MachineLimits m = parse_machine_limits(yaml, "from ini");
  const MachineLimits config = load_machine_limits(ROSMILL_SOURCE_DIR "/config/machine.yaml");
  EXPECT_EQ(m.trajectory.max_velocity, config.trajectory.max_velocity);
  EXPECT_EQ(m.trajectory.max_acceleration, config.trajectory.max_acceleration);
  EXPECT_DOUBLE_EQ(m.trajectory.max_linear_velocity, config.trajectory.max_linear_velocity);
  EXPECT_DOUBLE_EQ(m.trajectory.servo_period, config.trajectory.servo_period);
  EXPECT_DOUBLE_EQ(m.trajectory.max_feed_override, config.trajectory.max_feed_override);
  EXPECT_EQ(m.envelope.max, config.envelope.max);
  EXPECT_EQ(m.trajectory.tool_change_position, config.trajectory.tool_change_position);
  EXPECT_TRUE(m.trajectory.has_tool_change_position);
  EXPECT_NE(yaml.find("[AXIS_X], [AXIS_Y], [AXIS_Z] MAX_VELOCITY"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("[EMCMOT] SERVO_PERIOD"), std::string::npos) << yaml;
  // Inches become millimetres.
  std::string inch = ini_text;
  inch.replace(inch.find("LINEAR_UNITS = mm"), 17, "LINEAR_UNITS = inch");
  EXPECT_NEAR(parse_machine_limits(machine_yaml_from_ini(LinuxcncIni::parse(inch, "in.ini")), "in").trajectory
                  .max_velocity.x(),
              30.48 * 25.4, 1e-9);
  // A missing or bad key is named with its file and section.
  for (const auto& [bad, expected] : std::vector<std::pair<std::string, std::string>>{
           {"[AXIS_X]\nMAX_VELOCITY = fast\n", "bad.ini: [AXIS_X] MAX_VELOCITY = 'fast' is not a number"},
           {"[AXIS_X]\nMAX_VELOCITY = 30\n", "bad.ini: [AXIS_X] MAX_ACCELERATION is missing"},
           {"[AXIS_X\n", "bad.ini:1"}}) {
    try {
      machine_yaml_from_ini(LinuxcncIni::parse(bad, "bad.ini"));
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}
