// Reading node parameters with validation: a missing value takes its default, a value of the wrong type or out of
// range is a rosmill::Error naming the parameter (the node prints it and exits at start-up).
#pragma once
#include <ros/node_handle.h>

#include <string>
#include <vector>

#include "rosmill/ros/namespaces.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/cloud/cloud_input.hpp"
#include "rosmill/plan/plan_params.hpp"
#include "rosmill/planner/presets.hpp"

namespace rosmill::edge {

std::string string_param(const ::ros::NodeHandle& nh, const std::string& name, const std::string& fallback);
bool bool_param(const ::ros::NodeHandle& nh, const std::string& name, bool fallback);
// Numbers must lie in [min, max]; an integer given for a double is accepted.
double double_param(const ::ros::NodeHandle& nh, const std::string& name, double fallback, double min, double max);
int int_param(const ::ros::NodeHandle& nh, const std::string& name, int fallback, int min, int max);

// The tool table named by the node's `tool_table` parameter (a config/tools.yaml file): required; every error
// names the parameter or the file, the tool and the field.
ToolTable tool_table_param(const ::ros::NodeHandle& nh, const std::string& name);

// The planner defaults of the `planner/*` parameters (millimetres).
PlanParams plan_defaults_param(const ::ros::NodeHandle& nh);

// The cloud input step's options (orient, origin, voxel, outliers, holes: named after the command line's options);
// origin defaults to keep, the frame tf gave. A bad value is refused here, at start-up.
CloudInputOptions cloud_input_param(const ::ros::NodeHandle& nh);

// The preset table: the `presets` parameter, else presets.yaml next to the `tool_table` (config/).
PresetTable presets_param(const ::ros::NodeHandle& nh);

}  // namespace rosmill::edge
