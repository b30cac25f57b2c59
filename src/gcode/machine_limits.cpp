#include "rosmill/gcode/machine_limits.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/input_file.hpp"
#include "rosmill/number_text.hpp"
#include "rosmill/toolpath/canon_arc.hpp"
#include "rosmill/yaml/fields.hpp"

namespace rosmill::core::gcode {
namespace {

std::string fmt(double v) { return significant_text(v, 10); }

// [lo, hi] with lo below hi.
std::pair<double, double> range_of(const yaml::Fields& f, const std::string& key, const std::string& what) {
  const YAML::Node r = f.node(key);
  if (!r || !r.IsSequence() || r.size() != 2) f.fail(key, "must be [min, max]" + what);
  const double lo = f.converted<double>(r[0], key, "expected a number"),
               hi = f.converted<double>(r[1], key, "expected a number");
  if (!std::isfinite(lo) || !std::isfinite(hi)) f.fail(key, "expected finite numbers");
  if (!(lo < hi)) f.fail(key, "min must be below max");
  return {lo, hi};
}

machine::RotaryAxis rotary_axis(const yaml::Fields& rotary, const std::string& name) {
  const YAML::Node node = rotary.node(name);
  if (!node || !node.IsMap()) rotary.fail(name, "missing: {range: [min, max], velocity: deg/s, acceleration: deg/s^2}");
  const yaml::Fields f(node, rotary.file(), rotary.place(name), {"range", "velocity", "acceleration"});
  machine::RotaryAxis a;
  std::tie(a.min, a.max) = range_of(f, "range", " (degrees)");
  a.velocity = f.required_positive("velocity");
  a.acceleration = f.required_positive("acceleration");
  return a;
}

// {x: V, y: V, z: V}, each greater than 0.
Vec3 per_axis(const yaml::Fields& f, const std::string& key) {
  const yaml::Fields v(f.node(key), f.file(), f.place(key), {"x", "y", "z"});
  return Vec3(v.required_positive("x"), v.required_positive("y"), v.required_positive("z"));
}

// {tool number: length offset in mm, ...}: the controller's tool table.
std::map<int, double> tool_lengths(const yaml::Fields& f, const std::string& key) {
  const YAML::Node table = f.node(key);
  if (!table.IsMap()) f.fail(key, "must be {tool number: length offset in mm, ...} (the controller's tool table)");
  std::map<int, double> lengths;
  for (const auto& kv : table) {
    const std::string where = f.where_at(kv.first, key);
    const int tool = parse_tool_number(kv.first.IsScalar() ? kv.first.Scalar() : "?", where);
    const double length = f.converted<double>(kv.second, key, "expected a length in mm");
    if (!std::isfinite(length)) throw Error(where, "tool " + std::to_string(tool) + "'s length is not finite");
    lengths[tool] = length;
  }
  return lengths;
}

// `trajectory:`: the controller's trajectory planner; every field optional (LinuxCNC's defaults).
void read_trajectory(const yaml::Fields& top, TrajectoryLimits& out) {
  const yaml::Fields t(
      top.node("trajectory"), top.file(), "trajectory",
      {"max_velocity", "max_linear_velocity", "max_linear_acceleration", "servo_period", "optimization_depth",
       "arc_blend", "tangent_kink_ratio", "max_feed_override", "tool_change_seconds", "spindle_start_seconds",
       "tool_change_position", "spindle_acceleration", "spindle_at_speed_share", "tool_lengths"});
  if (t.has("max_velocity")) out.max_velocity = per_axis(t, "max_velocity");
  out.max_linear_velocity = t.positive("max_linear_velocity", out.max_linear_velocity);
  out.max_linear_acceleration = t.positive("max_linear_acceleration", out.max_linear_acceleration);
  out.servo_period = t.positive("servo_period", out.servo_period);
  if (t.has("optimization_depth")) {
    const double d = t.positive("optimization_depth", 0, 100000);
    if (d != std::floor(d)) t.fail("optimization_depth", "must be a whole number of segments");
    out.optimization_depth = int(d);
  }
  out.arc_blend = t.flag("arc_blend", out.arc_blend);
  out.tangent_kink_ratio = t.positive("tangent_kink_ratio", out.tangent_kink_ratio);
  out.max_feed_override = t.positive("max_feed_override", out.max_feed_override);
  if (t.has("tool_change_position")) {
    out.tool_change_position = t.vector3("tool_change_position");
    out.has_tool_change_position = true;
  }
  out.spindle_acceleration = t.positive("spindle_acceleration", out.spindle_acceleration);
  out.spindle_at_speed_share = t.positive("spindle_at_speed_share", out.spindle_at_speed_share, 1);
  out.tool_change_seconds = t.number("tool_change_seconds", out.tool_change_seconds, 0);
  out.spindle_start_seconds = t.number("spindle_start_seconds", out.spindle_start_seconds, 0);
  if (t.has("tool_lengths")) out.tool_lengths = tool_lengths(t, "tool_lengths");
}

// `rotary:` of a trunnion table (XYZAC): A about machine X carrying C about the table's Z.
machine::Trunnion trunnion(const yaml::Fields& top, const MachineLimits& m) {
  const yaml::Fields r(top.node("rotary"), top.file(), "rotary",
                       {"kinematics", "a", "c", "c_centre", "a_pivot", "mode", "safe_z", "max_tool_length"});
  if (r.text("kinematics", "", true) != "trunnion-ac")
    r.fail("kinematics", "must be trunnion-ac (A about X carrying C about Z: LinuxCNC's xyzac-trt)");
  machine::Trunnion t;
  t.a = rotary_axis(r, "a");
  t.c = rotary_axis(r, "c");
  t.centre = r.vector3("c_centre");
  t.pivot = r.vector3("a_pivot");
  const std::string mode = r.text("mode", "identity");
  if (mode != "identity" && mode != "tool-centre-point")
    r.fail("mode", "must be identity or tool-centre-point, got '" + mode + "'");
  t.mode = mode == "identity" ? machine::KinematicsMode::Identity : machine::KinematicsMode::ToolCentrePoint;
  if (!r.has("safe_z")) r.fail("safe_z", "missing (machine Z the tool retracts to to index)");
  t.safe_z = r.required_number("safe_z", m.envelope.min.z(), m.envelope.max.z());
  if (!r.has("max_tool_length"))
    r.fail("max_tool_length",
           "missing (the longest tool's length offset, mm: its tip hangs that far below the safe "
           "Z while the part turns)");
  t.max_tool_length = r.required_number("max_tool_length", 0);
  return t;
}

}  // namespace

MachineLimits load_machine_limits(const std::string& path) {
  return parse_machine_limits(read_input_file(path), path);
}

std::shared_ptr<const machine::Machine> MachineLimits::machine() const {
  const Vec3 acceleration = trajectory.max_acceleration.isZero() ? max_acceleration : trajectory.max_acceleration;
  if (trunnion) return machine::trunnion_mill(*trunnion, envelope, trajectory.max_velocity, acceleration);
  return machine::three_axis_mill(envelope, trajectory.max_velocity, acceleration);
}

MachineLimits parse_machine_limits(const std::string& yaml_text, const std::string& path) {
  const YAML::Node root = yaml::parse(yaml_text, path);
  if (!root.IsMap()) throw Error(yaml::line_of(root, path), "expected a map of machine fields");
  const yaml::Fields f(root, path, "",
                       {"name", "envelope", "work_offset", "table_z", "max_feed", "max_spindle_rpm",
                        "clearance_over_stock", "fixture_position", "max_acceleration", "rotary", "trajectory"});
  MachineLimits m;
  m.name = f.has("name") ? f.text("name", "") : "";
  if (!f.has("envelope")) f.fail("envelope", "missing (x, y, z: [min, max])");
  const yaml::Fields env(f.node("envelope"), path, "envelope", {"x", "y", "z"});
  static const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) std::tie(m.envelope.min[a], m.envelope.max[a]) = range_of(env, axes[a], "");
  if (f.has("work_offset")) m.work_offset.origin = f.vector3("work_offset");
  m.table_z = f.required_number("table_z", m.envelope.min.z() - 1e-9, m.envelope.max.z());
  m.max_feed = f.required_positive("max_feed");
  m.max_spindle_rpm = f.required_positive("max_spindle_rpm");
  m.clearance_over_stock = f.required_number("clearance_over_stock", 0);
  m.fixture_position = m.work_offset.origin.head<2>();
  if (const YAML::Node fp = f.node("fixture_position")) {
    if (!fp.IsSequence() || fp.size() != 2) f.fail("fixture_position", "must be [x, y]");
    for (int a = 0; a < 2; ++a) {
      m.fixture_position[a] = f.converted<double>(fp[a], "fixture_position", "expected a number");
      if (!(m.fixture_position[a] >= m.envelope.min[a] && m.fixture_position[a] <= m.envelope.max[a]))
        f.fail("fixture_position", "lies outside the envelope");
    }
  }
  if (f.has("max_acceleration")) m.max_acceleration = per_axis(f, "max_acceleration");
  if (f.has("rotary")) m.trunnion = trunnion(f, m);
  m.trajectory.max_acceleration = m.max_acceleration;
  if (f.has("trajectory")) read_trajectory(f, m.trajectory);
  if (m.trunnion)
    for (const auto& [tool, length] : m.trajectory.tool_lengths)
      if (length > m.trunnion->max_tool_length)
        f.fail("trajectory", "tool " + std::to_string(tool) + "'s length offset " + fmt(length) +
                                 " mm is over rotary.max_tool_length " + fmt(m.trunnion->max_tool_length) +
                                 " (its tip would hang below what the safe Z clears while the part turns)");
  if (m.trunnion) {
    m.trajectory.rotary_velocity = Vec2(m.trunnion->a.velocity, m.trunnion->c.velocity);
    m.trajectory.rotary_acceleration = Vec2(m.trunnion->a.acceleration, m.trunnion->c.acceleration);
  }
  return m;
}

