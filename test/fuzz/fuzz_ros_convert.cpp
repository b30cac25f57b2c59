// The ROS edge (src/ros/convert.cpp): a mesh, a point cloud or a toolpath job message, as a node receives it,
// made into the core's values (metres to millimetres). The message's fields are drawn from the input (a
// structured fuzzer): roscpp's deserializer would size every array from a length prefix before reading it, so raw
// bytes would mostly test roscpp's allocations, not rosmill's checks. The first byte chooses the message.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstring>

#include "fuzz_support.hpp"
#include "rosmill/ros/convert.hpp"

namespace {

using namespace rosmill;

// Mostly ordinary numbers, sometimes any bit pattern (NaN, infinities, denormals).
double number(FuzzedDataProvider& in) {
  if (in.ConsumeBool()) return in.ConsumeFloatingPointInRange<double>(-10.0, 10.0);
  double v = 0;
  const auto bytes = in.ConsumeBytes<uint8_t>(sizeof v);
  if (!bytes.empty()) std::memcpy(&v, bytes.data(), bytes.size());
  return v;
}

geometry_msgs::Point point(FuzzedDataProvider& in) {
  geometry_msgs::Point p;
  p.x = number(in);
  p.y = number(in);
  p.z = number(in);
  return p;
}

void mesh(FuzzedDataProvider& in) {
  shape_msgs::Mesh m;
  m.vertices.resize(in.ConsumeIntegralInRange<size_t>(0, 64));
  for (auto& v : m.vertices) v = point(in);
  m.triangles.resize(in.ConsumeIntegralInRange<size_t>(0, 128));
  for (auto& t : m.triangles)
    for (uint32_t& index : t.vertex_indices)
      index = in.ConsumeBool() ? in.ConsumeIntegral<uint32_t>()
                               : in.ConsumeIntegralInRange<uint32_t>(0, uint32_t(m.vertices.size()));
  fuzz::read_or_refuse([&] {
    const core::Mesh mesh = edge::from_mesh_msg(m);
    for (const core::Vec3& v : mesh.vertices) fuzz::require(v.allFinite(), "a vertex that is not finite");
    for (const auto& f : mesh.faces)
      for (int k = 0; k < 3; ++k) fuzz::require(f[k] < mesh.vertices.size(), "a face index beyond the vertices");
  });
}

void cloud(FuzzedDataProvider& in) {
  sensor_msgs::PointCloud2 m;
  static const char* names[] = {"x", "y", "z", "rgb", "intensity", ""};
  m.fields.resize(in.ConsumeIntegralInRange<size_t>(0, 5));
  for (auto& f : m.fields) {
    f.name = names[in.ConsumeIntegralInRange<size_t>(0, 5)];
    f.offset = in.ConsumeBool() ? in.ConsumeIntegralInRange<uint32_t>(0, 32) : in.ConsumeIntegral<uint32_t>();
    f.datatype = in.ConsumeIntegralInRange<uint8_t>(0, 9);
    f.count = in.ConsumeIntegralInRange<uint32_t>(0, 2);
  }
  m.height = in.ConsumeBool() ? in.ConsumeIntegralInRange<uint32_t>(0, 4) : in.ConsumeIntegral<uint32_t>();
  m.width = in.ConsumeBool() ? in.ConsumeIntegralInRange<uint32_t>(0, 64) : in.ConsumeIntegral<uint32_t>();
  m.point_step = in.ConsumeBool() ? in.ConsumeIntegralInRange<uint32_t>(0, 32) : in.ConsumeIntegral<uint32_t>();
  m.row_step = in.ConsumeBool() ? m.width * m.point_step : in.ConsumeIntegral<uint32_t>();
  m.is_bigendian = in.ConsumeIntegralInRange<uint8_t>(0, 1);
  m.data = in.ConsumeRemainingBytes<uint8_t>();
  fuzz::read_or_refuse([&] {
    const core::PointCloud c = edge::from_cloud_msg(m);
    fuzz::require(c.points.size() <= uint64_t(m.width) * m.height, "more points than the message holds");
    for (const core::Vec3& p : c.points) fuzz::require(p.allFinite(), "a point that is not finite");
  });
}

edge::msg::Toolpath toolpath(FuzzedDataProvider& in) {
  edge::msg::Toolpath t;
  t.strategy = in.ConsumeRandomLengthString(16);
  t.setup_rotation.w = in.ConsumeBool() ? 1.0 : number(in);
  if (in.ConsumeBool()) t.setup_rotation.x = number(in);
  t.tool.cutter_type = in.ConsumeIntegralInRange<uint8_t>(0, 3);
  t.tool.diameter = number(in);
  t.tool.corner_radius = number(in);
  t.tool.feed_rate = number(in);
  t.safe_z = number(in);
  t.clearance_z = number(in);
  t.start = point(in);
  t.passes.resize(in.ConsumeIntegralInRange<size_t>(0, 3));
  for (auto& p : t.passes) {
    p.name = in.ConsumeRandomLengthString(8);
    p.moves.resize(in.ConsumeIntegralInRange<size_t>(0, 16));
    for (auto& mv : p.moves) {
      mv.position = point(in);
      mv.move_type = in.ConsumeIntegralInRange<uint8_t>(0, 3);
      mv.feed_rate = number(in);
    }
  }
  return t;
}

void job(FuzzedDataProvider& in) {
  edge::msg::ToolpathJob m;
  m.toolpaths.resize(in.ConsumeIntegralInRange<size_t>(0, 3));
  for (auto& t : m.toolpaths) t = toolpath(in);
  fuzz::read_or_refuse([&] {
    const core::Job job = edge::from_job_msg(m);
    for (const core::Toolpath& tp : job) {
      fuzz::require(tp.start.allFinite() && std::isfinite(tp.safe_z) && std::isfinite(tp.clearance_z),
                    "a toolpath whose start or heights are not finite");
      fuzz::require(std::isfinite(tp.tool.cutter.diameter) && tp.tool.cutter.diameter > 0,
                    "a tool whose diameter is not a positive number");
      for (const core::ToolpathPass& p : tp.passes)
        for (const core::Move& mv : p.moves)
          fuzz::require(mv.to.allFinite() && std::isfinite(mv.feed), "a move that is not finite");
    }
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  switch (in.ConsumeIntegralInRange<int>(0, 2)) {
    case 0: mesh(in); break;
    case 1: cloud(in); break;
    default: job(in); break;
  }
  return 0;
}
