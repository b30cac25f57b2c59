#include "rosmill/cutter/tool_table.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "rosmill/error.hpp"
#include "rosmill/input_file.hpp"
#include "rosmill/number_text.hpp"
#include "rosmill/yaml/fields.hpp"

namespace rosmill::core {
namespace {

const std::set<std::string> kFields = {"id", "name", "type", "diameter", "corner_radius", "flute_length",
                                       "shank_diameter", "spindle_rpm", "feed", "plunge_feed", "stepover",
                                       "stepdown", "stick_out", "holder_diameter", "feed_engagement"};

Cutter read_cutter(const yaml::Fields& f) {
  const std::string type = f.text("type", "", true);
  const double d = f.required_positive("diameter");
  Cutter c;
  if (type == "flat") {
    c = Cutter::flat(d);
    if (f.number("corner_radius", 0) != 0) f.fail("corner_radius", "must be 0 for a flat end mill");
  } else if (type == "ball") {
    c = Cutter::ball(d);
    const double r = f.number("corner_radius", 0.5 * d);
    if (std::abs(r - 0.5 * d) > 1e-9 * d) f.fail("corner_radius", "must be half the diameter for a ball end mill");
  } else if (type == "bull") {
    const double r = f.required_positive("corner_radius");
    if (r > 0.5 * d) f.fail("corner_radius", "is larger than half the diameter");
    c = Cutter::bull(d, r);
  } else {
    f.fail("type", "must be flat, ball or bull, got '" + type + "'");
  }
  c.flute_length = f.required_positive("flute_length");
  c.shank_diameter = f.required_positive("shank_diameter");
  return c;
}

Tool read_tool(const YAML::Node& node, const std::string& source, size_t index) {
  const yaml::Fields f(node, source, "tools[" + std::to_string(index) + "]", kFields);
  Tool t;
  const double id = f.required_number("id");
  if (id < 1 || id != std::floor(id) || id > kMaxToolNumber)
    f.fail("id", "must be a whole number in [1, " + std::to_string(kMaxToolNumber) + "], got " + f.node("id").Scalar());
  t.id = static_cast<int>(id);
  t.cutter = read_cutter(f);
  t.name = f.text("name", std::string(cutter_type_name(t.cutter.type)) + " " + f.node("diameter").Scalar());
  t.spindle_rpm = f.required_positive("spindle_rpm");
  t.feed = f.required_positive("feed");
  t.plunge_feed = f.required_positive("plunge_feed");
  t.stepover = f.required_positive("stepover");
  if (t.stepover > t.cutter.diameter) f.fail("stepover", "is larger than the diameter");
  t.stepdown = f.required_positive("stepdown");
  if (t.stepdown > t.cutter.flute_length) f.fail("stepdown", "is larger than the flute length");
  t.feed_engagement = f.number("feed_engagement", NAN);
  if (!std::isnan(t.feed_engagement) && !(t.feed_engagement > 0 && t.feed_engagement <= 180))
    f.fail("feed_engagement", "must lie in (0, 180] degrees, got " + f.node("feed_engagement").Scalar());
  t.stick_out = f.number("stick_out", NAN);
  if (!std::isnan(t.stick_out) && t.stick_out < t.cutter.flute_length)
    f.fail("stick_out", "is shorter than the flute length");
  t.holder_diameter = f.number("holder_diameter", NAN);
  if (!std::isnan(t.holder_diameter) && t.holder_diameter < t.cutter.shank_diameter)
    f.fail("holder_diameter", "is smaller than the shank's diameter");
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

ToolTable parse_tool_table(const std::string& yaml_text, const std::string& name,
                           const std::set<std::string>& other_fields) {
  std::set<std::string> fields = other_fields;
  fields.insert("tools");
  const yaml::Fields top(yaml::parse(yaml_text, name), name, "", fields);
  const YAML::Node list = top.node("tools");
  if (!list || !list.IsSequence() || list.size() == 0) top.fail("tools", "expected a non-empty list of tools");
  ToolTable table;
  table.source = name;
  std::map<int, int> first_line;  // tool number: the line of its entry
  for (size_t i = 0; i < list.size(); ++i) {
    Tool t = read_tool(list[i], name, i);
    const int line = list[i].Mark().line + 1;
    if (const auto [at, fresh] = first_line.emplace(t.id, line); !fresh)
      throw Error(
          yaml::line_of(list[i]["id"], name) + " tools[" + std::to_string(i) + "].id",
          "tool " + std::to_string(t.id) + " is listed twice (first at line " + std::to_string(at->second) + ")");
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