std::string LimitViolation::message() const { return limit + ": " + detail + ": " + text; }

namespace {

// One line as the checker saw it: its move (if it moved) and the feed and spindle in force after it.
struct Step {
  size_t line;
  bool moved;
  CanonMove move;
  bool machine_coordinates;  // a G53 move: `move.to` holds the machine position along the axes known_to names
  double feed, rpm;
  int spindle;
  WorkOffset offset;  // the active coordinate system's origin on the machine when the move ran
  size_t run = 0;     // the runs of a 3+2 program between its indexings: each sees the part from another side
  bool tcp = false;   // after M428: tool-centre-point kinematics (X Y Z the tip on the table)
};

// The coordinate systems G54..G59 as far as the checker knows them: G54 from the machine file, each of them once the
// program sets it (G10 L2). A system neither gives is unknown, and selecting it is refused.
using KnownOffsets = std::array<std::optional<WorkOffset>, kWorkOffsets>;

// The index (1..6) of an active coordinate system G54..G59; 0 for G59.1..G59.3, which the checker does not follow.
int offset_index(int work_offset) { return work_offset >= 54 && work_offset <= 59 ? work_offset - 53 : 0; }

// The origin set by the block, when it is coordinate system data the checker can follow: G10 L2 for G54..G59 (P1..P6,
// or P0 for the active one) with all of X, Y and Z given; R (LinuxCNC's turn about Z) is 0 when absent, as the
// machine file's G54 has none. Empty for any other block.
std::optional<WorkOffset> followed_work_offset(const Interpreter& reader) {
  const Block& b = reader.block();
  if (!b.has_g(100) || !b.has('L') || std::lround(b.get('L')) != 2 || !b.has('P')) return std::nullopt;
  long p = std::lround(b.get('P'));
  if (p == 0) p = offset_index(reader.state().work_offset);
  if (p < 1 || p > kWorkOffsets) return std::nullopt;
  if (!(b.has('X') && b.has('Y') && b.has('Z'))) return std::nullopt;
  const double unit = reader.state().metric ? 1.0 : 25.4;
  WorkOffset w;
  w.origin = Vec3(b.get('X'), b.get('Y'), b.get('Z')) * unit;
  w.rotation_deg = b.has('R') ? b.get('R') : 0.0;
  w.index = static_cast<int>(p);
  return w;
}

// A move in machine coordinates the checker follows: G53 with G0 or G1 and linear axes alone (the retract before a
// trunnion turns the part).
bool machine_move(const Interpreter& reader) {
  const Block& b = reader.block();
  return b.has_g(530) && b.has_linear() && !b.has_rotary() && (reader.state().motion == 0 || reader.state().motion == 1);
}

// What the checker cannot follow is refused rather than passed unchecked: moves to stored or machine positions,
// offset changes other than coordinate system data it follows, and a coordinate system whose origin neither the
// machine file nor the program gives. Feeds it cannot check and arcs outside the XY plane stop the check.
template <class Add>
void refuse_unfollowed(const Interpreter& reader, int offset_before, const KnownOffsets& known, Add&& add) {
  const Block& block = reader.block();
  for (int k = 0; k < block.g_count; ++k) {
    const int g = block.g[k];
    if (g == 280 || g == 300 || (g == 530 && !machine_move(reader)))
      add("unchecked move", g_name(g) + " goes to a stored or machine position the checker cannot follow" +
                                (g == 530 ? std::string(" (G53 with G0 or G1 and X, Y, Z alone is followed)") : ""));
    if ((g == 100 && !followed_work_offset(reader)) || g == 920 || g == 921 || g == 922 || g == 923)
      add("unchecked move", g_name(g) + " changes an offset; later positions could not be checked" +
                                (g == 100 ? " (G10 L2 P1..P6 with X, Y and Z, setting G54..G59's origin, is followed)"
                                          : ""));
  }
  const ModalState& s = reader.state();
  const int index = offset_index(s.work_offset);
  if (s.work_offset != offset_before && (index == 0 || !known[index - 1]))
    add("work offset", work_offset_code(s.work_offset) +
                           " selected before the program set its origin (G10 L2); the machine file gives G54's "
                           "origin only");
  if (reader.moved() && reader.move().is_arc() && reader.move().plane != Plane::XY)
    throw Error(reader.where(), "arcs outside the XY plane (G17) are not followed");
}

// The rotary axes against the machine's rotary joints' ranges; a rotary word refused on a machine without that joint.
template <class Add>
void check_rotary(const MachineLimits& lim, const machine::Machine& machine, const CanonMove& m, bool tcp, Add&& add) {
  if (!m.known_rotary && !m.indexes()) return;
  const machine::Joint* a = machine.joint("A");
  const machine::Joint* c = machine.joint("C");
  if (!a || !c) {
    add("rotary axes", "the machine '" + lim.name + "' has no A or C axis");
    return;
  }
  // The table's check and the turning sweep assume the part stands still while the tool moves (3+2).
  if (!tcp && m.indexes() && (m.to - m.from).cwiseAbs().maxCoeff() > 0)
    add("simultaneous move", "A or C turns while X, Y or Z move: a 3+2 program indexes with A and C alone");
  const auto within = [&](const machine::Joint& j, double v, const char* limit) {
    if (j.within(v)) return;
    add(std::string(limit) + (v < j.min ? " min" : " max"),
        j.name + " " + fmt(v) + " outside its range [" + fmt(j.min) + ", " + fmt(j.max) + "]");
  };
  if (m.known_rotary & 1) within(*a, m.a_to, "rotary a");
  if (m.known_rotary & 2) within(*c, m.c_to, "rotary c");
}

// The extent of a move along each axis the controller knows: its end points, and for an arc the quadrant points
// it sweeps through.
void move_extent(const CanonMove& m, double lo[3], double hi[3], bool any[3]) {
  for (int a = 0; a < 3; ++a) {
    const bool to = m.known_to >> a & 1, from = m.known_from >> a & 1;
    lo[a] = INFINITY;
    hi[a] = -INFINITY;
    if (to) lo[a] = hi[a] = m.to[a];
    if (from) {
      lo[a] = std::min(lo[a], m.from[a]);
      hi[a] = std::max(hi[a], m.from[a]);
    }
    any[a] = to || from;
  }
  if (!m.is_arc()) return;
  Vec2 min, max;
  move_xy_bounds(m, min, max);
  for (int k = 0; k < 2; ++k) {
    lo[k] = std::min(lo[k], min[k]);
    hi[k] = std::max(hi[k], max[k]);
  }
}

// The move's extent in machine coordinates: its program extent through the work offset. Turned, the extent's
// corners are turned (for an arc a little more than it sweeps: the check errs on the safe side); an axis is known
// in the machine only when every program axis it mixes is known.
void machine_extent(const CanonMove& m, const WorkOffset& w, double lo[3], double hi[3], bool any[3]) {
  move_extent(m, lo, hi, any);
  if (w.rotation_deg != 0.0 && (any[0] || any[1])) {
    const bool xy = any[0] && any[1];
    const Eigen::Rotation2Dd turn(w.rotation_deg * M_PI / 180.0);
    double mlo[2] = {INFINITY, INFINITY}, mhi[2] = {-INFINITY, -INFINITY};
    if (xy)
      for (int c = 0; c < 4; ++c) {
        const Vec2 corner = turn * Vec2(c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1]);
        for (int a = 0; a < 2; ++a) {
          mlo[a] = std::min(mlo[a], corner[a]);
          mhi[a] = std::max(mhi[a], corner[a]);
        }
      }
    for (int a = 0; a < 2; ++a) {
      lo[a] = mlo[a];
      hi[a] = mhi[a];
      any[a] = xy;
    }
  }
  for (int a = 0; a < 3; ++a) {
    lo[a] += w.origin[a];
    hi[a] += w.origin[a];
  }
}

