#include "rosmill/cutter/tool_table.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "rosmill/error.hpp"
#include "rosmill/input_file.hpp"
#include "rosmill/number_text.hpp"

namespace rosmill::core {
namespace {

const std::set<std::string> kFields = {"id", "name", "type", "diameter", "corner_radius", "flute_length",
                                       "shank_diameter", "spindle_rpm", "feed", "plunge_feed", "stepover",
                                       "stepdown", "stick_out", "holder_diameter", "feed_engagement"};

// Reads the fields of one tool entry; `where` is "file: tool N" so that every message names both.
class EntryReader {
 public:
  EntryReader(const YAML::Node& node, std::string where) : node_(node), where_(std::move(where)) {}

  double number(const std::string& field, bool required, double fallback) const {
    const YAML::Node v = node_[field];
    if (!v) {
      if (required) fail(field, "is missing");
      return fallback;
    }
    double x = 0;
    try {
      x = v.as<double>();
    } catch (const YAML::Exception&) {
      fail(field, "is not a number" + got(v));
    }
    if (!std::isfinite(x)) fail(field, "is not finite");
    return x;
  }
  double positive(const std::string& field, bool required = true, double fallback = 0) const {
    const double x = number(field, required, fallback);
    if (!(x > 0)) fail(field, "must be > 0" + got(node_[field]));
    return x;
  }
  std::string text(const std::string& field, bool required, const std::string& fallback) const {
    const YAML::Node v = node_[field];
    if (!v) {
      if (required) fail(field, "is missing");
      return fallback;
    }
    if (!v.IsScalar()) fail(field, "must be a text");
    return v.Scalar();
  }
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw Error(where_, "field '" + field + "' " + what);
  }

 private:
  static std::string got(const YAML::Node& v) { return v && v.IsScalar() ? ", got '" + v.Scalar() + "'" : ""; }
  const YAML::Node& node_;
  std::string where_;
};

Cutter read_cutter(const EntryReader& e) {
  const std::string type = e.text("type", true, "");
  const double d = e.positive("diameter");
  Cutter c;
  if (type == "flat") {
    c = Cutter::flat(d);
    if (e.number("corner_radius", false, 0) != 0) e.fail("corner_radius", "must be 0 for a flat end mill");
  } else if (type == "ball") {
    c = Cutter::ball(d);
    const double r = e.number("corner_radius", false, 0.5 * d);
    if (std::abs(r - 0.5 * d) > 1e-9 * d) e.fail("corner_radius", "must be half the diameter for a ball end mill");
  } else if (type == "bull") {
    const double r = e.positive("corner_radius");
    if (r > 0.5 * d) e.fail("corner_radius", "is larger than half the diameter");
    c = Cutter::bull(d, r);
  } else {
    e.fail("type", "must be flat, ball or bull, got '" + type + "'");
  }
  c.flute_length = e.positive("flute_length");
  c.shank_diameter = e.positive("shank_diameter");
  return c;
}

Tool read_tool(const YAML::Node& node, const std::string& source, size_t index) {
  std::string where = source + ": tool #" + std::to_string(index + 1);
  if (!node.IsMap()) throw Error(where, "must be a map of fields");
  if (node["id"] && node["id"].IsScalar()) where = source + ": tool " + node["id"].Scalar();
  for (const auto& kv : node) {
    if (!kv.first.IsScalar()) throw Error(where, "a field name must be a text");
    const std::string key = kv.first.Scalar();
    if (!kFields.count(key)) throw Error(where, "unknown field '" + key + "'");
  }
  const EntryReader e(node, where);
  Tool t;
  const double id = e.number("id", true, 0);
  if (id < 1 || id != std::floor(id) || id > kMaxToolNumber)
    e.fail("id", "must be a whole number in [1, " + std::to_string(kMaxToolNumber) + "]");
  t.id = static_cast<int>(id);
  t.cutter = read_cutter(e);
  t.name = e.text("name", false, std::string(cutter_type_name(t.cutter.type)) + " " + e.text("diameter", true, ""));
  t.spindle_rpm = e.positive("spindle_rpm");
  t.feed = e.positive("feed");
  t.plunge_feed = e.positive("plunge_feed");
  t.stepover = e.positive("stepover");
  if (t.stepover > t.cutter.diameter) e.fail("stepover", "is larger than the diameter");
  t.stepdown = e.positive("stepdown");
  if (t.stepdown > t.cutter.flute_length) e.fail("stepdown", "is larger than the flute length");
  t.feed_engagement = e.number("feed_engagement", false, NAN);
  if (!std::isnan(t.feed_engagement) && !(t.feed_engagement > 0 && t.feed_engagement <= 180))
    e.fail("feed_engagement", "must lie in (0, 180] degrees, got " + e.text("feed_engagement", true, ""));
  t.stick_out = e.number("stick_out", false, NAN);
  if (!std::isnan(t.stick_out) && t.stick_out < t.cutter.flute_length)
    e.fail("stick_out", "is shorter than the flute length");
  t.holder_diameter = e.number("holder_diameter", false, NAN);
  if (!std::isnan(t.holder_diameter) && t.holder_diameter < t.cutter.shank_diameter)
    e.fail("holder_diameter", "is smaller than the shank's diameter");
  return t;
}

}  // namespace

