#include "rosmill/gcode/post.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <fstream>

#include "rosmill/error.hpp"
#include "rosmill/input_file.hpp"
#include "rosmill/gcode/arc_fit.hpp"
#include "rosmill/gcode/comment_text.hpp"
#include "rosmill/gcode/number_format.hpp"

namespace rosmill::core::gcode {
namespace {

constexpr int kFeedDecimals = 1;
constexpr int kSpeedDecimals = 0;
constexpr int kAngleDecimals = 4;  // degrees: 1e-4 degrees moves a point 0.2 m away by 0.35 um
constexpr int kInverseTimeDecimals = 3;  // G93 F (1/min), rounded down: the move never runs faster than planned

// Writes blocks and remembers the modal state the controller is in, so that only changed words are written.
class Writer {
 public:
  Writer(const Dialect& d, const PostOptions& o, Program& p) : dialect_(d), opt_(o), prog_(p) {}

  void line(const std::string& body, const LineOrigin& origin = {}) {
    std::string text;
    if (opt_.line_numbers) {
      text.push_back('N');
      text += std::to_string(next_number_);
      text.push_back(' ');
      next_number_ += opt_.line_number_step;
    }
    text += body;
    if (dialect_.max_line_length && text.size() > dialect_.max_line_length)
      throw Error("post " + dialect_.name, "line " + std::to_string(prog_.lines.size() + 1) + " is longer than " +
                                               std::to_string(dialect_.max_line_length) + " characters: " + text);
    prog_.lines.push_back(std::move(text));
    prog_.origin.push_back(origin);
  }

  // Every comment of the program: made inert for the dialect, and cut to its line length.
  void comment(const std::string& text) {
    const size_t number = opt_.line_numbers ? std::to_string(next_number_).size() + 2 : 0;
    const size_t room = dialect_.max_line_length > number ? dialect_.max_line_length - number : 0;
    line(comment_line(dialect_, text, room));
  }

  // motion: 0 rapid, 1 line, 2 clockwise arc, 3 counter-clockwise arc (centre given for arcs).
  // `ac`: the trunnion's A and C at the move's end, for a multi-axis move (written where they change).
  void move(int motion, const Vec3& to, double feed, const LineOrigin& origin, const Vec2* centre = nullptr,
            const machine::Index* ac = nullptr) {
    const int d = opt_.decimals;
    int64_t target[3];
    for (int a = 0; a < 3; ++a) target[a] = to_fixed(to[a], d);
    std::string& b = scratch_;
    b.clear();
    if (motion != motion_) {
      b.push_back('G');
      b.push_back(static_cast<char>('0' + motion));
    }
    static const char axis[3] = {'X', 'Y', 'Z'};
    bool moved = false;
    for (int a = 0; a < 3; ++a) {
      if (known_ && target[a] == pos_[a]) continue;
      if (!b.empty()) b.push_back(' ');
      b.push_back(axis[a]);
      append_fixed(b, target[a], d);
      moved = true;
    }
    int64_t turn[2] = {0, 0};
    if (ac) {
      turn[0] = to_fixed(ac->a, kAngleDecimals);
      turn[1] = to_fixed(ac->c, kAngleDecimals);
      for (int r = 0; r < 2; ++r) {
        if (rotary_known_ && turn[r] == rotary_[r]) continue;
        b += r == 0 ? " A" : " C";
        append_fixed(b, turn[r], kAngleDecimals);
        moved = true;
      }
      if (!b.empty() && b[0] == ' ') b.erase(0, 1);
    }
    if (!moved) return;  // a move shorter than the output precision: nothing for the controller to do
    if (centre) {
      // I and J are relative to the start point, as written (rounded) so the controller sees a consistent arc.
      b += " I";
      append_fixed(b, to_fixed((*centre).x(), d) - pos_[0], d);
      b += " J";
      append_fixed(b, to_fixed((*centre).y(), d) - pos_[1], d);
    }
    if (motion != 0 && inverse_time_) {
      // Under G93 every feed move gives its F: 1 / minutes.
      b += " F";
      append_fixed(b, to_fixed(std::floor(feed * 1000) / 1000, kInverseTimeDecimals), kInverseTimeDecimals);
    } else if (motion != 0) {
      if (!(feed > 0)) throw Error("post", "a feed move without a feed rate (toolpath " + std::to_string(origin.toolpath) +
                                               ", pass " + std::to_string(origin.pass) + ", move " +
                                               std::to_string(origin.first_move) + ")");
      const int64_t f = to_fixed(feed, kFeedDecimals);
      if (f != feed_) {
        b += " F";
        append_fixed(b, f, kFeedDecimals);
        feed_ = f;
      }
    }
    motion_ = motion;
    for (int a = 0; a < 3; ++a) pos_[a] = target[a];
    if (ac) rotary_[0] = turn[0], rotary_[1] = turn[1], rotary_known_ = true;
    known_ = true;
    line(b, origin);
  }

