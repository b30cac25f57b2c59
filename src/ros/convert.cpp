#include "rosmill/ros/convert.hpp"

#include <sensor_msgs/point_cloud2_iterator.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "rosmill/error.hpp"
#include "rosmill/gcode/cycle_time.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/toolpath/toolpath_stats.hpp"
#include "rosmill/value_range.hpp"

namespace rosmill::edge {

double to_metres(double mm) { return mm * kMetrePerMm; }
double to_mm(double metres) { return metres * kMmPerMetre; }

Eigen::Matrix4d to_mm_pose(const Eigen::Isometry3d& metres) {
  Eigen::Matrix4d t = metres.matrix();
  t.topRightCorner<3, 1>() *= kMmPerMetre;
  return t;
}

double to_radians(double degrees) { return degrees * M_PI / 180.0; }

double to_degrees(double radians) { return radians * 180.0 / M_PI; }

geometry_msgs::Point to_point_msg(const Vec3& mm) {
  geometry_msgs::Point p;
  p.x = to_metres(mm.x());
  p.y = to_metres(mm.y());
  p.z = to_metres(mm.z());
  return p;
}

Vec3 from_point_msg(const geometry_msgs::Point& m) { return {to_mm(m.x), to_mm(m.y), to_mm(m.z)}; }

geometry_msgs::TransformStamped to_transform_msg(const std::string& parent, const std::string& child,
                                                 const Eigen::Quaterniond& rotation, const Vec3& translation_m) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = ::ros::Time::now();
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation.x = translation_m.x();
  t.transform.translation.y = translation_m.y();
  t.transform.translation.z = translation_m.z();
  t.transform.rotation.x = rotation.x();
  t.transform.rotation.y = rotation.y();
  t.transform.rotation.z = rotation.z();
  t.transform.rotation.w = rotation.w();
  return t;
}