const Tool& ToolTable::get(int id) const {
  for (const Tool& t : tools)
    if (t.id == id) return t;
  std::ostringstream ids;
  for (const Tool& t : tools) ids << (ids.tellp() > 0 ? ", " : "") << t.id;
  throw Error(source, "no tool with id " + std::to_string(id) + " (ids: " + ids.str() + ")");
}

ToolTable parse_tool_table(const std::string& yaml_text, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw Error(name + ":" + std::to_string(e.mark.line + 1), "not valid YAML: " + e.msg);
  }
  if (!root.IsMap() || !root["tools"]) throw Error(name, "expected a map with a 'tools' list");
  const YAML::Node list = root["tools"];
  if (!list.IsSequence() || list.size() == 0) throw Error(name, "'tools' must be a non-empty list");
  ToolTable table;
  table.source = name;
  std::set<int> seen;
  for (size_t i = 0; i < list.size(); ++i) {
    Tool t = read_tool(list[i], name, i);
    if (!seen.insert(t.id).second) throw Error(name + ": tool " + std::to_string(t.id), "field 'id' is used twice");
    table.tools.push_back(std::move(t));
  }
  return table;
}

ToolTable read_tool_table(const std::string& path) {
  return parse_tool_table(read_input_file(path), path);
}

Tool default_tool(const Cutter& cutter) {
  Tool t;
  t.id = kNoToolNumber;
  t.cutter = cutter;
  t.name = std::string(cutter_type_name(cutter.type)) + " " + shortest_text(cutter.diameter);
  const double d = cutter.diameter;
  t.stepover = (cutter.type == CutterType::FlatEnd ? 0.4 : 0.1) * d;
  t.stepdown = 0.5 * d;
  t.feed = 1000.0;
  t.plunge_feed = 300.0;
  t.spindle_rpm = 12000.0;
  return t;
}

int parse_tool_number(const std::string& text, const std::string& where) {
  const bool digits = !text.empty() && text.size() <= 5 && std::all_of(text.begin(), text.end(), [](unsigned char c) {
    return std::isdigit(c);
  });
  const int n = digits ? std::stoi(text) : 0;
  if (n < 1 || n > kMaxToolNumber)
    throw Error(where, "tool number '" + text + "' must be a whole number in [1, " + std::to_string(kMaxToolNumber) +
                           "]: the tool's pocket in the controller's tool table");
  return n;
}

Tool resolve_tool(const std::string& spec, const ToolTable* table, const std::string& where) {
  const bool numeric = !spec.empty() && std::all_of(spec.begin(), spec.end(), [](unsigned char c) {
    return std::isdigit(c);
  });
  if (numeric && spec.size() <= 9) {
    if (!table) throw Error(where, "tool id " + spec + " needs a tool table (--tools FILE)");
    return table->get(std::stoi(spec));
  }
  const size_t at = spec.find('@');
  Tool t = default_tool(parse_cutter_spec(spec.substr(0, at), where));
  if (at != std::string::npos) t.id = parse_tool_number(spec.substr(at + 1), where);
  return t;
}

std::string inline_tool_spec(const Cutter& c, int number) {
  const auto text = [](double v) { return shortest_text(v); };
  std::string spec = c.type == CutterType::BallEnd   ? "ball:" + text(c.diameter)
                     : c.type == CutterType::FlatEnd ? "flat:" + text(c.diameter)
                                                     : "bull:" + text(c.diameter) + ":" + text(c.corner_radius);
  if (number != kNoToolNumber) spec += "@" + std::to_string(number);
  return spec;
}

}  // namespace rosmill::core
