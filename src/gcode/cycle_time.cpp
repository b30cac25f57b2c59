#include "rosmill/gcode/cycle_time.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <optional>

#include "rosmill/error.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/toolpath/toolpath_stats.hpp"

namespace rosmill::core::gcode {
namespace {

// The planner's constants (LinuxCNC 2.9, blendmath.h and tp.c).
constexpr double kTangentialShare = 0.5;  // of the acceleration an arc keeps along its path at its speed limit
const double kNormalShare = std::sqrt(1.0 - kTangentialShare * kTangentialShare);
constexpr double kBlendLengthShare = 0.5;  // a blend arc takes at most half of each segment it joins
constexpr double kToleranceShare = 0.25;   // and deviates at most a quarter of either one's length
constexpr double kMinBlendArc = 1e-6;      // mm: a shorter blend arc is not made (the corner blends parabolically)

// One canonical move as the planner takes it in: its path length, the unit tangents where it starts and ends,
// what it asks for and what the machine allows along it.
struct Element {
  double length = 0;
  Vec3 start_dir = Vec3::Zero(), end_dir = Vec3::Zero();
  bool rapid = false, arc = false;
  bool turns = false;  // the rotary axes turn along it (tool-centre-point control): blended parabolically
  double v_req = 0, v_max = 0, a_max = 0;  // mm/s, mm/s, mm/s^2 along the path
  // Arcs: the plane's normal, the radius, the feed and the axes' own limits (before the normal acceleration's share).
  Vec3 normal = Vec3::Zero();
  double radius = 0, feed = 0, v_axes = 0, a_axes = 0;
};

struct ArcLimits {
  double v_max, a_tangential;
};

// The normal acceleration v^2 / R takes its share of the acceleration `a` (pmCircleActualMaxVel): at the speed that
// needs the normal share the arc keeps the tangential share; slower, what is left of the whole.
ArcLimits arc_limits(double v_axes, double a, double radius) {
  const double v_cut = std::sqrt(kNormalShare * a * radius);
  if (v_axes > v_cut) return {v_cut, a * kTangentialShare};
  const double an = v_axes * v_axes / radius / a;
  return {v_axes, std::isfinite(a) ? a * std::sqrt(std::max(0.0, 1.0 - an * an)) : INFINITY};
}

// A segment of the planner's queue: a move (less what blends took of it) or a blend arc.
struct Segment {
  double length = 0, v_max = 0, a = 0;
  double end_cap = 0;   // the highest speed at its end: 0 where the machine stops
  double overlap = 0;   // seconds the next segment runs while this one ends (a parabolic blend)
};

// The limit of a quantity along unit direction u when each axis has its own (zero: none): the least of
// limit_i / |u_i| over the moving axes (each axis's share stays within its own limit).
double along(const Vec3& u, const Vec3& axis_limit, double path_limit) {
  double v = path_limit > 0 ? path_limit : INFINITY;
  for (int i = 0; i < 3; ++i)
    if (axis_limit[i] > 0 && std::abs(u[i]) > 1e-12) v = std::min(v, axis_limit[i] / std::abs(u[i]));
  return v;
}

// The limit in the plane normal to `n` (blendmath's inscribed diameter): the least over the axes of limit_i over
// the length of that axis's projection into the plane.
double in_plane(const Vec3& n, const Vec3& axis_limit) {
  double v = INFINITY;
  for (int i = 0; i < 3; ++i) {
    if (!(axis_limit[i] > 0)) continue;
    const double s = std::sqrt(std::max(1e-12, 1.0 - n[i] * n[i]));
    v = std::min(v, axis_limit[i] / s);
  }
  return v;
}

Element line_element(const CanonMove& m, const TrajectoryLimits& lim) {
  Element e;
  Vec3 d = m.to - m.from;
  for (int i = 0; i < 3; ++i)
    if (!(m.known_from >> i & 1)) d[i] = 0;  // an axis the program has not placed yet: its travel is unknown
  e.length = d.norm();
  e.rapid = m.rapid;
  if (e.length <= 0) return e;
  const Vec3 u = d / e.length;
  e.start_dir = e.end_dir = u;
  e.v_max = along(u, lim.max_velocity, lim.max_linear_velocity);
  e.a_max = along(u, lim.max_acceleration, lim.max_linear_acceleration);
  e.v_req = m.rapid ? e.v_max : std::min<double>(m.feed / 60.0, e.v_max);
  return e;
}

Element arc_element(const CanonMove& m, const TrajectoryLimits& lim) {
  Element e;
  e.arc = true;
  const PlaneAxes ax = plane_axes(m.plane);
  const Vec2 from(m.from[ax.first], m.from[ax.second]), to(m.to[ax.first], m.to[ax.second]);
  const Vec2 r0 = from - m.centre, r1 = to - m.centre;
  const double radius = r0.norm();
  double sweep = std::atan2(r0.x() * r1.y() - r0.y() * r1.x(), r0.dot(r1));  // counter-clockwise, (-pi, pi]
  if (m.clockwise()) sweep = -sweep;
  if (sweep <= 1e-9) sweep += 2 * M_PI;
  sweep += 2 * M_PI * std::max(0, int(m.turns) - 1);
  const double planar = radius * sweep, rise = m.to[ax.normal] - m.from[ax.normal];
  e.length = std::hypot(planar, rise);
  if (e.length <= 0 || radius <= 0) return e;
  const double sense = m.clockwise() ? -1.0 : 1.0;
  auto tangent = [&](const Vec2& r) {
    Vec3 t = Vec3::Zero();
    t[ax.first] = -sense * r.y() / radius * planar / e.length;
    t[ax.second] = sense * r.x() / radius * planar / e.length;
    t[ax.normal] = rise / e.length;
    return t;
  };
  e.start_dir = tangent(r0);
  e.end_dir = tangent(r1);
  // Each axis of the plane (and the helix's when it moves) bounds the speed and acceleration along the arc.
  Vec3 mask = Vec3::Zero();
  mask[ax.first] = mask[ax.second] = 1;
  if (std::abs(rise) > 1e-9) mask[ax.normal] = 1;
  double v_axes = lim.max_linear_velocity > 0 ? lim.max_linear_velocity : INFINITY, a = INFINITY;
  for (int i = 0; i < 3; ++i) {
    if (!mask[i]) continue;
    if (lim.max_velocity[i] > 0) v_axes = std::min(v_axes, lim.max_velocity[i]);
    if (lim.max_acceleration[i] > 0) a = std::min(a, lim.max_acceleration[i]);
  }
  const ArcLimits l = arc_limits(v_axes, a, radius);
  e.v_max = l.v_max;
  e.a_max = l.a_tangential;
  e.v_req = std::min<double>(m.feed / 60.0, e.v_max);
  e.normal[ax.normal] = 1;
  e.radius = radius;
  e.feed = m.feed / 60.0;
  e.v_axes = v_axes;
  e.a_axes = a;
  return e;
}

// How two moves meet under G64 P `tolerance` (0: exact path or exact stop, the machine stops).
struct Junction {
  enum Kind { Stop, Parabolic, Tangent, Arc } kind = Stop;
  double cap = 0;                    // speed where they meet (tangent) or through the blend arc
  double trim_prev = 0, trim_next = 0;  // what the blend arc takes of each
  double arc_length = 0, arc_a = 0;
  double overlap = 0;                // parabolic: seconds both run
};

// tpComputeBlendVelocity: the speed below which the first move hands over to the next while it brakes, both at
// half their acceleration; the time they then run together.
double parabolic_overlap(const Element& p, const Element& n, double p_length, double tolerance) {
  const double a_p = p.a_max * 0.5, a_n = n.a_max * 0.5;
  const double v_p = std::min(std::sqrt(a_p * p_length), p.v_req), v_n = std::min(std::sqrt(a_n * n.length), n.v_req);
  if (!(v_p > 0) || !(v_n > 0)) return 0;
  const double t_reach = std::min(p_length / v_p, n.length / v_n);
  const double t_blend = std::min(t_reach, std::max(v_p / a_p, v_n / a_n));
  double v_blend = std::min(v_p, t_blend * a_p);
  const double theta = std::acos(std::clamp(-p.end_dir.dot(n.start_dir), -1.0, 1.0)) / 2;
  if (tolerance > 0 && std::cos(theta) > 1e-6) v_blend = std::min(v_blend, 2 * std::sqrt(a_p * tolerance / std::cos(theta)));
  return std::isfinite(a_p) ? v_blend / a_p : 0;
}

Junction junction(const Element& p, double p_remaining, const Element& n, double tolerance,
                  const TrajectoryLimits& lim) {
  Junction j;
  if (!(tolerance > 0) || p.length <= 0 || n.length <= 0) return j;
  // tpCheckCanonType: a rapid meeting a feed blends parabolically; so does a line meeting an arc out of its plane
  // (a plunge into a circle), for which no blend arc exists.
  const auto out_of_plane = [](const Element& arc, const Element& other) {
    if (!arc.arc) return false;
    return other.arc ? arc.normal.cross(other.normal).norm() > 1e-3 : std::abs(arc.normal.dot(other.end_dir)) > 1e-3;
  };
  if (p.rapid != n.rapid || p.turns || n.turns || out_of_plane(p, n) || out_of_plane(n, p)) {
    j.kind = Junction::Parabolic;
    j.overlap = parabolic_overlap(p, n, p_remaining, tolerance);
    return j;
  }
  // tpSetupTangent: the jump of acceleration the change of direction asks within one servo period at full speed,
  // against each axis's limit; gentle enough, the corner is taken as tangent.
  const double v = std::min(p.v_req, n.v_req);
  const Vec3 jump = (n.start_dir - p.end_dir) * (v / lim.servo_period);
  double scale = 0;
  for (int i = 0; i < 3; ++i)
    if (lim.max_acceleration[i] > 0) scale = std::max(scale, std::abs(jump[i]) / lim.max_acceleration[i]);
  if (p.arc || n.arc) scale /= kTangentialShare;
  if (!lim.limited() || scale < lim.tangent_kink_ratio) {
    j.kind = Junction::Tangent;
    j.cap = std::min(p.v_max, n.v_max);
    return j;
  }
  const double theta = std::acos(std::clamp(-p.end_dir.dot(n.start_dir), -1.0, 1.0)) / 2;
  if (!lim.arc_blend || theta < 1e-6 || M_PI / 2 - theta < 1e-9) {
    j.kind = Junction::Parabolic;
    j.overlap = parabolic_overlap(p, n, p_remaining, tolerance);
    return j;
  }
  // blendComputeParameters: the blend arc's largest radius within the tolerance and the lengths it may take, the
  // speed its normal acceleration allows there, and the radius that speed needs.
  const double t = std::min({tolerance, p.length * kToleranceShare, n.length * kToleranceShare});
  const double l1 = std::min(p_remaining, p.length * kBlendLengthShare), l2 = n.length * kBlendLengthShare;
  const Vec3 binormal = p.end_dir.cross(n.start_dir).normalized();
  const double a_max = in_plane(binormal, lim.max_acceleration), a_n = a_max * kNormalShare;
  const double v_goal = std::min(std::max(p.v_req, n.v_req) * lim.max_feed_override, in_plane(binormal, lim.max_velocity));
  const double d_tol = std::cos(theta) * t / (1 - std::sin(theta));
  const double d_geom = std::min({l1, l2, d_tol});
  const double r_geom = std::tan(theta) * d_geom;
  const double v_plan = std::min(std::sqrt(a_n * r_geom), v_goal);
  const double phi = M_PI - 2 * theta;
  const double a_par = a_max * 0.5;
  const double t_blend = std::min(std::sqrt(2 * a_par * d_geom), v_plan) / a_par;
  const double r_blend = std::min(t_blend * v_plan / phi, r_geom);
  const double r_plan = std::max(v_plan * v_plan / a_n, r_blend);
  j.arc_length = r_plan * phi;
  if (!(r_plan > 1e-12) || j.arc_length < kMinBlendArc) {
    j.kind = Junction::Parabolic;
    j.overlap = parabolic_overlap(p, n, p_remaining, tolerance);
    return j;
  }
  j.kind = Junction::Arc;
  j.trim_prev = j.trim_next = r_plan / std::tan(theta);
  j.cap = std::min({v_plan, std::max(p.v_req, n.v_req), j.arc_length / lim.servo_period});
  j.arc_a = a_max * kTangentialShare;
  return j;
}

// A velocity profile over one segment from v0 to v1 (trapezoid, or triangle when the top speed is not reached).
double segment_seconds(double length, double v0, double v1, double v_max, double a) {
  if (length <= 0) return 0;
  if (!std::isfinite(a)) return length / v_max;
  const double v_top = std::min(v_max, std::sqrt(std::max(0.0, a * length + 0.5 * (v0 * v0 + v1 * v1))));
  if (!(v_top > 0)) return 0;
  const double ramps = (2 * v_top * v_top - v0 * v0 - v1 * v1) / (2 * a);
  return (v_top - v0) / a + (v_top - v1) / a + std::max(0.0, length - ramps) / v_top;
}

// The planner's queue for moves between two stops.
std::vector<Segment> queue(const std::vector<Element>& moves, const std::vector<double>& tolerance,
                           const TrajectoryLimits& lim) {
  std::vector<Segment> out;
  double trim_start = 0;
  bool halve_start = false;
  for (size_t k = 0; k < moves.size(); ++k) {
    const Element& e = moves[k];
    const double remaining = std::max(0.0, e.length - trim_start);
    Junction j;
    if (k + 1 < moves.size()) j = junction(e, remaining, moves[k + 1], tolerance[k], lim);
    Segment s;
    s.length = std::max(0.0, remaining - j.trim_prev);
    const bool parabolic = j.kind == Junction::Parabolic;
    double v_req = e.v_req, a = e.a_max;
    if (halve_start || parabolic) {  // tpGetScaledAccel: half the acceleration where a parabolic blend overlaps
      if (e.arc) {  // an arc's speed limit is then that of half its acceleration (tcFinalizeLength)
        const ArcLimits l = arc_limits(e.v_axes, e.a_axes * 0.5, e.radius);
        v_req = std::min(e.feed, l.v_max);
        a = l.a_tangential;
      } else {
        a *= 0.5;
      }
    }
    s.v_max = std::min(v_req, e.length / lim.servo_period);  // tcClampVelocityByLength: a period at least
    s.a = a;
    s.overlap = j.overlap;
    if (j.kind == Junction::Tangent) s.end_cap = std::min(j.cap, s.v_max);
    if (j.kind == Junction::Arc) s.end_cap = std::min(j.cap, s.v_max);
    out.push_back(s);
    if (j.kind == Junction::Arc) {
      Segment b;
      b.length = j.arc_length;
      b.v_max = j.cap;
      b.a = j.arc_a;
      b.end_cap = std::min(j.cap, std::min(moves[k + 1].v_req, moves[k + 1].length / lim.servo_period));
      out.push_back(b);
    }
    trim_start = j.trim_next;
    halve_start = parabolic;
  }
  return out;
}

// The look-ahead (tpRunOptimization) and the run: each segment's end speed is what still lets the machine stop by
// the end of the last segment the optimizer sees from it; the machine accelerates as far as that allows.
double run_seconds(std::vector<Segment>& q, int depth) {
  const size_t n = q.size();
  std::vector<double> v_end(n, 0.0);
  const size_t window = std::max(1, depth);
  for (size_t k = 0; k < n; ++k) {
    const size_t last = std::min(n - 1, k + window - 1);
    double v = 0;  // at the end of `last`
    for (size_t i = last; i > k; --i) v = std::min(q[i - 1].end_cap, std::sqrt(v * v + 2 * q[i].a * q[i].length));
    v_end[k] = last == k ? 0.0 : v;
    if (k + 1 == n) v_end[k] = 0;
  }
  double t = 0, v0 = 0;
  for (size_t k = 0; k < n; ++k) {
    const Segment& s = q[k];
    const double v1 = std::min(v_end[k], std::sqrt(v0 * v0 + 2 * s.a * s.length));
    t += segment_seconds(s.length, std::min(v0, s.v_max), std::min(v1, s.v_max), s.v_max, s.a) - s.overlap;
    v0 = v1;
  }
  return t;
}

// A move of the rotary axes alone (indexing a trunnion), from rest to rest: its length in degrees.
double rotary_seconds(const CanonMove& m, const TrajectoryLimits& lim) {
  const Vec3 d(m.a_to - m.a_from, m.c_to - m.c_from, 0);
  const double length = d.norm();
  if (length <= 0) return 0;
  double v = along(d / length, Vec3(lim.rotary_velocity.x(), lim.rotary_velocity.y(), 0), 0);
  if (!std::isfinite(v)) return 0;  // a machine file without rotary limits: not timed
  if (!m.rapid && m.feed > 0) v = std::min(v, m.feed / 60.0);  // a feed of the rotary axes alone: degrees/min
  return move_seconds(length, d / length, 60 * v,
                      Vec3(lim.rotary_acceleration.x(), lim.rotary_acceleration.y(), 0));
}

// A move of the linear and the rotary axes together (tool-centre-point control): a line of the tip on the table,
// whose speed and acceleration each rotary axis bounds too (its degrees per millimetre of the tip). LinuxCNC makes
// no blend arc for it (tcCanUseArcBlend wants the linear axes alone): it blends parabolically (junction()).
Element simultaneous_element(const CanonMove& m, const TrajectoryLimits& lim) {
  Element e = line_element(m, lim);
  e.turns = true;
  if (e.length <= 1e-9) return e;
  const double rate[2] = {std::abs(m.a_to - m.a_from) / e.length, std::abs(m.c_to - m.c_from) / e.length};
  for (int r = 0; r < 2; ++r) {
    if (!(rate[r] > 0)) continue;
    if (lim.rotary_velocity[r] > 0) e.v_max = std::min(e.v_max, lim.rotary_velocity[r] / rate[r]);
    if (lim.rotary_acceleration[r] > 0) e.a_max = std::min(e.a_max, lim.rotary_acceleration[r] / rate[r]);
  }
  e.v_req = std::min(e.v_req, e.v_max);
  return e;
}

// The program as the planner receives it: runs of moves between stops.
class Timer {
 public:
  explicit Timer(const TrajectoryLimits& lim) : lim_(lim) {}