geometry_msgs::Vector3 to_direction_msg(const Vec3& v) {
  geometry_msgs::Vector3 m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

Vec3 from_direction_msg(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }

geometry_msgs::Vector3 to_vector_msg(const Vec3& mm) { return to_direction_msg(mm * kMetrePerMm); }

Vec3 from_vector_msg(const geometry_msgs::Vector3& m) { return from_direction_msg(m) * kMmPerMetre; }

// ---------------------------------------------------------------------------------------------------- meshes

namespace {

shape_msgs::Mesh mesh_msg(const std::vector<Vec3>& vertices, const std::vector<Mesh::Face>& faces) {
  shape_msgs::Mesh msg;
  msg.vertices.reserve(vertices.size());
  for (const Vec3& v : vertices) msg.vertices.push_back(to_point_msg(v));
  msg.triangles.resize(faces.size());
  for (size_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i) msg.triangles[f].vertex_indices[i] = faces[f][i];
  return msg;
}

}  // namespace

shape_msgs::Mesh to_mesh_msg(const Mesh& mesh) { return mesh_msg(mesh.vertices, mesh.faces); }

shape_msgs::Mesh to_mesh_msg(const IndexedTriangles& triangles) {
  return mesh_msg(triangles.vertices, triangles.faces);
}

Mesh from_mesh_msg(const shape_msgs::Mesh& msg, const std::string& where) {
  std::vector<Vec3> vertices;
  vertices.reserve(msg.vertices.size());
  for (size_t i = 0; i < msg.vertices.size(); ++i) {
    const Vec3 v = from_point_msg(msg.vertices[i]);
    if (!v.allFinite()) throw Error(where, "vertex " + std::to_string(i) + " is not finite");
    vertices.push_back(v);
  }
  std::vector<Vec3> corners;
  corners.reserve(msg.triangles.size() * 3);
  for (size_t f = 0; f < msg.triangles.size(); ++f)
    for (uint32_t index : msg.triangles[f].vertex_indices) {
      if (index >= vertices.size())
        throw Error(where, "triangle " + std::to_string(f) + " uses vertex " + std::to_string(index) + " of " +
                               std::to_string(vertices.size()));
      corners.push_back(vertices[index]);
    }
  // Equal vertices scale to equal doubles, so an exact weld rebuilds the same vertices and faces in order.
  return build_mesh(corners);
}

// ---------------------------------------------------------------------------------------------------- clouds

namespace {

const sensor_msgs::PointField* find_field(const sensor_msgs::PointCloud2& msg, const std::string& name) {
  for (const auto& f : msg.fields)
    if (f.name == name) return &f;
  return nullptr;
}

size_t field_bytes(uint8_t datatype) {
  return datatype == sensor_msgs::PointField::FLOAT32 ? 4 : datatype == sensor_msgs::PointField::FLOAT64 ? 8 : 0;
}

// Checks that every x, y and z read lies inside the message: the layout fields (point_step, row_step, offsets)
// come from the sender and are not trusted. All products are taken in 64 bits from 32-bit factors: no overflow.
void check_cloud_layout(const sensor_msgs::PointCloud2& msg, const std::string& where) {
  if (msg.is_bigendian) throw Error(where, "is big-endian; only little-endian clouds are read");
  const uint64_t row_bytes = uint64_t(msg.width) * msg.point_step;
  if (msg.point_step == 0) throw Error(where, "has point_step 0 for " + std::to_string(msg.width) + " points a row");
  for (const char* name : {"x", "y", "z"}) {
    const sensor_msgs::PointField& f = *find_field(msg, name);
    const size_t bytes = field_bytes(f.datatype);
    if (bytes == 0)
      throw Error(where, std::string("field ") + name + " must be float32 or float64 (datatype " +
                             std::to_string(f.datatype) + ")");
    if (uint64_t(f.offset) + bytes > msg.point_step)
      throw Error(where, std::string("field ") + name + " at offset " + std::to_string(f.offset) + " (" +
                             std::to_string(bytes) + " bytes) lies beyond point_step " +
                             std::to_string(msg.point_step));
  }
  if (msg.height > 1 && msg.row_step < row_bytes)
    throw Error(where, "has row_step " + std::to_string(msg.row_step) + ", less than width x point_step = " +
                           std::to_string(row_bytes));
  const uint64_t stride = msg.height > 1 ? msg.row_step : row_bytes;
  const uint64_t needed = (uint64_t(msg.height) - 1) * stride + row_bytes;
  if (msg.data.size() < needed)
    throw Error(where, "holds " + std::to_string(msg.data.size()) + " bytes; " + std::to_string(msg.height) +
                           " row(s) of " + std::to_string(msg.width) + " points of " +
                           std::to_string(msg.point_step) + " bytes need " + std::to_string(needed));
}

template <typename T>
double read_coordinate(const uint8_t* point, uint32_t offset) {
  T v;
  std::memcpy(&v, point + offset, sizeof v);
  return double(v);
}

// Points row by row (a row may be padded past width x point_step), into `out` in the target frame, in mm.
template <typename T>
void read_points(const sensor_msgs::PointCloud2& msg, const Eigen::Isometry3d& to_target, PointCloud& out) {
  const uint32_t ox = find_field(msg, "x")->offset, oy = find_field(msg, "y")->offset,
                 oz = find_field(msg, "z")->offset;
  const size_t stride = msg.height > 1 ? msg.row_step : size_t(msg.width) * msg.point_step;
  out.points.reserve(size_t(msg.width) * msg.height);
  const Eigen::Matrix3d r = to_target.linear() * kMmPerMetre;
  const Vec3 t = to_target.translation() * kMmPerMetre;
  for (size_t row = 0; row < msg.height; ++row) {
    const uint8_t* point = msg.data.data() + row * stride;
    for (size_t i = 0; i < msg.width; ++i, point += msg.point_step) {
      const Vec3 p{read_coordinate<T>(point, ox), read_coordinate<T>(point, oy), read_coordinate<T>(point, oz)};
      if (p.allFinite()) out.points.push_back(r * p + t);
    }
  }
}

}  // namespace

PointCloud from_cloud_msg(const sensor_msgs::PointCloud2& msg, const Eigen::Isometry3d& to_target,
                          const std::string& where) {
  const sensor_msgs::PointField* fx = find_field(msg, "x");
  const sensor_msgs::PointField* fy = find_field(msg, "y");
  const sensor_msgs::PointField* fz = find_field(msg, "z");
  if (!fx || !fy || !fz) throw Error(where, "has no x, y and z fields");
  if (fx->datatype != fy->datatype || fx->datatype != fz->datatype)
    throw Error(where, "x, y and z fields have different types");
  PointCloud out;
  if (uint64_t(msg.width) * msg.height == 0) return out;
  check_cloud_layout(msg, where);
  if (fx->datatype == sensor_msgs::PointField::FLOAT32)
    read_points<float>(msg, to_target, out);
  else
    read_points<double>(msg, to_target, out);
  out.recompute_bbox();
  return out;
}

sensor_msgs::PointCloud2 to_cloud_msg(const PointCloud& cloud, const std::string& frame_id) {
  sensor_msgs::PointCloud2 msg;
  msg.header.frame_id = frame_id;
  sensor_msgs::PointCloud2Modifier modifier(msg);
  modifier.setPointCloud2FieldsByString(1, "xyz");
  modifier.resize(cloud.points.size());
  sensor_msgs::PointCloud2Iterator<float> x(msg, "x"), y(msg, "y"), z(msg, "z");
  for (const Vec3& p : cloud.points) {
    *x = float(to_metres(p.x()));
    *y = float(to_metres(p.y()));
    *z = float(to_metres(p.z()));
    ++x, ++y, ++z;
  }
  msg.is_dense = true;
  return msg;
}

// ---------------------------------------------------------------------------------------------------- tools

msg::Tool to_tool_msg(const core::Tool& tool) {
  msg::Tool m;
  m.id = tool.id;
  m.name = tool.name;
  switch (tool.cutter.type) {
    case CutterType::FlatEnd: m.cutter_type = msg::Tool::FLAT_END; break;
    case CutterType::BallEnd: m.cutter_type = msg::Tool::BALL_END; break;
    case CutterType::BullNose: m.cutter_type = msg::Tool::BULL_NOSE; break;
  }
  m.diameter = to_metres(tool.cutter.diameter);
  m.corner_radius = to_metres(tool.cutter.corner_radius);
  m.flute_length = to_metres(tool.cutter.flute_length);
  m.shank_diameter = to_metres(tool.cutter.shank_diameter);
  m.spindle_rpm = tool.spindle_rpm;
  m.feed_rate = tool.feed * kMetrePerSecondPerMmPerMinute;
  m.plunge_rate = tool.plunge_feed * kMetrePerSecondPerMmPerMinute;
  m.stepover = to_metres(tool.stepover);
  m.stepdown = to_metres(tool.stepdown);
  m.stick_out = to_metres(tool.stick_out_mm());
  m.holder_diameter = to_metres(tool.holder_mm());
  return m;
}

core::Tool from_tool_msg(const msg::Tool& m, const std::string& where) {
  core::Tool t;
  t.id = m.id;
  t.name = m.name;
  switch (m.cutter_type) {
    case msg::Tool::FLAT_END: t.cutter.type = CutterType::FlatEnd; break;
    case msg::Tool::BALL_END: t.cutter.type = CutterType::BallEnd; break;
    case msg::Tool::BULL_NOSE: t.cutter.type = CutterType::BullNose; break;
    default: throw Error(where, "unknown cutter_type " + std::to_string(m.cutter_type));
  }
  t.cutter.diameter = to_mm(m.diameter);
  t.cutter.corner_radius = to_mm(m.corner_radius);
  t.cutter.flute_length = to_mm(m.flute_length);
  t.cutter.shank_diameter = to_mm(m.shank_diameter);
  if (!(t.cutter.diameter > 0) || !std::isfinite(t.cutter.diameter))
    throw Error(where, "diameter must be positive and finite");
  t.spindle_rpm = m.spindle_rpm;
  t.feed = m.feed_rate / kMetrePerSecondPerMmPerMinute;
  t.plunge_feed = m.plunge_rate / kMetrePerSecondPerMmPerMinute;
  t.stepover = to_mm(m.stepover);
  t.stepdown = to_mm(m.stepdown);
  // 0: not given (a message from before these fields): the tool table's rule of thumb.
  if (m.stick_out != 0) t.stick_out = to_mm(m.stick_out);
  if (m.holder_diameter != 0) t.holder_diameter = to_mm(m.holder_diameter);
  return t;
}

// ---------------------------------------------------------------------------------------------------- toolpaths

namespace {

uint8_t to_move_type_msg(MoveType t) {
  switch (t) {
    case MoveType::Rapid: return msg::ToolpathMove::RAPID;
    case MoveType::Feed: return msg::ToolpathMove::FEED;
    case MoveType::Plunge: return msg::ToolpathMove::PLUNGE;
  }
  return msg::ToolpathMove::FEED;
}

MoveType from_move_type_msg(uint8_t t, const std::string& where) {
  switch (t) {
    case msg::ToolpathMove::RAPID: return MoveType::Rapid;
    case msg::ToolpathMove::FEED: return MoveType::Feed;
    case msg::ToolpathMove::PLUNGE: return MoveType::Plunge;
  }
  throw Error(where, "unknown move_type " + std::to_string(t));
}

geometry_msgs::Quaternion to_quaternion_msg(const Eigen::Quaterniond& q) {
  geometry_msgs::Quaternion m;
  m.x = q.x();
  m.y = q.y();
  m.z = q.z();
  m.w = q.w();
  return m;
}

}  // namespace

msg::Toolpath to_toolpath_msg(const core::Toolpath& tp, const SetupFrame& setup) {
  msg::Toolpath m;
  m.strategy = tp.strategy;
  m.setup = setup.name;
  m.tool_axis = to_direction_msg(setup.tool_axis);
  m.setup_rotation = to_quaternion_msg(setup.rotation());
  m.setup_translation = to_vector_msg(setup.placement.translation());
  m.tool = to_tool_msg(tp.tool);
  m.safe_z = to_metres(tp.safe_z);
  m.clearance_z = to_metres(tp.clearance_z);
  m.start = to_point_msg(tp.start);
  m.indexed = tp.indexed;
  m.a = to_radians(tp.a);
  m.c = to_radians(tp.c);
  m.passes.resize(tp.passes.size());
  for (size_t p = 0; p < tp.passes.size(); ++p) {
    const core::ToolpathPass& pass = tp.passes[p];
    msg::ToolpathPass& out = m.passes[p];
    out.name = pass.name;
    out.moves.resize(pass.moves.size());
    for (size_t i = 0; i < pass.moves.size(); ++i) {
      out.moves[i].position = to_point_msg(pass.moves[i].to);
      out.moves[i].move_type = to_move_type_msg(pass.moves[i].type);
      out.moves[i].feed_rate = pass.moves[i].feed * kMetrePerSecondPerMmPerMinute;
    }
    out.axes.reserve(pass.axes.size());
    for (const Vec3& a : pass.axes) out.axes.push_back(to_direction_msg(a));
  }
  return m;
}

namespace {

// The setup a toolpath message says it is in: a unit quaternion, or all zeros for none (+Z). A NaN or a scaled
// rotation would place every status position and marker somewhere else.
void check_setup_rotation(const geometry_msgs::Quaternion& q, const std::string& where) {
  const Eigen::Vector4d v(q.x, q.y, q.z, q.w);
  if (!v.allFinite() || (!v.isZero() && std::abs(v.norm() - 1.0) > 1e-6))
    throw Error(where + " setup_rotation", "must be a unit quaternion (or all zeros for +Z), got (" +
                                               std::to_string(q.x) + ", " + std::to_string(q.y) + ", " +
                                               std::to_string(q.z) + ", " + std::to_string(q.w) + ")");
}

// A multi-axis pass's tool axes: none, or one unit vector per move. A zero or scaled axis would tilt the tool
// somewhere else than planned, a missing one leave moves without an axis.
std::vector<Vec3> from_axes_msg(const msg::ToolpathPass& pass, const std::string& where) {
  if (pass.axes.empty()) return {};
  if (pass.axes.size() != pass.moves.size())
    throw Error(where + " axes", "must hold one tool axis per move (" + std::to_string(pass.moves.size()) +
                                     " moves), or none for a 3-axis pass; got " + std::to_string(pass.axes.size()));
  std::vector<Vec3> axes;
  axes.reserve(pass.axes.size());
  for (size_t k = 0; k < pass.axes.size(); ++k) {
    const Vec3 a = from_direction_msg(pass.axes[k]);
    if (!a.allFinite() || std::abs(a.norm() - 1.0) > 1e-6)
      throw Error(where + " axes[" + std::to_string(k) + "]", "a tool axis must be a finite unit vector");
    axes.push_back(a);
  }
  return axes;
}

}  // namespace

core::Toolpath from_toolpath_msg(const msg::Toolpath& m, const std::string& where) {
  check_setup_rotation(m.setup_rotation, where);
  if (!from_direction_msg(m.setup_translation).allFinite()) throw Error(where + " setup_translation", "is not finite");
  core::Toolpath tp;
  tp.strategy = m.strategy;
  tp.tool = from_tool_msg(m.tool, where + " tool");
  tp.safe_z = to_mm(m.safe_z);
  tp.clearance_z = to_mm(m.clearance_z);
  tp.start = from_point_msg(m.start);
  // The heights and the start are where the program retracts to and begins: a NaN there is a wrong program.
  if (!std::isfinite(tp.safe_z) || !std::isfinite(tp.clearance_z))
    throw Error(where, "safe_z and clearance_z must be finite");
  if (!tp.start.allFinite()) throw Error(where, "start is not finite");
  tp.indexed = m.indexed;
  if (m.indexed && !(std::isfinite(m.a) && std::isfinite(m.c))) throw Error(where, "an indexed toolpath's a or c is not finite");
  tp.a = m.indexed ? to_degrees(m.a) : 0.0;
  tp.c = m.indexed ? to_degrees(m.c) : 0.0;
  tp.passes.resize(m.passes.size());
  for (size_t p = 0; p < m.passes.size(); ++p) {
    tp.passes[p].name = m.passes[p].name;
    auto& moves = tp.passes[p].moves;
    moves.resize(m.passes[p].moves.size());
    for (size_t i = 0; i < moves.size(); ++i) {
      const msg::ToolpathMove& in = m.passes[p].moves[i];
      const std::string at = where + " pass " + std::to_string(p) + " move " + std::to_string(i);
      moves[i].to = from_point_msg(in.position);
      if (!moves[i].to.allFinite()) throw Error(at, "position is not finite");
      moves[i].type = from_move_type_msg(in.move_type, at);
      moves[i].feed = in.feed_rate / kMetrePerSecondPerMmPerMinute;
      if (!std::isfinite(moves[i].feed) || moves[i].feed < 0) throw Error(at, "feed_rate must be finite and >= 0");
      if (moves[i].type != MoveType::Rapid && !(moves[i].feed > 0))
        throw Error(at, "a feed or plunge move needs a positive feed_rate");
    }
    tp.passes[p].axes = from_axes_msg(m.passes[p], where + " pass " + std::to_string(p));
  }
  return tp;
}

msg::ToolpathJob to_job_msg(const Job& job, const SetupFrame& setup, const std_msgs::Header& header) {
  msg::ToolpathJob m;
  m.header = header;
  m.toolpaths.reserve(job.size());
  for (const core::Toolpath& tp : job) {
    m.toolpaths.push_back(to_toolpath_msg(tp, setup));
    m.toolpaths.back().header = header;
  }
  return m;
}

Job from_job_msg(const msg::ToolpathJob& m) {
  Job job;
  for (size_t i = 0; i < m.toolpaths.size(); ++i)
    job.push_back(from_toolpath_msg(m.toolpaths[i], "toolpath " + std::to_string(i)));
  return job;
}

std::optional<gcode::WorkOffset> work_offset_of(const msg::ToolpathJob& m) {
  if (m.work_offset == 0) return std::nullopt;
  if (m.work_offset > gcode::kWorkOffsets)
    throw Error("job work_offset", "must be 0 (none) or 1..6 (G54..G59), got " + std::to_string(m.work_offset));
  gcode::WorkOffset w;
  w.index = m.work_offset;
  w.origin = from_point_msg(m.work_offset_origin);
  w.rotation_deg = m.work_offset_rotation * 180.0 / M_PI;
  if (!w.origin.allFinite() || !std::isfinite(w.rotation_deg))
    throw Error("job work_offset_origin", "is not finite");
  return w;
}

void set_work_offset(msg::ToolpathJob& m, const gcode::WorkOffset& w) {
  m.work_offset = static_cast<uint8_t>(w.index);
  m.work_offset_origin = to_point_msg(w.origin);
  m.work_offset_rotation = w.rotation_deg * M_PI / 180.0;
}

// ---------------------------------------------------------------------------------------------------- planning

namespace {

// A length field: 0 or NaN keeps `fallback` (mm); negative or infinite is an error naming the field.
double length_field(double metres, double fallback, const char* field, bool allow_zero_value) {
  if (std::isnan(metres) || (metres == 0.0 && !allow_zero_value)) return fallback;
  if (!std::isfinite(metres) || metres < 0)
    throw Error(std::string("parameters.") + field, "must be a finite length >= 0 m, got " + std::to_string(metres));
  return to_mm(metres);
}

}  // namespace

PlanParams from_plan_parameters(const msg::PlanParameters& m, const core::Tool& tool, const PlanParams& defaults) {
  PlanParams p = defaults;
  p.tool = tool;
  p.stepover = length_field(m.stepover, defaults.stepover, "stepover", false);
  p.stepdown = length_field(m.stepdown, defaults.stepdown, "stepdown", false);
  p.allowance = length_field(m.allowance, defaults.allowance, "allowance", true);
  p.tolerance = length_field(m.tolerance, defaults.tolerance, "tolerance", false);
  p.stock_margin = length_field(m.stock_margin, defaults.stock_margin, "stock_margin", false);
  p.safe_clearance = length_field(m.safe_clearance, defaults.safe_clearance, "safe_clearance", false);
  check_range(m.angle, -2 * M_PI, 2 * M_PI, "parameters.angle", "rad");  // radians as sent, not degrees
  p.angle_deg = m.angle == 0.0 ? defaults.angle_deg : m.angle * 180.0 / M_PI;
  if (m.engagement != 0.0 && !std::isnan(m.engagement)) {
    check_range(m.engagement, 0, M_PI, "parameters.engagement", "rad", Bound::Open);
    p.engagement_deg = m.engagement * 180.0 / M_PI;
  }
  if (!std::isnan(p.stepover) && p.stepover > tool.cutter.diameter)
    throw Error("parameters.stepover", "is larger than the tool diameter (" +
                                           std::to_string(to_metres(tool.cutter.diameter)) + " m)");
  return p;
}

msg::PlanStatistics to_statistics_msg(const Job& job, double planning_seconds,
                                      const gcode::TrajectoryLimits& trajectory, const gcode::MachineLimits* machine) {
  msg::PlanStatistics s;
  Box3 box;
  for (const core::Toolpath& tp : job) {
    const ToolpathStats st = toolpath_stats(tp);
    s.toolpaths += 1;
    s.passes += tp.passes.size();
    s.moves += st.moves;
    s.cutting_length += to_metres(st.cutting_length);
    s.rapid_length += to_metres(st.rapid_length);
    box.add(tp.bounds());
  }
  const bool multi_axis = std::any_of(job.begin(), job.end(), [](const core::Toolpath& tp) { return tp.multi_axis(); });
  const bool tcp = machine && machine->machine()->simultaneous();
  if (multi_axis && !tcp) {
    s.estimated_duration = NAN;
  } else if (!job.empty()) {
    gcode::PostOptions post = gcode::post_options_for("linuxcnc");
    if (multi_axis) post = gcode::with_tool_centre_point(post, *machine, "parameter machine");
    s.estimated_duration = gcode::estimate_cycle_time(job, post, trajectory).seconds;
  }
  s.planning_time = planning_seconds;
  if (!box.empty()) {
    s.bounds_min = to_point_msg(box.min);
    s.bounds_max = to_point_msg(box.max);
  }
  return s;
}

}  // namespace rosmill::edge
