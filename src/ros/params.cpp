#include "rosmill/ros/params.hpp"

#include <filesystem>

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

ToolTable tool_table_param(const ::ros::NodeHandle& nh, const std::string& name) {
  const std::string path = string_param(nh, name, "");
  if (path.empty()) throw Error(full_name(nh, name), "must name the tool table file (config/tools.yaml)");
  return read_tool_table(path);
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

CloudInputOptions cloud_input_param(const ::ros::NodeHandle& nh) {
  CloudInputOptions o;
  o.orient = string_param(nh, "orient", o.orient);
  o.origin = string_param(nh, "origin", "keep");  // the cloud is already in the workpiece frame (tf)
  o.voxel = double_param(nh, "voxel", o.voxel, 0.0, 1000.0);
  o.outliers = int_param(nh, "outliers", o.outliers, 0, 1000);
  o.holes = string_param(nh, "holes", o.holes);
  const std::string prefix = nh.resolveName("") + "/";
  cloud_prep_options(o, prefix);
  cloud_hole_policy(o, prefix);
  return o;
}

PresetTable presets_param(const ::ros::NodeHandle& nh) {
  std::string path = string_param(nh, "presets", "");
  if (path.empty())
    path = (std::filesystem::path(string_param(nh, "tool_table", "")).parent_path() / "presets.yaml").string();
  return read_presets(path);
}

}  // namespace rosmill::edge