// With tool-centre-point control LinuxCNC limits the speeds of the program's axes (the tip on the table, A, C) but
// not of the machine's joints, which the turning table can drive several times faster (checked on its xyzac-trt
// simulator: 47 mm/s on a 20 mm/s joint, without a word). The move's time is what the program asks (its length at
// its feed; for a rapid, the slowest program axis at its limit), each joint's speed its path over that time.
template <class Add>
void check_joint_speeds(const MachineLimits& lim, const CanonMove& m, const Vec3& travel, Add&& add) {
  const TrajectoryLimits& tl = lim.trajectory;
  const double length = (m.to - m.from).norm();
  const double turn = std::hypot(m.a_to - m.a_from, m.c_to - m.c_from);
  double seconds = 0;
  if (m.rapid) {
    for (int a = 0; a < 3; ++a)
      if (tl.max_velocity[a] > 0) seconds = std::max(seconds, std::abs(m.to[a] - m.from[a]) / tl.max_velocity[a]);
    const double turns[2] = {std::abs(m.a_to - m.a_from), std::abs(m.c_to - m.c_from)};
    for (int r = 0; r < 2; ++r)
      if (tl.rotary_velocity[r] > 0) seconds = std::max(seconds, turns[r] / tl.rotary_velocity[r]);
  } else if (m.feed > 0) {
    seconds = 60.0 * (length > 0 ? length : turn) / m.feed;
  }
  if (!(seconds > 0)) return;
  for (int a = 0; a < 3; ++a) {
    if (!(tl.max_velocity[a] > 0)) continue;
    const double speed = travel[a] / seconds;
    if (speed > tl.max_velocity[a] * (1 + 1e-3) + 1e-9)
      add(std::string("joint ") + "xyz"[a] + " speed",
          "the table's turn drives machine " + std::string(1, "xyz"[a]) + " at " + fmt(speed) + " mm/s, over its " +
              fmt(tl.max_velocity[a]) + " mm/s (slow the move: an inverse-time feed, G93)");
  }
}

}  // namespace

