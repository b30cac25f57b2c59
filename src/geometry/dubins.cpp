#include "rosmill/geometry/dubins.hpp"

#include <algorithm>
#include <cmath>

namespace rosmill::core {
namespace {

double mod2pi(double a) {
  a = std::fmod(a, 2 * M_PI);
  return a < 0 ? a + 2 * M_PI : a;
}

// The pose after a piece: an arc turns the heading by its length (left positive), a line moves along it.
void advance(char kind, double length, double rho, Vec2& p, Vec2& h) {
  if (kind == 'S') {
    p += rho * length * h;
    return;
  }
  const double s = kind == 'L' ? 1.0 : -1.0;
  const Vec2 left(-h.y(), h.x());
  const Vec2 centre = p + s * rho * left;
  const double c = std::cos(s * length), n = std::sin(s * length);
  const Vec2 r = p - centre;
  p = centre + Vec2(c * r.x() - n * r.y(), n * r.x() + c * r.y());
  h = Vec2(c * h.x() - n * h.y(), n * h.x() + c * h.y());
}

}  // namespace

std::vector<DubinsPath> dubins_paths(const Vec2& from, const Vec2& from_heading, const Vec2& to,
                                     const Vec2& to_heading, double rho) {
  const Vec2 delta = (to - from) / rho;
  const double d = delta.norm();
  const double theta = d > 1e-12 ? std::atan2(delta.y(), delta.x()) : 0.0;
  const double a = mod2pi(std::atan2(from_heading.y(), from_heading.x()) - theta);
  const double b = mod2pi(std::atan2(to_heading.y(), to_heading.x()) - theta);
  const double sa = std::sin(a), sb = std::sin(b), ca = std::cos(a), cb = std::cos(b), cab = std::cos(a - b);
  std::vector<DubinsPath> out;
  const auto add = [&](const char* word, double t, double p, double q) {
    if (!std::isfinite(t) || !std::isfinite(p) || !std::isfinite(q)) return;
    DubinsPath path;
    std::copy(word, word + 3, path.word);
    path.piece[0] = t, path.piece[1] = p, path.piece[2] = q;
    path.rho = rho;
    // The closed forms are checked by where the path ends: a word that does not join the poses is dropped.
    Vec2 at = from, h = from_heading.normalized();
    for (int k = 0; k < 3; ++k) advance(path.word[k], path.piece[k], rho, at, h);
    if ((at - to).norm() <= 1e-6 * std::max(1.0, rho) && (h - to_heading.normalized()).norm() <= 1e-6)
      out.push_back(path);
  };
  {  // LSL
    const double p2 = 2 + d * d - 2 * cab + 2 * d * (sa - sb);
    const double tmp = std::atan2(cb - ca, d + sa - sb);
    if (p2 >= 0) add("LSL", mod2pi(-a + tmp), std::sqrt(p2), mod2pi(b - tmp));
  }
  {  // RSR
    const double p2 = 2 + d * d - 2 * cab + 2 * d * (sb - sa);
    const double tmp = std::atan2(ca - cb, d - sa + sb);
    if (p2 >= 0) add("RSR", mod2pi(a - tmp), std::sqrt(p2), mod2pi(-b + tmp));
  }
  {  // LSR
    const double p2 = -2 + d * d + 2 * cab + 2 * d * (sa + sb);
    if (p2 >= 0) {
      const double p = std::sqrt(p2);
      const double tmp = std::atan2(-ca - cb, d + sa + sb) - std::atan2(-2.0, p);
      add("LSR", mod2pi(-a + tmp), p, mod2pi(-b + tmp));
    }
  }
  {  // RSL
    const double p2 = -2 + d * d + 2 * cab - 2 * d * (sa + sb);
    if (p2 >= 0) {
      const double p = std::sqrt(p2);
      const double tmp = std::atan2(ca + cb, d - sa - sb) - std::atan2(2.0, p);
      add("RSL", mod2pi(a - tmp), p, mod2pi(b - tmp));
    }
  }
  {  // RLR
    const double c = (6 - d * d + 2 * cab + 2 * d * (sa - sb)) / 8;
    if (std::abs(c) <= 1) {
      const double p = mod2pi(2 * M_PI - std::acos(c));
      const double t = mod2pi(a - std::atan2(ca - cb, d - sa + sb) + p / 2);
      add("RLR", t, p, mod2pi(a - b - t + p));
    }
  }
  {  // LRL
    const double c = (6 - d * d + 2 * cab + 2 * d * (sb - sa)) / 8;
    if (std::abs(c) <= 1) {
      const double p = mod2pi(2 * M_PI - std::acos(c));
      const double t = mod2pi(-a - std::atan2(ca - cb, d + sa - sb) + p / 2);
      add("LRL", t, p, mod2pi(b - a - t + p));
    }
  }
  std::sort(out.begin(), out.end(), [](const DubinsPath& x, const DubinsPath& y) { return x.length() < y.length(); });
  return out;
}

std::vector<Vec2> dubins_points(const DubinsPath& path, const Vec2& from, const Vec2& from_heading, double step) {
  std::vector<Vec2> out;
  Vec2 p = from, h = from_heading.normalized();
  for (int k = 0; k < 3; ++k) {
    const double length = path.piece[k] * path.rho;
    if (length <= 0) continue;
    // A line is one move; an arc, chords of at most `step`.
    const int parts = path.word[k] == 'S' ? 1 : std::max(1, static_cast<int>(std::ceil(length / step)));
    for (int i = 0; i < parts; ++i) {
      advance(path.word[k], path.piece[k] / parts, path.rho, p, h);
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace rosmill::core
