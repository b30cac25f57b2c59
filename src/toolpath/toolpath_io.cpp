#include "rosmill/toolpath/toolpath_io.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "rosmill/error.hpp"
#include "rosmill/input_file.hpp"

namespace rosmill::core {
namespace {

using nlohmann::json;

double number(const json& j, const char* key, const std::string& where) {
  auto it = j.find(key);
  if (it == j.end() || !it->is_number()) throw Error(where, std::string("field '") + key + "' missing or not a number");
  const double v = it->get<double>();
  if (!std::isfinite(v)) throw Error(where, std::string("field '") + key + "' is not finite");
  return v;
}

Vec3 vec3(const json& j, const std::string& where) {
  if (!j.is_array() || j.size() < 3) throw Error(where, "expected [x, y, z]");
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) throw Error(where, "coordinate is not a number");
    v[i] = j[i].get<double>();
    if (!std::isfinite(v[i])) throw Error(where, "coordinate is not finite");
  }
  return v;
}

// An optional text field: `fallback` when absent; a value of another type is an error, not a library exception.
std::string text_field(const json& j, const char* key, const std::string& fallback, const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (!it->is_string()) throw Error(where, std::string("field '") + key + "' is not a text");
  return it->get<std::string>();
}

CutterType cutter_type(const std::string& name, const std::string& where) {
  if (name == "flat") return CutterType::FlatEnd;
  if (name == "ball") return CutterType::BallEnd;
  if (name == "bull") return CutterType::BullNose;
  throw Error(where, "unknown cutter type '" + name + "' (expected flat, ball or bull)");
}

}  // namespace

json tool_to_json(const Tool& t) {
  return json{{"id", t.id},
              {"name", t.name},
              {"type", cutter_type_name(t.cutter.type)},
              {"diameter", t.cutter.diameter},
              {"corner_radius", t.cutter.corner_radius},
              {"flute_length", t.cutter.flute_length},
              {"shank_diameter", t.cutter.shank_diameter},
              {"spindle_rpm", t.spindle_rpm},
              {"feed", t.feed},
              {"plunge_feed", t.plunge_feed},
              {"stepover", t.stepover},
              {"stepdown", t.stepdown},
              {"feed_engagement", t.feed_engagement_deg()}};
}

Tool tool_from_json(const json& j, const std::string& where) {
  if (!j.is_object()) throw Error(where, "tool is not an object");
  Tool t;
  const double id = number(j, "id", where);
  if (!(id >= 0 && id <= 1e6)) throw Error(where, "field 'id' must lie in [0, 1e6]");
  t.id = static_cast<int>(id);
  t.name = text_field(j, "name", "", where);
  t.cutter.type = cutter_type(text_field(j, "type", "", where), where);
  t.cutter.diameter = number(j, "diameter", where);
  t.cutter.corner_radius = number(j, "corner_radius", where);
  t.cutter.flute_length = number(j, "flute_length", where);
  t.cutter.shank_diameter = number(j, "shank_diameter", where);
  t.spindle_rpm = number(j, "spindle_rpm", where);
  t.feed = number(j, "feed", where);
  t.plunge_feed = number(j, "plunge_feed", where);
  t.stepover = number(j, "stepover", where);
  t.stepdown = number(j, "stepdown", where);
  // Toolpath files written before tools stated their feed's engagement have none: the stepover's then.
  if (j.contains("feed_engagement")) t.feed_engagement = number(j, "feed_engagement", where);
  check_tool(t, where);
  return t;
}

json toolpath_to_json(const Toolpath& tp) {
  json passes = json::array();
  for (const ToolpathPass& p : tp.passes) {
    json moves = json::array();
    for (const Move& m : p.moves)
      moves.push_back(json::array({m.to.x(), m.to.y(), m.to.z(), static_cast<int>(m.type), m.feed}));
    json pass{{"name", p.name}, {"moves", std::move(moves)}};
    if (!p.axes.empty()) {
      json axes = json::array();
      for (const Vec3& a : p.axes) axes.push_back(json::array({a.x(), a.y(), a.z()}));
      pass["axes"] = std::move(axes);
    }
    passes.push_back(std::move(pass));
  }
  return json{{"strategy", tp.strategy},      {"tool", tool_to_json(tp.tool)},
              {"safe_z", tp.safe_z},          {"clearance_z", tp.clearance_z},
              {"start", {tp.start.x(), tp.start.y(), tp.start.z()}},
              {"tolerance", std::isnan(tp.tolerance) ? json() : json(tp.tolerance)},
              {"passes", std::move(passes)}};
}

