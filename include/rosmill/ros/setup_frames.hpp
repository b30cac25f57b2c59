// The frame of each setup on tf. A setup other than +Z is machined with the part turned so that its tool axis
// becomes the machine's +Z, and its toolpath is written in that turned frame; the frame is published as a static
// child of the workpiece frame (REP 105 style: data is stamped with the frame it is expressed in), so that rviz and
// any other consumer can place the toolpath without knowing about setups.
#pragma once
#include <tf2_ros/static_transform_broadcaster.h>

#include <map>
#include <mutex>
#include <string>

#include "rosmill/ros/namespaces.hpp"
#include "rosmill/geometry/setup_frame.hpp"

namespace rosmill::edge {

// The name of a setup's frame: the workpiece frame itself for +Z (no rotation), else
// "<workpiece>_setup_<axis>" ("workpiece_setup_mx" for -X) or, for a direction, "<workpiece>_setup_d<x>_<y>_<z>"
// with the unit direction in thousandths ("workpiece_setup_d577_m577_577").
std::string setup_frame_id(const std::string& workpiece, const SetupFrame& setup);

// The frame of a job's setup `index` (from 0): "<workpiece>_setup<index + 1>" (workpiece_setup1, ...), the part
// turned onto the setup's tool axis with its origin at the setup's datum (the program's zero).
std::string job_setup_frame_id(const std::string& workpiece, size_t index);

class SetupFramePublisher {
 public:
  // Publishes (once per frame) the setup's frame as a static child of `workpiece`; returns its name.
  std::string publish(const std::string& workpiece, const SetupFrame& setup);
  // Publishes the setup's frame under `id`, again whenever its pose differs from the one last sent under it.
  void publish_as(const std::string& workpiece, const std::string& id, const SetupFrame& setup);

 private:
  std::mutex mutex_;
  std::map<std::string, Eigen::Matrix4d> sent_;
  tf2_ros::StaticTransformBroadcaster broadcaster_;
};

}  // namespace rosmill::edge
