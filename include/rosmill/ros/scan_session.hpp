// A scanning session of the scan_registrar node: views collected on request from a PointCloud2 topic, each with
// the sensor's pose from tf2 at the view's own stamp (a robot moves the sensor between views), then fused
// (scan/view_fusion.hpp) into one cloud in the fixed frame. The latest cloud is also kept as it came, for a
// registration or an inspection of a single view. Thread-safe: clouds arrive while a service waits for one.
#pragma once
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>

#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "rosmill/ros/namespaces.hpp"
#include "rosmill/scan/view_fusion.hpp"

namespace rosmill::edge {

class ScanSession {
 public:
  ScanSession(const tf2_ros::Buffer& tf, std::string fixed_frame, double transform_timeout)
      : tf_(tf), fixed_frame_(std::move(fixed_frame)), transform_timeout_(transform_timeout) {}

  // The subscriber's callback.
  void on_cloud(const sensor_msgs::PointCloud2::ConstPtr& msg);

  // A new session: the views held are dropped. Returns what was dropped, for the reply.
  std::string start();
  std::string reset() { return start(); }
  // Takes the first cloud that arrives after the call (waiting up to `timeout_s`), in the fixed frame through its
  // pose at its stamp, as the session's next view. Throws Error naming the view when there is none, it is empty,
  // or tf has no pose for it at its stamp. Returns a summary.
  std::string add_view(double timeout_s);
  // Fuses the views held; throws Error when there are none or the fusion refuses one. Keeps the result.
  PointCloud finish(const scan::FusionOptions& options, scan::FusionReport& report);

  // The cloud a request names: "fused"/"" the last fused one, "latest" the latest cloud on the topic (in the
  // fixed frame); Error when there is none yet.
  PointCloud cloud_named(const std::string& name) const;
  const std::string& fixed_frame() const { return fixed_frame_; }
  size_t views() const;

 private:
  scan::ScanView view_of(const sensor_msgs::PointCloud2& msg, const std::string& name) const;

  const tf2_ros::Buffer& tf_;
  const std::string fixed_frame_;
  const double transform_timeout_;
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  sensor_msgs::PointCloud2::ConstPtr latest_;
  uint64_t received_ = 0;
  std::vector<scan::ScanView> views_;
  std::optional<PointCloud> fused_;
};

}  // namespace rosmill::edge
