#include "rosmill/segment/setup_filter.hpp"

#include <algorithm>
#include <cmath>

#include "rosmill/error.hpp"
#include "rosmill/geometry/setup_frame.hpp"

namespace rosmill::core::segment {
namespace {

// Slack on the dot-product tests so that a wall whose normal is perpendicular to the tool axis up to rounding
// counts as reached at 90 degrees.
constexpr double kSlack = 1e-9;

Vec3 axis_of(char c, const std::string& text) {
  switch (c) {
    case 'x': case 'X': return Vec3::UnitX();
    case 'y': case 'Y': return Vec3::UnitY();
    case 'z': case 'Z': return Vec3::UnitZ();
  }
  throw Error("setup '" + text + "'", "axis must be x, y or z");
}

}  // namespace

ReachTest::ReachTest(const SetupFilter& filter) : kind_(filter.kind), axis_(filter.axis), bound_(0.0) {
  const double limit = filter.max_angle_deg * M_PI / 180.0;
  if (kind_ == SetupFilter::Kind::ThreeAxis) bound_ = std::cos(limit) - kSlack;
  if (kind_ == SetupFilter::Kind::FourAxis) bound_ = std::sin(std::min(limit, M_PI / 2)) + kSlack;
}

bool SetupFilter::reaches(const Vec3& n) const { return ReachTest(*this)(n); }

double SetupFilter::angle_to_allowed(const Vec3& d) const {
  switch (kind) {
    case Kind::ThreeAxis: return std::acos(std::clamp(d.dot(axis), -1.0, 1.0));
    case Kind::FourAxis: return std::asin(std::min(1.0, std::abs(d.dot(axis))));
    case Kind::FiveAxis: return 0.0;
  }
  return 0.0;
}

SetupFilter parse_setup(const std::string& text) {
  SetupFilter s;
  s.name = text;
  if (text == "5axis") {
    s.kind = SetupFilter::Kind::FiveAxis;
    return s;
  }
  if (text.size() == 7 && text.compare(0, 6, "4axis:") == 0) {
    s.kind = SetupFilter::Kind::FourAxis;
    s.axis = axis_of(text[6], text);
    return s;
  }
  if (text.size() == 2 && (text[0] == '+' || text[0] == '-')) {
    s.axis = axis_of(text[1], text) * (text[0] == '-' ? -1.0 : 1.0);
    s.name = std::string(1, text[0]) + char(std::tolower(text[1]));
    return s;
  }
  throw Error("setup '" + text + "'", "expected +x, -x, +y, -y, +z, -z, 4axis:x|y|z or 5axis");
}

std::vector<SetupFilter> parse_setups(const std::string& list) {
  std::vector<SetupFilter> out;
  size_t start = 0;
  for (;;) {
    const size_t comma = list.find(',', start);
    out.push_back(parse_setup(list.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

const std::vector<SetupFilter>& axis_setups() {
  static const std::vector<SetupFilter> setups = parse_setups("+z,-z,+x,-x,+y,-y");
  return setups;
}

SetupFilter setup_filter_of(const std::string& name, const Vec3& direction, double max_angle_deg,
                            const std::string& where) {
  if (!std::isfinite(max_angle_deg) || max_angle_deg <= 0 || max_angle_deg > 180)
    throw Error(where, "max angle must lie in (0, 180] degrees, got " + std::to_string(max_angle_deg));
  SetupFilter filter;
  if (name.empty()) {
    filter.axis = direction_setup(direction, where).tool_axis;
    filter.name = "custom";
  } else {
    std::string text = name;
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
    if (text.size() == 1) text = "+" + text;
    try {
      filter = parse_setup(text);
    } catch (const Error&) {
      throw Error(where, "unknown setup '" + name + "' (expected +Z, -Z, +X, -X, +Y, -Y, 4axis:x|y|z or 5axis)");
    }
    if (filter.kind == SetupFilter::Kind::ThreeAxis) filter.name = named_setup(text, where).name;
  }
  filter.max_angle_deg = max_angle_deg;
  return filter;
}

}  // namespace rosmill::core::segment