Toolpath toolpath_from_json(const json& doc, const std::string& where) {
  if (!doc.is_object()) throw Error(where, "toolpath is not an object");
  Toolpath tp;
  tp.strategy = text_field(doc, "strategy", "", where);
  tp.tool = tool_from_json(doc.value("tool", json()), where + ": tool");
  tp.safe_z = number(doc, "safe_z", where);
  tp.clearance_z = number(doc, "clearance_z", where);
  tp.start = vec3(doc.value("start", json()), where + ": start");
  // Optional (older files have none): the plan's tolerance, which the post's rounding keeps within a tenth of.
  if (doc.contains("tolerance") && !doc["tolerance"].is_null()) {
    const json& t = doc["tolerance"];
    if (!t.is_number() || !(t.get<double>() > 0) || !std::isfinite(t.get<double>()))
      throw Error(where, "field 'tolerance' must be a positive number of mm");
    tp.tolerance = t.get<double>();
  }
  const json& passes = doc.value("passes", json());
  if (!passes.is_array()) throw Error(where, "field 'passes' missing or not an array");
  for (size_t i = 0; i < passes.size(); ++i) {
    const std::string pw = where + ": pass " + std::to_string(i);
    if (!passes[i].is_object()) throw Error(pw, "pass is not an object");
    ToolpathPass pass;
    pass.name = text_field(passes[i], "name", "", pw);
    const json& moves = passes[i].value("moves", json());
    if (!moves.is_array()) throw Error(pw, "field 'moves' missing or not an array");
    pass.moves.reserve(moves.size());
    for (size_t k = 0; k < moves.size(); ++k) {
      const std::string mw = pw + ", move " + std::to_string(k);
      const json& m = moves[k];
      if (!m.is_array() || m.size() != 5) throw Error(mw, "expected [x, y, z, type, feed]");
      Move mv;
      mv.to = vec3(m, mw);
      if (!m[3].is_number_integer() || m[3] < 0 || m[3] > 2)
        throw Error(mw, "move type must be 0 (rapid), 1 (feed) or 2 (plunge)");
      mv.type = static_cast<MoveType>(m[3].get<int>());
      if (!m[4].is_number() || !std::isfinite(m[4].get<double>()) || m[4].get<double>() < 0)
        throw Error(mw, "feed must be a finite number >= 0");
      mv.feed = m[4].get<double>();
      if (mv.type != MoveType::Rapid && !(mv.feed > 0)) throw Error(mw, "a feed or plunge move needs a feed > 0");
      pass.moves.push_back(mv);
    }
    // Optional: a multi-axis pass's tool axis at each move's end (unit vectors), one per move.
    if (passes[i].contains("axes")) {
      const json& axes = passes[i]["axes"];
      if (!axes.is_array() || axes.size() != pass.moves.size())
        throw Error(pw, "field 'axes' must hold one tool axis per move (" + std::to_string(pass.moves.size()) + ")");
      for (size_t k = 0; k < axes.size(); ++k) {
        const std::string aw = pw + ", axis " + std::to_string(k);
        const Vec3 a = vec3(axes[k], aw);
        if (std::abs(a.norm() - 1) > 1e-6) throw Error(aw, "a tool axis must be a unit vector");
        pass.axes.push_back(a);
      }
    }
    tp.passes.push_back(std::move(pass));
  }
  return tp;
}

void write_toolpath_file(const std::string& path, const std::vector<Toolpath>& job) {
  json toolpaths = json::array();
  for (const Toolpath& tp : job) toolpaths.push_back(toolpath_to_json(tp));
  const json doc{{"format", "rosmill-toolpath"}, {"version", 1}, {"units", "mm"}, {"toolpaths", std::move(toolpaths)}};
  std::ofstream out(path);
  if (!out) throw Error(path, "cannot open for writing");
  out << doc.dump() << '\n';
  if (!out) throw Error(path, "write failed");
}

std::vector<Toolpath> read_toolpath_file(const std::string& path) {
  return parse_toolpath_text(read_input_file(path), path);
}

std::vector<Toolpath> parse_toolpath_text(const std::string& text, const std::string& path) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(path, std::string("not valid JSON: ") + e.what());
  }
  if (!doc.is_object() || text_field(doc, "format", "", path) != "rosmill-toolpath")
    throw Error(path, "not a rosmill toolpath file (field \"format\" must be \"rosmill-toolpath\")");
  if (text_field(doc, "units", "mm", path) != "mm") throw Error(path, "units must be \"mm\"");
  const json& list = doc.value("toolpaths", json());
  if (!list.is_array() || list.empty()) throw Error(path, "field 'toolpaths' missing, empty or not an array");
  std::vector<Toolpath> job;
  for (size_t i = 0; i < list.size(); ++i) job.push_back(toolpath_from_json(list[i], path + ": toolpath " + std::to_string(i)));
  return job;
}

}  // namespace rosmill::core