  void stop() {
    if (moves_.empty()) return;
    std::vector<Segment> q = queue(moves_, tolerance_, lim_);
    result_.segments += q.size();
    result_.motion_seconds += run_seconds(q, lim_.optimization_depth);
    ++result_.stops;
    moves_.clear();
    tolerance_.clear();
  }
  void wait(double seconds) { result_.seconds += std::max(0.0, seconds); }
  void blend(double tolerance) { tolerance_now_ = tolerance; }
  // The program's G54 origin on the machine (G10 L2): where the tool change position lies in its coordinates.
  void origin(const Vec3& machine) { origin_ = machine; }

  // M6: the machine stops, moves the tool to the tool change position in one rapid, changes it; the next move
  // starts there.
  void tool_change(const Vec3& at) {
    stop();
    if (lim_.has_tool_change_position) {
      CanonMove to_change;
      to_change.from = at;
      to_change.to = lim_.tool_change_position - origin_;
      to_change.rapid = true;
      move(to_change);
      stop();
      start_ = to_change.to;
    }
    wait(lim_.tool_change_seconds);
  }
  // M3/M4 at `rpm` (after the moves before it): the spindle accelerates while the next rapids run; the first feed
  // move waits until it is at speed.
  void spindle(double rpm) {
    stop();
    wait(lim_.spindle_start_seconds);
    if (lim_.spindle_acceleration > 0 && rpm > rpm_)
      at_speed_ = now() + (lim_.spindle_at_speed_share * rpm - rpm_) / lim_.spindle_acceleration;
    rpm_ = rpm;
  }
  // A move in machine coordinates (G53): to `machine` less the G54 origin and, in Z, the tool length offset in
  // force (G43 made the program's Z the tip's, `length` below the spindle's). The reader leaves its axes unknown;
  // the next move starts where it ends.
  void machine_move(const Vec3& from, const Vec3& machine, const bool given[3], bool rapid, double feed,
                    double length) {
    CanonMove m;
    m.from = from;
    m.to = from;
    for (int i = 0; i < 3; ++i)
      if (given[i]) m.to[i] = machine[i] - origin_[i] - (i == 2 ? length : 0.0);
    m.rapid = rapid;
    m.feed = float(feed);
    move(m);
    start_ = m.to;
  }
  void spindle_stop() {
    stop();
    rpm_ = 0;
  }
  void move(const CanonMove& given) {
    CanonMove m = given;
    if (start_) {
      m.from = *start_;
      m.known_from = 7;
      start_.reset();
    }
    // An axis the reader has lost (after a G53 move) but this timer followed: from where that move left it, and
    // there still where the move does not name it.
    for (int i = 0; i < 3; ++i) {
      const uint8_t bit = uint8_t(1u << i);
      if (!(held_known_ & bit)) continue;
      if (!(m.known_from & bit)) m.from[i] = held_[i], m.known_from |= bit;
      if (!(m.known_to & bit)) m.to[i] = m.from[i], m.known_to |= bit;
    }
    for (int i = 0; i < 3; ++i)
      if (m.known_to >> i & 1) held_[i] = m.to[i], held_known_ |= uint8_t(1u << i);
    const bool tip_moves = m.from_known() && (m.to - m.from).squaredNorm() > 1e-18;
    if (m.indexes() && !tip_moves) {  // the rotary axes alone (an indexing, a turn in place): from rest to rest
      stop();
      result_.motion_seconds += rotary_seconds(m, lim_);
      return;
    }
    const Element e = m.indexes()  ? simultaneous_element(m, lim_)
                      : m.is_arc() ? arc_element(m, lim_)
                                   : line_element(m, lim_);
    if (e.length <= 1e-9) return;  // the planner drops a move that goes nowhere
    if (!m.rapid && at_speed_ > 0) {  // the planner holds the first feed move until the spindle is at speed
      stop();
      wait(at_speed_ - now());
      at_speed_ = 0;
    }
    moves_.push_back(e);
    tolerance_.push_back(tolerance_now_);
  }
  CycleTime finish() {
    stop();
    result_.seconds += result_.motion_seconds;
    return result_;
  }