  // Inverse time (G93) on or off (G94): the feeds the moves are then given are 1 / minutes.
  void inverse_time(bool on, const LineOrigin& origin) {
    if (on == inverse_time_) return;
    line(on ? "G93" : "G94", origin);
    inverse_time_ = on;
    feed_ = -1;  // G94 again: the next feed is written whatever it is
  }

  // The table turned to `at` by a block written apart (an indexing).
  void set_rotary(const machine::Index& at) {
    rotary_[0] = to_fixed(at.a, kAngleDecimals);
    rotary_[1] = to_fixed(at.c, kAngleDecimals);
    rotary_known_ = true;
  }

  // Moves straight up (or down) to z at the current XY; used for retracts whose XY is the current one.
  void rapid_z(double z, const LineOrigin& origin) {
    if (!known_) {
      if (motion_ == 0 && z_only_ == to_fixed(z, opt_.decimals)) return;
      std::string b = "G0 Z";
      append_fixed(b, to_fixed(z, opt_.decimals), opt_.decimals);
      line(b, origin);
      motion_ = 0;
      z_only_ = to_fixed(z, opt_.decimals);
      return;
    }
    Vec3 at(static_cast<double>(pos_[0]), static_cast<double>(pos_[1]), z);
    const double s = static_cast<double>(decimal_scale(opt_.decimals));
    at.x() /= s;
    at.y() /= s;
    move(0, at, 0.0, origin);
  }

  // Before the first full position, only Z is known (from rapid_z); the first XY rapid fills in the rest.
  void rapid_xy(double x, double y, const LineOrigin& origin) {
    if (known_) {
      const double s = static_cast<double>(decimal_scale(opt_.decimals));
      move(0, Vec3(x, y, static_cast<double>(pos_[2]) / s), 0.0, origin);
      return;
    }
    std::string b = motion_ == 0 ? "X" : "G0 X";
    append_fixed(b, to_fixed(x, opt_.decimals), opt_.decimals);
    b += " Y";
    append_fixed(b, to_fixed(y, opt_.decimals), opt_.decimals);
    pos_[0] = to_fixed(x, opt_.decimals);
    pos_[1] = to_fixed(y, opt_.decimals);
    pos_[2] = z_only_;
    known_ = true;
    motion_ = 0;
    line(b, origin);
  }

  // X and Y alone with Z where a machine-coordinate move (G53) left it: Z stays unknown, so the next rapid_z is
  // written whatever it is.
  void rapid_xy_at_unknown_z(double x, double y, const LineOrigin& origin) {
    std::string b = "G0 X";
    append_fixed(b, to_fixed(x, opt_.decimals), opt_.decimals);
    b += " Y";
    append_fixed(b, to_fixed(y, opt_.decimals), opt_.decimals);
    line(b, origin);
    known_ = false;
    motion_ = 0;
    z_only_ = std::numeric_limits<int64_t>::min();
  }

  // After a tool change the tool's length (and so the program Z of the tip) changed: write every axis again.
  void forget_position() {
    known_ = false;
    motion_ = -1;
  }

  bool position_known() const { return known_; }
  Vec3 position() const {
    const double s = static_cast<double>(decimal_scale(opt_.decimals));
    return Vec3(pos_[0] / s, pos_[1] / s, pos_[2] / s);
  }

