#include "rosmill/testing/program_sweep.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/testing/swept_check.hpp"

namespace rosmill::core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kSliver = 0.005;  // mm: material this near a cut is no more than a sliver
using swept_check::Segment;

std::vector<double> numbers_in(const std::string& line) {
  std::vector<double> out;
  const size_t open = line.find('('), close = line.rfind(')');
  if (open == std::string::npos || close == std::string::npos) return out;
  std::string inner = line.substr(open + 1, close - open - 1);
  std::replace(inner.begin(), inner.end(), ',', ' ');
  std::istringstream in(inner);
  for (double v; in >> v;) out.push_back(v);
  return out;
}

double corner_of(const SweptCutter& c) {
  return c.type == CutterType::FlatEnd ? 0 : c.type == CutterType::BallEnd ? c.radius : c.corner_radius;
}

// The canonical moves of a program as LinuxCNC's interpreter prints them, with a tool table of the given tools (no
// length offsets) and a home folder of its own (LinuxCNC 2.9 keeps the loaded table in $HOME/.tool.mmap).
std::vector<std::string> rs274_lines(const std::string& program, const std::map<int, SweptCutter>& tools) {
  char dir[] = "/tmp/rosmill-sweep-XXXXXX";
  if (!mkdtemp(dir)) throw std::runtime_error("cannot make a temporary folder");
  const std::string home(dir), table = home + "/tools.tbl", out = home + "/canon.txt";
  {
    std::ofstream t(table);
    for (const auto& [number, cutter] : tools)
      t << 'T' << number << " P" << number << " Z0 D" << 2 * cutter.radius << " ;program sweep\n";
  }
  const std::string command = "cd '" + home + "' && HOME='" + home + "' rs274 -t '" + table + "' -g '" + program +
                              "' '" + out + "' < /dev/null > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(out);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::system(("rm -rf '" + home + "'").c_str());
  if (status != 0 || lines.empty()) throw std::runtime_error("rs274 refuses " + program);
  return lines;
}

void chords(const Vec3& from, const Vec3& to, const Vec2& centre, int rotation, const SweptCutter& c,
            std::vector<Segment>& out) {
  const Vec2 p = from.head<2>() - centre, q = to.head<2>() - centre;
  const double rho = p.norm();
  double a0 = std::atan2(p.y(), p.x()), a1 = std::atan2(q.y(), q.x());
  double sweep = a1 - a0;
  if (rotation > 0) {
    while (sweep <= 1e-12) sweep += 2 * M_PI;
    sweep += 2 * M_PI * (rotation - 1);
  } else {
    while (sweep >= -1e-12) sweep -= 2 * M_PI;
    sweep -= 2 * M_PI * (-rotation - 1);
  }
  const double step = rho > 1e-4 ? 2 * std::acos(1 - 1e-4 / rho) : M_PI / 2;
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / step)));
  Vec3 last = from;
  for (int i = 1; i <= n; ++i) {
    const double s = static_cast<double>(i) / n, a = a0 + s * sweep;
    const Vec3 next = i == n ? to
                             : Vec3(centre.x() + rho * std::cos(a), centre.y() + rho * std::sin(a),
                                    from.z() + s * (to.z() - from.z()));
    out.push_back(swept_check::segment(last, next, c.radius, corner_of(c)));
    last = next;
  }
}

std::vector<Segment> read_moves(const std::string& program, const std::map<int, SweptCutter>& tools) {
  std::vector<Segment> out;
  Vec3 at = Vec3::Zero();
  bool known = false;
  const SweptCutter* cutter = nullptr;
  int selected = -1;
  for (const std::string& line : rs274_lines(program, tools)) {
    const std::vector<double> v = numbers_in(line);
    // SELECT_TOOL names the tool number; CHANGE_TOOL puts it in the spindle (its argument is a pocket of the table).
    if (line.find("SELECT_TOOL(") != std::string::npos && !v.empty()) {
      selected = static_cast<int>(v[0]);
      continue;
    }
    if (line.find("CHANGE_TOOL(") != std::string::npos) {
      const auto t = tools.find(selected);
      if (t == tools.end()) throw std::runtime_error(program + ": tool T" + std::to_string(selected) + " is not given");
      cutter = &t->second;
      continue;
    }
    const bool line_move = line.find("STRAIGHT_TRAVERSE(") != std::string::npos ||
                           line.find("STRAIGHT_FEED(") != std::string::npos;
    const bool arc = line.find("ARC_FEED(") != std::string::npos;
    if (line.find("SELECT_PLANE(") != std::string::npos && line.find("CANON_PLANE_XY") == std::string::npos)
      throw std::runtime_error(program + ": an arc plane other than XY");
    if (!line_move && !arc) continue;
    if ((line_move && v.size() < 3) || (arc && v.size() < 6)) throw std::runtime_error("bad line: " + line);
    const Vec3 to = line_move ? Vec3(v[0], v[1], v[2]) : Vec3(v[0], v[1], v[5]);
    const size_t rotary = line_move ? 3 : 6;
    for (size_t k = rotary; k < std::min(v.size(), rotary + 3); ++k)
      if (v[k] != 0) throw std::runtime_error(program + ": rotary axes are not swept here: " + line);
    // The position before the first move is the controller's, not the program's: nothing is swept to it.
    if (known && cutter) {
      if (line_move) out.push_back(swept_check::segment(at, to, cutter->radius, corner_of(*cutter)));
      else chords(at, to, Vec2(v[2], v[3]), static_cast<int>(v[4]), *cutter, out);
    }
    at = to;
    known = true;
  }
  return out;
}