 private:
  double now() const { return result_.seconds + result_.motion_seconds; }  // of the moves planned so far

  const TrajectoryLimits& lim_;
  std::vector<Element> moves_;
  std::vector<double> tolerance_;  // G64 P in force at each move's end
  double tolerance_now_ = 0;       // exact stop until the program sets G64
  Vec3 origin_ = Vec3::Zero();
  std::optional<Vec3> start_;      // where the next move starts when the reader cannot know (after a tool change)
  Vec3 held_ = Vec3::Zero();       // the position as far as the timer knows it, for the axes in held_known_
  uint8_t held_known_ = 0;
  double rpm_ = 0, at_speed_ = 0;
  CycleTime result_;
};

bool has_any_m(const Block& b, std::initializer_list<int> codes) {
  for (int c : codes)
    if (b.has_m(c)) return true;
  return false;
}

}  // namespace

CycleTime estimate_cycle_time(const std::vector<std::string>& program, const TrajectoryLimits& limits,
                              const std::string& source) {
  Interpreter in(source);
  Timer timer(limits);
  for (size_t k = 0; k < program.size(); ++k) {
    const Vec3 before = in.state().position;
    const Block& b = in.read(program[k], k + 1);
    // What the block does before it moves (RS274/NGC's order of execution): these wait for the motion queue.
    if (has_any_m(b, {7, 8, 9}) || b.has_g(40) || b.has_g(430) || b.has_g(490) || b.has_g(100))
      timer.stop();
    if (b.has_m(6)) timer.tool_change(in.state().position);
    if (b.has_m(3) || b.has_m(4)) timer.spindle(in.state().spindle_rpm);
    if (b.has_m(5)) timer.spindle_stop();
    if (b.has_g(40)) timer.wait(b.get('P'));
    // G10 L2 P1 (or P0 while G54 is in force): the G54 origin the program sets on the machine.
    if (b.has_g(100) && b.get('L') == 2 && (b.get('P') == 1 || (b.get('P') == 0 && in.state().work_offset == 54)))
      timer.origin(Vec3(b.has('X') ? b.get('X') : 0, b.has('Y') ? b.get('Y') : 0, b.has('Z') ? b.get('Z') : 0));
    if (b.has_g(610) || b.has_g(611)) timer.blend(0);
    if (b.has_g(640)) timer.blend(b.has('P') ? b.get('P') : 1e9);  // G64 alone: as fast as the corners allow
    if (in.moved()) timer.move(in.move());
    if (b.has_g(530) && b.has_linear()) {
      const bool given[3] = {b.has('X'), b.has('Y'), b.has('Z')};
      const Vec3 to(given[0] ? b.get('X') : 0, given[1] ? b.get('Y') : 0, given[2] ? b.get('Z') : 0);
      const int h = in.state().length_offset;
      timer.machine_move(before, to, given, in.state().motion == 0, in.state().feed,
                         h >= 0 ? limits.tool_length(h) : 0.0);
    }
    if (in.state().ended) break;
  }
  return timer.finish();
}

CycleTime estimate_cycle_time(const Job& job, const PostOptions& post_options, const TrajectoryLimits& limits) {
  return estimate_cycle_time(post(job, post_options).lines, limits, "the posted job");
}

}  // namespace rosmill::core::gcode
