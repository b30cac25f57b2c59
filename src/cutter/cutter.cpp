#include "rosmill/cutter/cutter.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "rosmill/error.hpp"
#include "rosmill/value_range.hpp"

namespace rosmill::core {

const char* cutter_type_name(CutterType t) {
  switch (t) {
    case CutterType::FlatEnd: return "flat";
    case CutterType::BallEnd: return "ball";
    case CutterType::BullNose: return "bull";
  }
  return "flat";
}

namespace {

double positive_number(const std::string& text, const std::string& where, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v <= 0)
    throw Error(where, what + " '" + text + "' is not a positive number");
  return v;
}

}  // namespace

void check_tool(const Tool& t, const std::string& where) {
  const Cutter& c = t.cutter;
  check_range(c.diameter, 0, 500, where + " diameter", "mm", Bound::Open);
  check_range(c.corner_radius, 0, 0.5 * c.diameter, where + " corner_radius", "mm (0 to half the diameter)");
  if (c.type == CutterType::FlatEnd && c.corner_radius != 0)
    throw Error(where + " corner_radius", "must be 0 for a flat end mill");
  if (c.type == CutterType::BallEnd && std::abs(c.corner_radius - c.radius()) > 1e-9 * c.diameter)
    throw Error(where + " corner_radius", "must be half the diameter for a ball end mill");
  check_range(t.feed, 0, 1e5, where + " feed", "mm/min", Bound::Open);
  check_range(t.plunge_feed, 0, 1e5, where + " plunge_feed", "mm/min", Bound::Open);
  check_range(t.spindle_rpm, 0, 1e5, where + " spindle_rpm", "rpm");
  check_range(t.stepover, 0, 500, where + " stepover", "mm", Bound::Open);
  check_range(t.stepdown, 0, 500, where + " stepdown", "mm", Bound::Open);
  if (!std::isnan(t.feed_engagement))
    check_range(t.feed_engagement, 0, 180, where + " feed_engagement", "degrees", Bound::Open);
  if (!std::isnan(t.stick_out))
    check_range(t.stick_out, c.flute_length, 1000, where + " stick_out", "mm (the flute length to 1000)");
  if (!std::isnan(t.holder_diameter))
    check_range(t.holder_diameter, c.shank_diameter, 1000, where + " holder_diameter",
                "mm (the shank's diameter to 1000)");
}

Cutter offset_cutter(const Cutter& cutter, double allowance) {
  if (!(allowance >= 0)) throw Error("allowance", "must be >= 0");
  if (allowance == 0.0) return cutter;
  Cutter grown = cutter;
  grown.diameter += 2 * allowance;
  switch (cutter.type) {
    case CutterType::BallEnd: grown.corner_radius = 0.5 * grown.diameter; break;
    case CutterType::FlatEnd: grown.type = CutterType::BullNose; grown.corner_radius = allowance; break;
    case CutterType::BullNose: grown.corner_radius = cutter.corner_radius + allowance; break;
  }
  return grown;
}

Cutter parse_cutter_spec(const std::string& spec, const std::string& where) {
  std::vector<std::string> parts;
  std::stringstream ss(spec);
  for (std::string part; std::getline(ss, part, ':');) parts.push_back(part);
  const std::string usage = " (expected ball:D, flat:D or bull:D:r)";
  if (parts.empty()) throw Error(where, "empty cutter spec" + usage);
  const std::string& type = parts[0];
  if ((type == "ball" || type == "flat") && parts.size() == 2) {
    const double d = positive_number(parts[1], where, "diameter");
    return type == "ball" ? Cutter::ball(d) : Cutter::flat(d);
  }
  if (type == "bull" && parts.size() == 3) {
    const double d = positive_number(parts[1], where, "diameter");
    const double r = positive_number(parts[2], where, "corner radius");
    if (r > 0.5 * d) throw Error(where, "corner radius " + parts[2] + " is larger than half the diameter " + parts[1]);
    return Cutter::bull(d, r);
  }
  throw Error(where, "bad cutter spec '" + spec + "'" + usage);
}

}  // namespace rosmill::core
