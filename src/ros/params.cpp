#include "rosmill/ros/params.hpp"

#include <xmlrpcpp/XmlRpcValue.h>

#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::edge {

namespace {

std::string full_name(const ::ros::NodeHandle& nh, const std::string& name) {
  return "parameter " + nh.resolveName(name);
}

bool number_of(const XmlRpc::XmlRpcValue& v, double& out) {
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
    out = double(const_cast<XmlRpc::XmlRpcValue&>(v));
    return true;
  }
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) {
    out = int(const_cast<XmlRpc::XmlRpcValue&>(v));
    return true;
  }
  return false;
}

}  // namespace

std::string string_param(const ::ros::NodeHandle& nh, const std::string& name, const std::string& fallback) {
  XmlRpc::XmlRpcValue v;
  if (!nh.getParam(name, v)) return fallback;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeString) throw Error(full_name(nh, name), "must be a string");
  return std::string(v);
}

bool bool_param(const ::ros::NodeHandle& nh, const std::string& name, bool fallback) {
  XmlRpc::XmlRpcValue v;
  if (!nh.getParam(name, v)) return fallback;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) throw Error(full_name(nh, name), "must be true or false");
  return bool(v);
}

double double_param(const ::ros::NodeHandle& nh, const std::string& name, double fallback, double min, double max) {
  XmlRpc::XmlRpcValue v;
  if (!nh.getParam(name, v)) return fallback;
  double d = 0;
  if (!number_of(v, d)) throw Error(full_name(nh, name), "must be a number");
  if (!std::isfinite(d) || d < min || d > max)
    throw Error(full_name(nh, name),
                std::to_string(d) + " is outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  return d;
}

int int_param(const ::ros::NodeHandle& nh, const std::string& name, int fallback, int min, int max) {
  XmlRpc::XmlRpcValue v;
  if (!nh.getParam(name, v)) return fallback;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) throw Error(full_name(nh, name), "must be an integer");
  const int i = int(v);
  if (i < min || i > max)
    throw Error(full_name(nh, name),
                std::to_string(i) + " is outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  return i;
}

namespace {

double tool_number(XmlRpc::XmlRpcValue& entry, const char* field, double fallback, const std::string& where) {
  if (!entry.hasMember(field)) return fallback;
  double d = 0;
  if (!number_of(entry[field], d) || !std::isfinite(d) || d <= 0)
    throw Error(where + "." + field, "must be a positive number");
  return d;
}

}  // namespace

std::vector<Tool> tool_table_param(const ::ros::NodeHandle& nh, const std::string& name) {
  XmlRpc::XmlRpcValue list;
  std::vector<Tool> tools;
  if (!nh.getParam(name, list)) return tools;
  if (list.getType() != XmlRpc::XmlRpcValue::TypeArray) throw Error(full_name(nh, name), "must be a list of tools");
  for (int i = 0; i < list.size(); ++i) {
    const std::string where = full_name(nh, name) + "[" + std::to_string(i) + "]";
    XmlRpc::XmlRpcValue& entry = list[i];
    if (entry.getType() != XmlRpc::XmlRpcValue::TypeStruct) throw Error(where, "must be a map");
    Tool t;
    if (!entry.hasMember("id") || entry["id"].getType() != XmlRpc::XmlRpcValue::TypeInt || int(entry["id"]) <= 0)
      throw Error(where + ".id", "must be a positive integer");
    t.id = int(entry["id"]);
    if (entry.hasMember("name")) t.name = std::string(entry["name"]);
    if (!entry.hasMember("cutter") || entry["cutter"].getType() != XmlRpc::XmlRpcValue::TypeString)
      throw Error(where + ".cutter", "must be a cutter spec such as \"ball:6\"");
    t.cutter = parse_cutter_spec(std::string(entry["cutter"]), where + ".cutter");
    t.feed = tool_number(entry, "feed", t.feed, where);
    t.plunge_feed = tool_number(entry, "plunge_feed", t.plunge_feed, where);
    t.spindle_rpm = tool_number(entry, "spindle_rpm", t.spindle_rpm, where);
    t.stepover = tool_number(entry, "stepover", 0.4 * t.cutter.diameter, where);
    t.stepdown = tool_number(entry, "stepdown", 0.5 * t.cutter.diameter, where);
    for (const Tool& other : tools)
      if (other.id == t.id) throw Error(where + ".id", "tool " + std::to_string(t.id) + " is listed twice");
    tools.push_back(t);
  }
  return tools;
}

const Tool& find_tool(const std::vector<Tool>& tools, int id) {
  for (const Tool& t : tools)
    if (t.id == id) return t;
  std::string known;
  for (const Tool& t : tools) known += (known.empty() ? "" : ", ") + std::to_string(t.id);
  throw Error("tool_id", "no tool " + std::to_string(id) + " in the tool table (known: " + known + ")");
}

PlanParams plan_defaults_param(const ::ros::NodeHandle& nh) {
  PlanParams p;
  p.allowance = double_param(nh, "planner/allowance", p.allowance, 0.0, 50.0);
  p.tolerance = double_param(nh, "planner/tolerance", p.tolerance, 1e-5, 5.0);
  p.angle_deg = double_param(nh, "planner/angle_deg", p.angle_deg, -360.0, 360.0);
  p.stock_margin = double_param(nh, "planner/stock_margin", p.stock_margin, 0.0, 500.0);
  p.safe_clearance = double_param(nh, "planner/safe_clearance", p.safe_clearance, 0.5, 500.0);
  return p;
}

}  // namespace rosmill::edge