 private:
  const Dialect& dialect_;
  const PostOptions& opt_;
  Program& prog_;
  std::string scratch_;
  int next_number_ = 10;
  int motion_ = -1;
  int64_t feed_ = -1;
  int64_t pos_[3] = {0, 0, 0};
  int64_t z_only_ = 0;
  bool known_ = false;
  int64_t rotary_[2] = {0, 0};
  bool rotary_known_ = false;
  bool inverse_time_ = false;
};

std::string fixed_text(double v, int decimals) {
  std::string s;
  append_fixed(s, to_fixed(v, decimals), decimals);
  return s;
}

std::string tool_text(const Tool& t) {
  std::string s = "T" + std::to_string(t.id) + " " + cutter_type_name(t.cutter.type) + " D" +
                  fixed_text(t.cutter.diameter, 3);
  if (t.cutter.type == CutterType::BullNose) s += " r" + fixed_text(t.cutter.corner_radius, 3);
  if (!t.name.empty()) s += " " + t.name;
  return s;
}

void spindle_stop(Writer& w, const LineOrigin& origin, const PostOptions& o) {
  w.line("M5", origin);
  if (o.coolant != Coolant::Off) w.line("M9", origin);
}

// The toolpath's tool into the spindle and its length offset on: the program Z of the tip is no longer known.
void load_tool(Writer& w, const Dialect& d, const Toolpath& tp, const LineOrigin& origin) {
  if (d.tool_change_m6) {
    w.line("T" + std::to_string(tp.tool.id) + " M6", origin);
    if (d.tool_length_offset) w.line("G43 H" + std::to_string(tp.tool.id), origin);
  } else {
    w.comment("load tool " + tool_text(tp.tool) + ", set its length, then cycle start");
    w.line("M0", origin);
  }
  w.forget_position();
}

void spindle_start(Writer& w, const Toolpath& tp, const LineOrigin& origin, const PostOptions& o) {
  w.line("S" + fixed_text(tp.tool.spindle_rpm, kSpeedDecimals) + " M3", origin);
  if (o.coolant == Coolant::Flood) w.line("M8", origin);
  if (o.coolant == Coolant::Mist) w.line("M7", origin);
}

void tool_change(Writer& w, const Dialect& d, const Toolpath& tp, int index, bool first, const PostOptions& o) {
  const LineOrigin origin{index};
  if (!first) spindle_stop(w, origin, o);
  w.rapid_z(tp.clearance_z, origin);
  load_tool(w, d, tp, origin);
  w.rapid_z(tp.clearance_z, origin);  // first move after the length offset: straight up to the clearance
  spindle_start(w, tp, origin, o);
}

// The part turned for an indexed toolpath (3+2): the tool up to the machine's safe Z in machine coordinates (G53,
// whatever the work offset), the toolpath's tool loaded there when it changes, then A and C alone, and the tool over
// the toolpath's start before it goes down (the turned table may stand under the old X Y). No move in between uses
// the new setup's heights while the part still stands as the old one had it.
void index_part(Writer& w, const Dialect& d, const Toolpath& tp, int index, bool change, bool first,
                const PostOptions& o) {
  const LineOrigin origin{index};
  if (!std::isfinite(o.index_safe_z))
    throw Error("post", "an indexed toolpath needs the machine's safe Z to retract to (index_safe_z)");
  if (!std::isfinite(tp.a) || !std::isfinite(tp.c)) throw Error("post", "an indexed toolpath's A or C is not finite");
  if (first && o.select_identity) {
    w.comment("identity kinematics: the program's X Y Z are the machine's axes");
    w.line("M429", origin);
  }
  w.comment("index the part: A " + fixed_text(tp.a, kAngleDecimals) + ", C " + fixed_text(tp.c, kAngleDecimals));
  if (change && !first) spindle_stop(w, origin, o);
  w.line("G53 G0 Z" + fixed_text(o.index_safe_z, o.decimals), origin);
  w.forget_position();
  if (change) load_tool(w, d, tp, origin);
  w.line(index_block(tp.a, tp.c), origin);
  w.rapid_xy_at_unknown_z(tp.start.x(), tp.start.y(), origin);
  if (change) spindle_start(w, tp, origin, o);
}

// A pass's moves, with runs of equal-feed linear moves handed to the arc fitter when arcs are on.
void write_pass(Writer& w, const ToolpathPass& pass, int ti, int pi, const PostOptions& o) {
  const auto& moves = pass.moves;
  const int n = static_cast<int>(moves.size());
  ArcFitOptions fit;
  fit.tolerance = o.arc_tolerance;
  std::vector<Vec3> run;
  int k = 0;
  while (k < n) {
    const Move& m = moves[k];
    if (!o.arcs || m.type != MoveType::Feed || !w.position_known()) {
      w.move(m.type == MoveType::Rapid ? 0 : 1, m.to, m.feed, LineOrigin{ti, pi, k, k});
      ++k;
      continue;
    }
    int e = k;
    while (e + 1 < n && moves[e + 1].type == MoveType::Feed && moves[e + 1].feed == m.feed) ++e;
    run.clear();
    run.push_back(w.position());
    for (int q = k; q <= e; ++q) run.push_back(moves[q].to);
    for (const ArcPiece& piece : fit_arcs(run, fit)) {
      if (piece.arc) {
        w.move(piece.clockwise ? 2 : 3, run[piece.last], m.feed, LineOrigin{ti, pi, k + piece.first, k + piece.last - 1},
               &piece.centre);
      } else {
        for (int s = piece.first; s < piece.last; ++s) w.move(1, run[s + 1], m.feed, LineOrigin{ti, pi, k + s, k + s});
      }
    }
    k = e + 1;
  }
}

// A multi-axis program needs a trunnion with tool-centre-point control and no 3+2 toolpath (their positions are
// machine coordinates at an indexing, the identity kinematics' meaning).
void check_tool_centre_point(const Job& job, const Dialect& d, const PostOptions& o) {
  if (!d.tool_centre_point)
    throw Error("post " + d.name,
                "a toolpath carries a tool axis at every move (simultaneous multi-axis), which the "
                "dialect cannot write (no rotary axes, inverse time or kinematics switch)");
  if (!o.trunnion || o.trunnion->mode != machine::KinematicsMode::ToolCentrePoint)
    throw Error("post",
                "a toolpath carries a tool axis at every move (simultaneous multi-axis): it needs a "
                "trunnion with tool-centre-point control (the machine file's rotary.mode: tool-centre-point)");
  if (!std::isfinite(o.index_safe_z))
    throw Error("post", "a multi-axis program needs the machine's safe Z to retract to before the table turns");
  if (o.work_offset && o.work_offset->rotation_deg != 0)
    throw Error("post",
                "a multi-axis program's work offset cannot turn about Z (G10 L2 R): the tip is written on the "
                "table, which the trunnion turns itself");
  for (size_t t = 0; t < job.size(); ++t)
    if (job[t].indexed)
      throw Error("post", "toolpath " + std::to_string(t + 1) + " (" + job[t].strategy +
                              ") is indexed 3+2 in machine coordinates, which a tool-centre-point program does not "
                              "mix with its multi-axis toolpaths");
}

// The tool axis at the toolpath's start and at the end of each of its moves, in order.
std::vector<Vec3> move_axes(const Toolpath& tp) {
  std::vector<Vec3> axes;
  axes.reserve(tp.move_count() + 1);
  for (const ToolpathPass& p : tp.passes) {
    if (axes.empty()) axes.push_back(p.axes.empty() ? Vec3(Vec3::UnitZ()) : p.axes.front());
    for (size_t k = 0; k < p.moves.size(); ++k) axes.push_back(p.axes.empty() ? Vec3(Vec3::UnitZ()) : p.axes[k]);
  }
  if (axes.empty()) axes.push_back(Vec3::UnitZ());
  return axes;
}

// A point as the program writes it: each coordinate rounded to the decimals.
Vec3 as_written(const Vec3& p, int decimals) {
  const double scale = static_cast<double>(decimal_scale(decimals));
  Vec3 q;
  for (int a = 0; a < 3; ++a) q[a] = static_cast<double>(to_fixed(p[a], decimals)) / scale;
  return q;
}

// A and C as the program writes them (rounded), which the controller turns between.
machine::Index as_written(const machine::Index& i) {
  const double scale = static_cast<double>(decimal_scale(kAngleDecimals));
  return {static_cast<double>(to_fixed(i.a, kAngleDecimals)) / scale,
          static_cast<double>(to_fixed(i.c, kAngleDecimals)) / scale};
}

// The minutes a move of a tool-centre-point program takes: the longest of the tip's length at the feed (none for a
// rapid), the program axes' travel at their speeds (X Y Z on the table, A, C) and the joints' (machine::sweep_joints).
double tool_centre_point_minutes(const machine::Trunnion& t, const Vec3& origin, const Vec3& from, const Vec3& to,
                                 const machine::Index& i0, const machine::Index& i1, double feed,
                                 const PostOptions& o) {
  const double length = (to - from).norm(), da = std::abs(i1.a - i0.a), dc = std::abs(i1.c - i0.c);
  double seconds = feed > 0 ? 60 * length / feed : 0;
  if (o.max_feed > 0) seconds = std::max(seconds, 60 * length / o.max_feed);
  if (t.a.velocity > 0) seconds = std::max(seconds, da / t.a.velocity);
  if (t.c.velocity > 0) seconds = std::max(seconds, dc / t.c.velocity);
  const Vec3 travel = machine::sweep_joints(t, origin + from, origin + to, i0, i1).travel;
  for (int a = 0; a < 3; ++a)
    if (o.axis_velocity[a] > 0)
      seconds = std::max({seconds, std::abs(to[a] - from[a]) / o.axis_velocity[a], travel[a] / o.axis_velocity[a]});
  // A millisecond at least (a move the rounding leaves nothing of), and a hair more than the limits allow, so that
  // the written F, its length and the reader's single-precision feed do not come out a rounding over them.
  return std::max(seconds, 1e-3) * (1 + 1e-5) / 60;
}

// The toolpaths of a tool-centre-point program. The table turns to the first toolpath's first axis in identity
// kinematics with the tool retracted in machine coordinates, as for an indexing; from M428 on, X Y Z are the tip on
// the table and every move carries its A and C. M429 and the retract at the end leave the machine as it began.
void write_tool_centre_point(Writer& w, const Dialect& d, const Job& job, const PostOptions& o) {
  const machine::Trunnion& trunnion = *o.trunnion;
  machine::Index at;
  for (size_t t = 0; t < job.size(); ++t) {
    const Toolpath& tp = job[t];
    const int ti = static_cast<int>(t);
    const LineOrigin origin{ti};
    std::string why;
    const auto turns = machine::indexes_along(trunnion, move_axes(tp), at, &why);
    if (!turns) throw Error("post", "toolpath " + std::to_string(t + 1) + " (" + tp.strategy + "): " + why);
    if (t == 0) {
      w.comment("identity kinematics: retract, turn the table to the first tool axis");
      w.line("M429", origin);
      w.line("G53 G0 Z" + fixed_text(o.index_safe_z, o.decimals), origin);
      w.line(index_block(turns->front().a, turns->front().c), origin);
      w.set_rotary(turns->front());
      // The spindle over the start, in machine coordinates: the tip then lies on the tool axis through the start, and
      // the first move of tool-centre-point kinematics runs down that axis (machine Z alone).
      const Vec3 over =
          trunnion.machine_point((o.work_offset ? o.work_offset->origin : o.program_origin) +
                                     Vec3(tp.start.x(), tp.start.y(), std::max(tp.clearance_z, tp.start.z())),
                                 turns->front().a, turns->front().c);
      w.line("G53 G0 X" + fixed_text(over.x(), o.decimals) + " Y" + fixed_text(over.y(), o.decimals), origin);
      w.comment("tool-centre-point kinematics: X Y Z are the tool tip on the table");
      w.line("M428", origin);
      w.forget_position();
      load_tool(w, d, tp, origin);
      // One full move to the start: down the tool axis from where the machine-coordinate moves left the tip.
      w.move(0, Vec3(tp.start.x(), tp.start.y(), std::max(tp.clearance_z, tp.start.z())), 0, origin);
      spindle_start(w, tp, origin, o);
    } else if (tp.tool.id != job[t - 1].tool.id) {
      tool_change(w, d, tp, ti, false, o);
    }
    w.rapid_z(std::max(tp.clearance_z, tp.start.z()), origin);
    w.rapid_xy(tp.start.x(), tp.start.y(), origin);
    w.rapid_z(tp.start.z(), origin);
    // Every move, the rapids too, in inverse time at what the program axes and the joints allow: a rapid of LinuxCNC
    // would run the program axes at their limits and the joints beyond theirs.
    const Vec3 table_origin = o.work_offset ? o.work_offset->origin : o.program_origin;
    w.inverse_time(true, origin);
    size_t flat = 1;
    Vec3 from = w.position();
    for (size_t p = 0; p < tp.passes.size(); ++p) {
      const auto& moves = tp.passes[p].moves;
      for (size_t k = 0; k < moves.size(); ++k, ++flat) {
        const int kk = static_cast<int>(k);
        const double feed = moves[k].type == MoveType::Rapid ? 0.0 : moves[k].feed;
        // From the numbers as written (rounded), which the controller moves between: on a short move near the
        // pole A's last decimal is a part in a thousand of the joints' travel.
        const double minutes =
            tool_centre_point_minutes(trunnion, table_origin, from, as_written(moves[k].to, o.decimals),
                                      as_written((*turns)[flat - 1]), as_written((*turns)[flat]), feed, o);
        w.move(1, moves[k].to, 1.0 / minutes, LineOrigin{ti, static_cast<int>(p), kk, kk}, nullptr, &(*turns)[flat]);
        from = as_written(moves[k].to, o.decimals);
      }
    }
    w.inverse_time(false, origin);
    at = turns->back();
    w.rapid_z(tp.clearance_z, origin);
  }
}

}  // namespace

bool switches_kinematics(const std::string& line) {
  std::string word;
  for (char ch : line) {
    if (ch == '(' || ch == ';') break;
    if (!std::isspace(static_cast<unsigned char>(ch))) word.push_back(static_cast<char>(std::toupper(ch)));
  }
  return word == "M428" || word == "M429";
}

std::string Program::text() const {
  size_t total = 0;
  for (const auto& l : lines) total += l.size() + 1;
  std::string out;
  out.reserve(total);
  for (const auto& l : lines) {
    out += l;
    out.push_back('\n');
  }
  return out;
}

size_t Program::motion_blocks() const {
  size_t n = 0;
  for (const LineOrigin& o : origin) n += o.first_move >= 0;
  return n;
}

PostOptions post_options_for(const std::string& dialect) {
  PostOptions o;
  o.dialect = dialect;
  return o;
}

std::string index_block(double a, double c) {
  return "G0 A" + fixed_text(a, kAngleDecimals) + " C" + fixed_text(c, kAngleDecimals);
}

int decimals_for_tolerance(double tolerance) {
  if (!(tolerance > 0) || !std::isfinite(tolerance)) return 3;
  const double d = std::ceil(std::log10(5.0 * std::sqrt(3.0) / tolerance) - 1e-9);
  return static_cast<int>(std::clamp(d, 3.0, 6.0));
}

Program post(const Job& job, const PostOptions& given) {
  const Dialect& d = find_dialect(given.dialect);
  PostOptions o = given;
  if (o.decimals == 0) {
    double tolerance = INFINITY;
    for (const Toolpath& tp : job)
      if (tp.tolerance > 0) tolerance = std::min(tolerance, tp.tolerance);
    o.decimals = decimals_for_tolerance(tolerance);
  }
  decimal_scale(o.decimals);  // validates
  if (job.empty()) throw Error("post", "the job has no toolpath");
  Program prog;
  prog.dialect = d.name;
  prog.decimals = o.decimals;
  Writer w(d, o, prog);
  if (!o.title.empty()) w.comment(o.title);
  w.comment("rosmill post, dialect " + d.name + ", mm");
  for (const Toolpath& tp : job) w.comment(tp.strategy + ": " + tool_text(tp.tool));
  std::string setup = d.setup_words;
  if (o.work_offset) {
    w.comment("work offset " + o.work_offset->code() + " " + o.work_offset_note);
    w.line(work_offset_block(*o.work_offset, d, o.decimals));
    const size_t g54 = setup.find("G54");
    if (g54 == std::string::npos) throw Error("post", "dialect " + d.name + " selects no work offset");
    setup.replace(g54, 3, o.work_offset->code());
  }
  w.line(setup);
  const bool multi_axis = std::any_of(job.begin(), job.end(), [](const Toolpath& tp) { return tp.multi_axis(); });
  if (d.path_blending) {
    // A multi-axis program blends within half the plan's tolerance: its chords take the other half, and the tip
    // must stay on the cutter locations to within the tolerance whatever the table does.
    double blend = o.blend_tolerance;
    if (multi_axis)
      for (const Toolpath& tp : job)
        if (tp.tolerance > 0) blend = std::min(blend, 0.5 * tp.tolerance);
    w.line("G64 P" + fixed_text(blend, o.decimals));
  }
  if (multi_axis) {
    check_tool_centre_point(job, d, o);
    write_tool_centre_point(w, d, job, o);
    w.line("M5");
    if (o.coolant != Coolant::Off) w.line("M9");
    w.comment("identity kinematics again, the tool retracted");
    w.line("M429");
    w.line("G53 G0 Z" + fixed_text(o.index_safe_z, o.decimals));
    w.line(d.program_end);
    return prog;
  }
  for (size_t t = 0; t < job.size(); ++t) {
    const Toolpath& tp = job[t];
    const int ti = static_cast<int>(t);
    const bool change = t == 0 || tp.tool.id != job[t - 1].tool.id;
    if (tp.indexed && (t == 0 || !job[t - 1].indexed || job[t - 1].a != tp.a || job[t - 1].c != tp.c))
      index_part(w, d, tp, ti, change, t == 0, o);
    else if (change)
      tool_change(w, d, tp, ti, t == 0, o);
    w.rapid_z(std::max(tp.clearance_z, tp.start.z()), LineOrigin{ti});
    w.rapid_xy(tp.start.x(), tp.start.y(), LineOrigin{ti});
    w.rapid_z(tp.start.z(), LineOrigin{ti});
    for (size_t p = 0; p < tp.passes.size(); ++p) write_pass(w, tp.passes[p], ti, static_cast<int>(p), o);
    w.rapid_z(tp.clearance_z, LineOrigin{ti});
  }
  w.line("M5");
  if (o.coolant != Coolant::Off) w.line("M9");
  w.line(d.program_end);
  return prog;
}

void write_program(const std::string& path, const Program& program) { write_program_lines(path, program.lines); }

void write_program_lines(const std::string& path, const std::vector<std::string>& lines) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error(path, "cannot open for writing");
  for (const std::string& l : lines) {
    out.write(l.data(), static_cast<std::streamsize>(l.size()));
    out.put('\n');
  }
  out.flush();
  if (!out) throw Error(path, "write failed");
}

bool is_program_path(const std::string& path) {
  const size_t dot = path.rfind('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return false;
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == "ngc" || ext == "nc" || ext == "gcode";
}

std::vector<std::string> read_program_lines(const std::string& path) {
  const std::string text = read_input_file(path);
  std::vector<std::string> lines;
  for (size_t at = 0; at < text.size();) {
    const size_t eol = std::min(text.find('\n', at), text.size());
    std::string l = text.substr(at, eol - at);
    if (!l.empty() && l.back() == '\r') l.pop_back();
    lines.push_back(std::move(l));
    at = eol + 1;
  }
  return lines;
}

}  // namespace rosmill::core::gcode