// Where the ray p + t n (t > t0) first meets a facet of the part: each facet by its plane and barycentric test.
double ray_to_part(const Mesh& part, const Vec3& p, const Vec3& n, double t0) {
  double best = kInf;
  for (size_t f = 0; f < part.face_count(); ++f) {
    const Vec3 &a = part.corner(f, 0), &b = part.corner(f, 1), &c = part.corner(f, 2);
    const Vec3 normal = (b - a).cross(c - a);
    const double denom = normal.dot(n);
    if (std::abs(denom) < 1e-15) continue;
    const double t = normal.dot(a - p) / denom;
    if (!(t > t0) || t >= best) continue;
    const Vec3 x = p + t * n;
    const double area = normal.squaredNorm();
    const double wa = (b - x).cross(c - x).dot(normal), wb = (c - x).cross(a - x).dot(normal),
                 wc = (a - x).cross(b - x).dot(normal);
    const double slack = -1e-12 * area;
    if (wa >= slack && wb >= slack && wc >= slack) best = t;
  }
  return best;
}

// How far from p along n no move cuts (`cut` false), up to `end`: stepped out, then halved to 0.1 um.
template <class Cut>
double uncut_run(const Cut& cut, const Vec3& p, const Vec3& n, double end, double step) {
  double lo = 1e-5, hi = lo;
  if (end <= lo || cut(p + lo * n)) return 0.0;
  for (;;) {
    hi = std::min(lo + step, end);
    if (cut(p + hi * n)) break;
    if (hi >= end) return end;
    lo = hi;
  }
  while (hi - lo > 1e-4) {
    const double mid = 0.5 * (lo + hi);
    (cut(p + mid * n) ? hi : lo) = mid;
  }
  return hi;
}

double box_exit(const Box3& box, const Vec3& p, const Vec3& n) {
  double t1 = kInf;
  for (int a = 0; a < 3; ++a) {
    if (p[a] < box.min[a] - 1e-9 || p[a] > box.max[a] + 1e-9) return 0;
    if (n[a] > 0) t1 = std::min(t1, (box.max[a] - p[a]) / n[a]);
    if (n[a] < 0) t1 = std::min(t1, (box.min[a] - p[a]) / n[a]);
  }
  return t1;
}

}  // namespace

SweepCheck sweep_programs(const Mesh& part, const Box3& stock, const std::vector<SweptProgram>& programs,
                          double spacing, double step, double reach) {
  SweepCheck out;
  swept_check::SweptJob swept;
  for (const SweptProgram& p : programs) {
    SetupFrame frame;
    frame.placement.pose = p.workpiece_to_program;
    frame.tool_axis = p.workpiece_to_program.linear().transpose() * Vec3::UnitZ();
    const std::vector<Segment> moves = read_moves(p.path, p.tools);
    swept.add_segments(frame, moves);
    out.moves += moves.size();
  }
  const auto cut = [&](const Vec3& q) { return swept.swept(q); };
  const auto near = [&](const Vec3& q) { return swept.swept(q, -kSliver); };
  std::mt19937 random(20261201);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (size_t f = 0; f < part.face_count(); ++f) {
    const Vec3 &a = part.corner(f, 0), &b = part.corner(f, 1), &c = part.corner(f, 2);
    const Vec3 cross = (b - a).cross(c - a);
    const double area = 0.5 * cross.norm();
    if (!(area > 0)) continue;
    const Vec3 n = cross.normalized();
    const int count = std::max(1, static_cast<int>(std::ceil(area / (spacing * spacing))));
    for (int k = 0; k < count; ++k) {
      double s = unit(random), t = unit(random);
      if (s + t > 1) s = 1 - s, t = 1 - t;
      const Vec3 p = a + s * (b - a) + t * (c - a);
      SweepSample sample{p, n, static_cast<uint32_t>(f), area / count, 0};
      // Cut into the part: how deep below the face the cut reaches.
      if (cut(p - 2e-3 * n)) {
        double lo = 2e-3, hi = 2e-3;
        while (hi < reach && cut(p - hi * n)) lo = hi, hi += step;
        while (hi - lo > 1e-4) {
          const double mid = 0.5 * (lo + hi);
          (cut(p - mid * n) ? lo : hi) = mid;
        }
        sample.left = -lo;
        out.samples.push_back(sample);
        continue;
      }
      const double end = std::min({box_exit(stock, p, n), ray_to_part(part, p, n, 1e-6), reach});
      sample.left = uncut_run(cut, p, n, end, step);
      // Beyond a hundredth of a millimetre, material counts only as far as it lies more than kSliver from every cut
      // (a ray along a facet's corner runs inside the few micrometres a cutter leaves there).
      if (sample.left > 0.01) sample.left = std::min(sample.left, uncut_run(near, p, n, end, step) + kSliver);
      out.samples.push_back(sample);
    }
  }
  return out;
}

}  // namespace rosmill::core