std::vector<LimitViolation> check_limits(const std::vector<std::string>& lines, const MachineLimits& lim,
                                         const LimitCheckOptions& o) {
  std::vector<LimitViolation> out;
  auto add = [&](size_t line, std::string limit, std::string detail) {
    out.push_back({line + 1, std::move(limit), std::move(detail), lines[line]});
  };
  // First pass: the moves, and the stock top when it is not given.
  std::vector<Step> steps;
  Interpreter reader;
  std::vector<double> tops = {-INFINITY};  // per run: the highest cutting move across the part
  KnownOffsets known;
  known[0] = lim.work_offset;
  bool tcp = false;
  const std::shared_ptr<const machine::Machine> machine = lim.machine();
  for (size_t i = 0; i < lines.size(); ++i) {
    const int offset_before = reader.state().work_offset;
    reader.read(lines[i], i + 1);
    if (reader.block().has_m(428)) {
      // Refused on a machine without tool-centre-point control; its moves are then checked as they read.
      if (!machine->simultaneous())
        add(i, "kinematics",
            "M428 switches to tool-centre-point kinematics, which the machine '" + lim.name +
                "' is not set up for (rotary.mode: tool-centre-point)");
      else
        tcp = true;
    }
    if (reader.block().has_m(429)) tcp = false;
    if (const std::optional<WorkOffset> set = followed_work_offset(reader)) known[set->index - 1] = *set;
    refuse_unfollowed(reader, offset_before, known, [&](std::string limit, std::string detail) {
      add(i, std::move(limit), std::move(detail));
    });
    const ModalState& s = reader.state();
    const int index = offset_index(s.work_offset);
    // A system the checker does not know was refused above; the moves are then checked as if in G54.
    const WorkOffset offset = index > 0 && known[index - 1] ? *known[index - 1] : *known[0];
    if (machine_move(reader)) {
      // G53: the machine position along the axes given (the reader's program position there becomes unknown).
      CanonMove m;
      m.rapid = s.motion == 0;
      const double unit = s.metric ? 1.0 : 25.4;
      m.known_from = 0;
      m.known_to = 0;
      for (int a = 0; a < 3; ++a)
        if (reader.block().has("XYZ"[a])) {
          m.to[a] = reader.block().get("XYZ"[a]) * unit;
          m.known_to |= uint8_t(1 << a);
        }
      steps.push_back({i, true, m, true, s.feed, s.spindle_rpm, s.spindle, offset, tops.size() - 1, tcp});
      continue;
    }
    // An indexing turns the part: the stock's top is another side's from here on (with tool-centre-point control
    // the program's coordinates stay the table's).
    if (reader.moved() && reader.move().indexes() && !tcp) tops.push_back(-INFINITY);
    steps.push_back(
        {i, reader.moved(), reader.move(), false, s.feed, s.spindle_rpm, s.spindle, offset, tops.size() - 1, tcp});
    // Cutting moves across the part (not plunges or feed retracts) run inside the stock. Under tool-centre-point
    // control every move is an inverse-time feed, the ones that position the tool over the part too: they tell
    // nothing of the stock (give it: LimitCheckOptions::stock_top).
    const CanonMove& m = reader.move();
    if (reader.moved() && !m.rapid && !(tcp && s.feed_mode == 93) && (m.known_to & 4) &&
        (m.to.x() != m.from.x() || m.to.y() != m.from.y()))
      tops.back() = std::max(tops.back(), m.to.z());
  }
  static const char* axis = "xyz";
  for (const Step& st : steps) {
    const CanonMove& m = st.move;
    if (st.rpm > lim.max_spindle_rpm && st.spindle != 5)
      add(st.line, "max spindle speed", "S" + fmt(st.rpm) + " rpm over " + fmt(lim.max_spindle_rpm));
    if (!st.moved) continue;
    // The feed along the tool tip's path (an inverse-time move's is its F times its length; a move of the rotary
    // axes alone has none in mm/min).
    if (!m.rapid && m.feed > lim.max_feed * (1 + 1e-6) && (m.to - m.from).squaredNorm() > 0)
      add(st.line, "max feed", "F" + fmt(m.feed) + " mm/min over " + fmt(lim.max_feed));
    double lo[3], hi[3];
    bool any[3];
    machine_extent(m, st.machine_coordinates ? WorkOffset{} : st.offset, lo, hi, any);
    check_rotary(lim, *machine, m, st.tcp, [&](std::string limit, std::string detail) { add(st.line, limit, detail); });
    double lowest_on_table = INFINITY;
    if (st.tcp && !st.machine_coordinates) {
      if (m.is_arc()) add(st.line, "unchecked move", "an arc in tool-centre-point kinematics is not followed");
      const bool turns = m.indexes();
      if ((m.known_to & 7) == 7 && (m.known_rotary & 3) == 3 && ((m.known_from & 7) == 7 || !turns)) {
        // With A and C held the joints move along a straight line (a fixed turn of the table is affine): a move
        // from an unknown place is followed from its end, as in identity kinematics.
        CanonMove known = m;
        if ((m.known_from & 7) != 7) known.from = m.to;
        // The joints along the move (the chain's curve), the tip's lowest on the table at an end (it moves straight).
        const machine::JointSweep joints =
            machine::sweep_joints(*lim.trunnion, st.offset.to_machine(known.from), st.offset.to_machine(known.to),
                                  {known.a_from, known.c_from}, {known.a_to, known.c_to});
        for (int a = 0; a < 3; ++a) lo[a] = joints.lo[a], hi[a] = joints.hi[a];
        lowest_on_table = std::min(st.offset.to_machine(known.from).z(), st.offset.to_machine(known.to).z());
        any[0] = any[1] = any[2] = true;
        check_joint_speeds(lim, known, joints.travel, [&](std::string limit, std::string detail) {
          add(st.line, std::move(limit), std::move(detail));
        });
      } else {
        add(st.line, "unchecked move",
            "in tool-centre-point kinematics a move that turns A or C must start and end "
            "at known X, Y, Z, A and C (the joints cannot be followed otherwise)");
      }
    }
    for (int a = 0; a < 3; ++a) {
      if (!any[a]) continue;
      const double mlo = lo[a], mhi = hi[a];
      if (mlo < lim.envelope.min[a] - 1e-9)
        add(st.line, std::string("envelope ") + axis[a] + " min",
            "machine " + std::string(1, axis[a]) + " " + fmt(mlo) + " below the soft limit " + fmt(lim.envelope.min[a]));
      if (mhi > lim.envelope.max[a] + 1e-9)
        add(st.line, std::string("envelope ") + axis[a] + " max",
            "machine " + std::string(1, axis[a]) + " " + fmt(mhi) + " above the soft limit " + fmt(lim.envelope.max[a]));
    }
    if (st.tcp && !st.machine_coordinates) {
      if (lowest_on_table < lim.table_z - 1e-9)
        add(st.line, "table", "tool tip " + fmt(lim.table_z - lowest_on_table) + " mm below the table's top");
    } else if (lim.trunnion && (m.known_to & 7) == 7 && !st.machine_coordinates) {
      // On a trunnion the table turns: the tool tip is checked against its top in the table's own frame, below
      // which it is inside the table (or behind it) at whatever turn.
      const Vec3 tip = lim.trunnion->table_point(st.offset.to_machine(m.to), m.a_to, m.c_to);
      if (tip.z() < lim.table_z - 1e-9)
        add(st.line, "table", "tool tip " + fmt(lim.table_z - tip.z()) + " mm below the turned table's top (A " +
                                  fmt(m.a_to) + ", C " + fmt(m.c_to) + ")");
    } else if (!lim.trunnion && any[2] && lo[2] < lim.table_z - 1e-9) {
      add(st.line, "table", "tool tip at machine z " + fmt(lo[2]) + " below the table top " +
                                fmt(lim.table_z));
    }
    const double stock_top = std::isnan(o.stock_top) ? tops[st.run] : o.stock_top;
    const double rapid_floor = stock_top + lim.clearance_over_stock;
    if (m.rapid && !o.rapids_checked_by_stock && std::isfinite(stock_top) && (m.known_to & 4)) {
      // A rapid ends above the clearance; one that travels sideways must also start there.
      const bool sideways = m.to.x() != m.from.x() || m.to.y() != m.from.y();
      const double low = sideways && (m.known_from & 4) ? std::min(m.from.z(), m.to.z()) : m.to.z();
      if (low < rapid_floor - 1e-9)
        add(st.line, "rapid clearance", "rapid at z " + fmt(low) + " below the stock top " + fmt(stock_top) + " + " +
                                            fmt(lim.clearance_over_stock) + " mm clearance");
    }
  }
  // By line, the checks in their order within a line; at most max_violations.
  std::stable_sort(out.begin(), out.end(), [](const LimitViolation& a, const LimitViolation& b) { return a.line < b.line; });
  if (out.size() > o.max_violations) out.resize(o.max_violations);
  return out;
}

void require_within_limits(const std::vector<std::string>& lines, const MachineLimits& lim, const LimitCheckOptions& o) {
  const auto v = check_limits(lines, lim, o);
  if (v.empty()) return;
  std::string more = v.size() > 1 ? " (and " + std::to_string(v.size() - 1) + " more)" : "";
  throw Error("line " + std::to_string(v.front().line), "refused by machine '" + lim.name + "': " + v.front().message() + more);
}

}  // namespace rosmill::core::gcode
