#include "rosmill/gcode/machine_limits.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "rosmill/error.hpp"
#include "rosmill/gcode/block.hpp"

namespace rosmill::gcode {
namespace {

double positive(const YAML::Node& root, const char* key, const std::string& path) {
  const YAML::Node n = root[key];
  if (!n) throw Error(path, std::string("field '") + key + "' is missing");
  double v;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    throw Error(path, std::string("field '") + key + "' is not a number");
  }
  if (!std::isfinite(v) || v <= 0) throw Error(path, std::string("field '") + key + "' must be a positive number");
  return v;
}

double number(const YAML::Node& n, const std::string& what, const std::string& path) {
  try {
    const double v = n.as<double>();
    if (std::isfinite(v)) return v;
  } catch (const YAML::Exception&) {
  }
  throw Error(path, what + " is not a finite number");
}

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

}  // namespace

MachineLimits load_machine_limits(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw Error(path, "cannot open machine file");
  } catch (const YAML::Exception& e) {
    throw Error(path, std::string("not valid YAML: ") + e.what());
  }
  if (!root.IsMap()) throw Error(path, "expected a map of machine fields");
  MachineLimits m;
  m.name = root["name"] ? root["name"].as<std::string>() : "";
  const YAML::Node env = root["envelope"];
  if (!env || !env.IsMap()) throw Error(path, "field 'envelope' (x, y, z: [min, max]) is missing");
  static const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    const YAML::Node r = env[axes[a]];
    const std::string field = std::string("envelope.") + axes[a];
    if (!r || !r.IsSequence() || r.size() != 2) throw Error(path, "field '" + field + "' must be [min, max]");
    m.envelope.min[a] = number(r[0], field + " min", path);
    m.envelope.max[a] = number(r[1], field + " max", path);
    if (!(m.envelope.min[a] < m.envelope.max[a])) throw Error(path, "field '" + field + "': min must be below max");
  }
  if (const YAML::Node w = root["work_offset"]) {
    if (!w.IsSequence() || w.size() != 3) throw Error(path, "field 'work_offset' must be [x, y, z]");
    for (int a = 0; a < 3; ++a) m.work_offset[a] = number(w[a], "work_offset", path);
  }
  if (!root["table_z"]) throw Error(path, "field 'table_z' is missing");
  m.table_z = number(root["table_z"], "table_z", path);
  if (m.table_z < m.envelope.min.z() - 1e-9 || m.table_z > m.envelope.max.z())
    throw Error(path, "table_z " + fmt(m.table_z) + " lies outside the envelope's z range");
  m.max_feed = positive(root, "max_feed", path);
  m.max_spindle_rpm = positive(root, "max_spindle_rpm", path);
  m.clearance_over_stock = number(root["clearance_over_stock"], "clearance_over_stock", path);
  if (m.clearance_over_stock < 0) throw Error(path, "field 'clearance_over_stock' must be >= 0");
  return m;
}

std::string LimitViolation::message() const { return limit + ": " + detail + ": " + text; }

