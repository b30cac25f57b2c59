#include "rosmill/gcode/machine_from_ini.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "rosmill/error.hpp"
#include "rosmill/gcode/linuxcnc_tool_table.hpp"
#include "rosmill/input_file.hpp"
#include "rosmill/number_text.hpp"

namespace rosmill::core::gcode {
namespace {

// A number as the machine file shows it: no trailing zeros.
std::string num(double v) { return significant_text(std::abs(v) < 1e-12 ? 0.0 : v, 10); }

double positive(const LinuxcncIni& ini, const std::string& section, const std::string& key) {
  const double v = ini.number(section, key);
  if (!(v > 0)) throw Error(ini.path(), "[" + section + "] " + key + " must be positive, got " + num(v));
  return v;
}

// The tool table the ini names (a path from the ini's folder): each tool's length offset, which the estimate of a
// machine-coordinate move (G53) needs.
void write_tool_lengths(std::ostringstream& y, const LinuxcncIni& ini, double mm) {
  const std::string name = ini.text("EMCIO", "TOOL_TABLE");
  const std::string path = (std::filesystem::path(ini.path()).parent_path() / name).string();
  const std::map<int, double> lengths = tool_lengths_from_table(read_input_file(path), path, mm);
  y << "  tool_lengths: {";
  for (auto t = lengths.begin(); t != lengths.end(); ++t)
    y << (t == lengths.begin() ? "" : ", ") << t->first << ": " << num(t->second);
  y << "}  # mm: [EMCIO] TOOL_TABLE " << name << ", each tool's length offset (Z)\n";
}

}  // namespace

std::string machine_yaml_from_ini(const LinuxcncIni& ini) {
  const std::string units = ini.has("TRAJ", "LINEAR_UNITS") ? ini.text("TRAJ", "LINEAR_UNITS") : "mm";
  double mm = 1;
  if (units == "inch" || units == "in" || units == "imperial") mm = 25.4;
  else if (units != "mm" && units != "metric")
    throw Error(ini.path(), "[TRAJ] LINEAR_UNITS = '" + units + "': rosmill reads mm or inch");
  const char* axes[3] = {"X", "Y", "Z"};
  double vmax[3], amax[3], lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const std::string s = std::string("AXIS_") + axes[a];
    vmax[a] = positive(ini, s, "MAX_VELOCITY") * mm;
    amax[a] = positive(ini, s, "MAX_ACCELERATION") * mm;
    lo[a] = ini.number(s, "MIN_LIMIT") * mm;
    hi[a] = ini.number(s, "MAX_LIMIT") * mm;
    if (!(lo[a] < hi[a])) throw Error(ini.path(), "[" + s + "] MIN_LIMIT must be below MAX_LIMIT");
  }
  const double servo_ns = positive(ini, "EMCMOT", "SERVO_PERIOD");
  std::ostringstream y;
  y << "# The machine of " << ini.path() << " (rosmill machine --from-ini): millimetres, mm/min and rpm for the\n"
    << "# limits the programs are checked against; mm/s and mm/s^2 for the trajectory planner that times them.\n"
    << "# Each number's source is the comment beside it.\n";
  y << "name: " << (ini.has("EMC", "MACHINE") ? ini.text("EMC", "MACHINE") : "linuxcnc") << "  # [EMC] MACHINE\n";
  y << "envelope:\n";
  for (int a = 0; a < 3; ++a)
    y << "  " << char('x' + a) << ": [" << num(lo[a]) << ", " << num(hi[a]) << "]  # [AXIS_" << axes[a]
      << "] MIN_LIMIT, MAX_LIMIT\n";
  y << "work_offset: [0, 0, 0]  # not in the ini: G54 at machine zero\n";
  y << "table_z: " << num(lo[2]) << "  # not in the ini: the table top at the lowest Z ([AXIS_Z] MIN_LIMIT); measure it\n";
  y << "max_feed: " << num(60 * *std::min_element(vmax, vmax + 3))
    << "  # mm/min: the slowest of [AXIS_X], [AXIS_Y], [AXIS_Z] MAX_VELOCITY\n";
  if (ini.has("SPINDLE_0", "MAX_FORWARD_VELOCITY"))
    y << "max_spindle_rpm: " << num(positive(ini, "SPINDLE_0", "MAX_FORWARD_VELOCITY"))
      << "  # [SPINDLE_0] MAX_FORWARD_VELOCITY\n";
  else
    y << "max_spindle_rpm: 24000  # not in the ini ([SPINDLE_0] MAX_FORWARD_VELOCITY): the spindle's rating\n";
  y << "clearance_over_stock: 2  # rosmill's own: rapids end this high over the stock\n";
  y << "max_acceleration: {x: " << num(amax[0]) << ", y: " << num(amax[1]) << ", z: " << num(amax[2])
    << "}  # mm/s^2: [AXIS_X], [AXIS_Y], [AXIS_Z] MAX_ACCELERATION\n";
  y << "trajectory:\n";
  y << "  max_velocity: {x: " << num(vmax[0]) << ", y: " << num(vmax[1]) << ", z: " << num(vmax[2])
    << "}  # mm/s: [AXIS_X], [AXIS_Y], [AXIS_Z] MAX_VELOCITY\n";
  if (ini.has("TRAJ", "MAX_LINEAR_VELOCITY"))
    y << "  max_linear_velocity: " << num(positive(ini, "TRAJ", "MAX_LINEAR_VELOCITY") * mm)
      << "  # mm/s: [TRAJ] MAX_LINEAR_VELOCITY\n";
  if (ini.has("TRAJ", "MAX_LINEAR_ACCELERATION"))
    y << "  max_linear_acceleration: " << num(positive(ini, "TRAJ", "MAX_LINEAR_ACCELERATION") * mm)
      << "  # mm/s^2: [TRAJ] MAX_LINEAR_ACCELERATION\n";
  y << "  servo_period: " << num(servo_ns * 1e-9) << "  # s: [EMCMOT] SERVO_PERIOD (" << num(servo_ns) << " ns)\n";
  const auto setting = [&](const char* field, const char* key, const std::string& fallback, bool whole) {
    y << "  " << field << ": ";
    if (!ini.has("TRAJ", key)) {
      y << fallback << "  # [TRAJ] " << key << " not set: LinuxCNC's default\n";
      return;
    }
    const double v = ini.number("TRAJ", key);
    if (whole && (v != std::floor(v) || v < 0))
      throw Error(ini.path(), std::string("[TRAJ] ") + key + " must be a whole number, got " + num(v));
    y << num(v) << "  # [TRAJ] " << key << "\n";
  };
  setting("optimization_depth", "ARC_BLEND_OPTIMIZATION_DEPTH", "50", true);
  if (ini.has("TRAJ", "ARC_BLEND_ENABLE"))
    y << "  arc_blend: " << (ini.number("TRAJ", "ARC_BLEND_ENABLE") != 0 ? "true" : "false")
      << "  # [TRAJ] ARC_BLEND_ENABLE\n";
  else
    y << "  arc_blend: true  # [TRAJ] ARC_BLEND_ENABLE not set: LinuxCNC's default\n";
  setting("tangent_kink_ratio", "ARC_BLEND_KINK_RATIO", "0.1", false);
  if (ini.has("DISPLAY", "MAX_FEED_OVERRIDE"))
    y << "  max_feed_override: " << num(positive(ini, "DISPLAY", "MAX_FEED_OVERRIDE"))
      << "  # [DISPLAY] MAX_FEED_OVERRIDE\n";
  y << "  tool_change_seconds: 0  # not in the ini: the tool changer's time per M6\n";
  if (ini.has("EMCIO", "TOOL_CHANGE_POSITION")) {
    std::istringstream words(ini.text("EMCIO", "TOOL_CHANGE_POSITION"));
    double p[3];
    for (double& v : p)
      if (!(words >> v) || !std::isfinite(v))
        throw Error(ini.path(), "[EMCIO] TOOL_CHANGE_POSITION = '" + ini.text("EMCIO", "TOOL_CHANGE_POSITION") +
                                    "' must start with X Y Z");
    y << "  tool_change_position: [" << num(p[0] * mm) << ", " << num(p[1] * mm) << ", " << num(p[2] * mm)
      << "]  # machine mm: [EMCIO] TOOL_CHANGE_POSITION\n";
  }
  y << "  spindle_start_seconds: 0  # not in the ini: the spindle's time to reach its speed\n";
  if (ini.has("EMCIO", "TOOL_TABLE")) write_tool_lengths(y, ini, mm);
  return y.str();
}

}  // namespace rosmill::core::gcode
