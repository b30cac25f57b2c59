// The ROS edge: the ONE place where core values (millimetres, mm/min) become messages (metres, m/s, radians;
// REP 103) and back. Nodes never scale a number themselves; they call these functions.
//
// Message types carry the suffix Msg (msg::Toolpath) because catkin generates them into the package's
// namespace, `rosmill`, where the core's own rosmill::Toolpath, rosmill::Tool, ... already live.
#pragma once
#include <geometry_msgs/Point.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Vector3.h>
#include <sensor_msgs/PointCloud2.h>
#include <shape_msgs/Mesh.h>

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "rosmill/PlanParameters.h"
#include "rosmill/PlanStatistics.h"
#include "rosmill/Tool.h"
#include "rosmill/Toolpath.h"
#include "rosmill/ToolpathJob.h"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/trajectory_limits.hpp"
#include "rosmill/gcode/work_offset.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/plan/plan_params.hpp"
#include "rosmill/ros/namespaces.hpp"
#include "rosmill/toolpath/job.hpp"
#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::edge {

constexpr double kMetrePerMm = 1e-3;
constexpr double kMmPerMetre = 1e3;
constexpr double kMetrePerSecondPerMmPerMinute = 1e-3 / 60.0;  // feeds: mm/min -> m/s

geometry_msgs::Point to_point_msg(const Vec3& mm);
Vec3 from_point_msg(const geometry_msgs::Point& m);
// `child` placed in `parent` (a point p of child is rotation * p + translation in parent; metres), stamped now.
geometry_msgs::TransformStamped to_transform_msg(const std::string& parent, const std::string& child,
                                                 const Eigen::Quaterniond& rotation, const Vec3& translation_m);           // -> mm
geometry_msgs::Vector3 to_direction_msg(const Vec3& unitless);
geometry_msgs::Vector3 to_vector_msg(const Vec3& mm);  // a displacement, -> m
Vec3 from_vector_msg(const geometry_msgs::Vector3& m);  // -> mm
Vec3 from_direction_msg(const geometry_msgs::Vector3& v);
double to_metres(double mm);
double to_mm(double metres);
double to_radians(double degrees);  // rotary axes: degrees in the core, radians in messages
double to_degrees(double radians);
// A rigid transform from tf (metres) as the core's 4x4 pose in millimetres.
Eigen::Matrix4d to_mm_pose(const Eigen::Isometry3d& metres);

// Mesh (mm) <-> shape_msgs/Mesh (m). The message keeps the welded vertices and the face order, so a facet index
// means the same facet on both sides (msg::Segmentation.facet_labels relies on it).
shape_msgs::Mesh to_mesh_msg(const Mesh& mesh);
shape_msgs::Mesh to_mesh_msg(const IndexedTriangles& triangles);  // the same, from welded triangles
Mesh from_mesh_msg(const shape_msgs::Mesh& msg, const std::string& where = "mesh message");

// PointCloud2 (m, any frame) -> PointCloud (mm) after `to_target` (a rigid transform in metres). NaN and infinite
// points are dropped. Needs float32 or float64 fields x, y, z; throws Error(where) otherwise.
PointCloud from_cloud_msg(const sensor_msgs::PointCloud2& msg,
                          const Eigen::Isometry3d& to_target = Eigen::Isometry3d::Identity(),
                          const std::string& where = "cloud message");
// PointCloud (mm) -> PointCloud2 (m, float32 x y z, dense): recorded bags and benchmarks.
sensor_msgs::PointCloud2 to_cloud_msg(const PointCloud& cloud, const std::string& frame_id);

msg::Tool to_tool_msg(const core::Tool& tool);
core::Tool from_tool_msg(const msg::Tool& msg, const std::string& where = "tool");

// Toolpath (mm, setup frame) <-> message. The setup names the frame the positions are in (see msg::Toolpath).
msg::Toolpath to_toolpath_msg(const core::Toolpath& tp, const SetupFrame& setup);
core::Toolpath from_toolpath_msg(const msg::Toolpath& msg, const std::string& where = "toolpath message");
msg::ToolpathJob to_job_msg(const Job& job, const SetupFrame& setup, const std_msgs::Header& header);
Job from_job_msg(const msg::ToolpathJob& msg);
// The work offset a job message asks its program to set (none for work_offset 0); throws Error naming the field for
// an index beyond P6 or a position that is not finite.
std::optional<gcode::WorkOffset> work_offset_of(const msg::ToolpathJob& msg);
void set_work_offset(msg::ToolpathJob& msg, const gcode::WorkOffset& offset);

// Planning parameters of a request on top of the tool's; throws Error naming the bad field.
PlanParams from_plan_parameters(const msg::PlanParameters& msg, const core::Tool& tool, const PlanParams& defaults);
// The estimated duration: the job's LinuxCNC program timed by the machine's trajectory planner (cycle_time.hpp). A
// multi-axis job is timed as written for `machine`'s tool-centre-point control; without such a machine its
// duration is not known (NaN).
msg::PlanStatistics to_statistics_msg(const Job& job, double planning_seconds,
                                      const gcode::TrajectoryLimits& trajectory,
                                      const gcode::MachineLimits* machine = nullptr);

}  // namespace rosmill::edge