std::vector<LimitViolation> check_limits(const std::vector<std::string>& lines, const MachineLimits& lim,
                                         const LimitCheckOptions& o) {
  std::vector<LimitViolation> out;
  // First pass: the moves, and the stock top when it is not given.
  struct Step {
    size_t line;
    BlockMotion motion;
    double feed, rpm;
    int spindle;
  };
  std::vector<Step> steps;
  ModalState s;
  double top = -INFINITY;
  auto add = [&](size_t line, std::string limit, std::string detail) {
    out.push_back({line + 1, std::move(limit), std::move(detail), lines[line]});
  };
  int offset_before = s.work_offset;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string where = "line " + std::to_string(i + 1);
    const Block block = parse_block(lines[i], where);
    const BlockMotion bm = apply_block(s, block, where);
    // What the checker cannot follow is refused rather than passed unchecked: moves to stored or machine
    // positions, offset changes, and work offsets other than the one the machine file gives.
    for (int g : block.g_codes()) {
      if (g == 280 || g == 300 || g == 530)
        add(i, "unchecked move", "G" + fmt(g / 10.0) + " goes to a stored or machine position the checker cannot follow");
      if (g == 100 || g == 920 || g == 921 || g == 922 || g == 923)
        add(i, "unchecked move", "G" + fmt(g / 10.0) + " changes an offset; later positions could not be checked");
    }
    if (s.work_offset != 54 && s.work_offset != offset_before)
      add(i, "work offset", "G" + std::to_string(s.work_offset) + " selected; the machine file gives G54's origin only");
    offset_before = s.work_offset;
    steps.push_back({i, bm, s.feed, s.spindle_rpm, s.spindle});
    // Cutting moves across the part (not plunges or feed retracts) run inside the stock.
    if (bm.moved && bm.motion != 0 && bm.to_known[2] && (bm.to.x() != bm.from.x() || bm.to.y() != bm.from.y()))
      top = std::max(top, bm.to.z());
  }
  const double stock_top = std::isnan(o.stock_top) ? top : o.stock_top;
  const double rapid_floor = stock_top + lim.clearance_over_stock;
  static const char* axis = "xyz";
  for (const Step& st : steps) {
    const BlockMotion& bm = st.motion;
    if (st.rpm > lim.max_spindle_rpm && st.spindle != 5)
      add(st.line, "max spindle speed", "S" + fmt(st.rpm) + " rpm over " + fmt(lim.max_spindle_rpm));
    if (!bm.moved) continue;
    if (bm.motion != 0 && st.feed > lim.max_feed)
      add(st.line, "max feed", "F" + fmt(st.feed) + " mm/min over " + fmt(lim.max_feed));
    // The extent of the move along each axis the controller knows: its end points, and for an arc the
    // quadrant points it sweeps through.
    double lo[3], hi[3];
    bool any[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = INFINITY;
      hi[a] = -INFINITY;
      if (bm.to_known[a]) lo[a] = hi[a] = bm.to[a];
      if (bm.from_known[a]) {
        lo[a] = std::min(lo[a], bm.from[a]);
        hi[a] = std::max(hi[a], bm.from[a]);
      }
      any[a] = bm.to_known[a] || bm.from_known[a];
    }
    const bool from_known = bm.from_known[0] && bm.from_known[1];
    if ((bm.motion == 2 || bm.motion == 3) && from_known) {
      const Vec2 a = bm.from.head<2>() - bm.centre, b = bm.to.head<2>() - bm.centre;
      const double r = b.norm();
      auto along = [&](const Vec2& v) {  // angle from the start in the arc's direction, in [0, 2pi)
        double t = std::atan2(a.x() * v.y() - a.y() * v.x(), a.dot(v));
        if (bm.motion == 2) t = -t;
        return t < 0 ? t + 2 * M_PI : t;
      };
      const Vec2 dirs[4] = {Vec2(1, 0), Vec2(0, 1), Vec2(-1, 0), Vec2(0, -1)};
      for (const Vec2& d : dirs)
        if (along(d) <= along(b)) {
          const Vec2 p = bm.centre + r * d;
          for (int k = 0; k < 2; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
          }
        }
    }
    for (int a = 0; a < 3; ++a) {
      if (!any[a]) continue;
      const double mlo = lo[a] + lim.work_offset[a], mhi = hi[a] + lim.work_offset[a];
      if (mlo < lim.envelope.min[a] - 1e-9)
        add(st.line, std::string("envelope ") + axis[a] + " min",
            "machine " + std::string(1, axis[a]) + " " + fmt(mlo) + " below the soft limit " + fmt(lim.envelope.min[a]));
      if (mhi > lim.envelope.max[a] + 1e-9)
        add(st.line, std::string("envelope ") + axis[a] + " max",
            "machine " + std::string(1, axis[a]) + " " + fmt(mhi) + " above the soft limit " + fmt(lim.envelope.max[a]));
    }
    if (any[2] && lo[2] + lim.work_offset.z() < lim.table_z - 1e-9)
      add(st.line, "table", "tool tip at machine z " + fmt(lo[2] + lim.work_offset.z()) + " below the table top " +
                                fmt(lim.table_z));
    if (bm.motion == 0 && std::isfinite(stock_top) && bm.to_known[2]) {
      // A rapid ends above the clearance; one that travels sideways must also start there.
      const bool sideways = bm.to.x() != bm.from.x() || bm.to.y() != bm.from.y();
      const double low = sideways && bm.from_known[2] ? std::min(bm.from.z(), bm.to.z()) : bm.to.z();
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

}  // namespace rosmill::gcode
