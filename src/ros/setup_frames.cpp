#include "rosmill/ros/setup_frames.hpp"

#include "rosmill/ros/convert.hpp"

#include <cctype>
#include <cmath>

namespace rosmill::edge {
namespace {

std::string thousandths(double v) {
  const long n = std::lround(v * 1000.0);
  return (n < 0 ? "m" : "") + std::to_string(std::labs(n));
}

}  // namespace

std::string setup_frame_id(const std::string& workpiece, const SetupFrame& setup) {
  if (setup.identity()) return workpiece;
  const std::string& n = setup.name;
  if (n.size() == 2 && (n[0] == '+' || n[0] == '-'))
    return workpiece + "_setup_" + (n[0] == '+' ? "p" : "m") + char(std::tolower(static_cast<unsigned char>(n[1])));
  const Vec3& d = setup.tool_axis;
  return workpiece + "_setup_d" + thousandths(d.x()) + "_" + thousandths(d.y()) + "_" + thousandths(d.z());
}

std::string job_setup_frame_id(const std::string& workpiece, size_t index) {
  return workpiece + "_setup" + std::to_string(index + 1);
}

std::string SetupFramePublisher::publish(const std::string& workpiece, const SetupFrame& setup) {
  const std::string id = setup_frame_id(workpiece, setup);
  if (id != workpiece) publish_as(workpiece, id, setup);
  return id;
}

void SetupFramePublisher::publish_as(const std::string& workpiece, const std::string& id, const SetupFrame& setup) {
  // The setup frame's pose in the workpiece frame: the inverse of the workpiece's placement in the setup frame.
  const Placement pose = setup.placement.inverse();
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = sent_.find(id);
  if (it != sent_.end() && it->second.isApprox(pose.pose.matrix(), 1e-12)) return;
  sent_[id] = pose.pose.matrix();
  broadcaster_.sendTransform(to_transform_msg(workpiece, id, pose.rotation(), pose.translation() * kMetrePerMm));
}

}  // namespace rosmill::edge
