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

  // The subscriber's callback. With every cloud a view (below), it also adds the cloud as the session's next view.
  void on_cloud(const sensor_msgs::PointCloud2::ConstPtr& msg);

  // Every cloud that arrives is a view, up to `max_views` a session (0: no bound): for a scanner that publishes one
  // cloud a capture, and for the replay of a recording, where no one calls add_view between the clouds. A cloud
  // refused (no pose at its stamp, no points) is kept as the session's error, which finish reports.
  void take_every_cloud(size_t max_views);
  // The frame every cloud is taken in, whatever its header says (empty: the header's): for a driver or a
  // recording whose clouds name a frame the cell's tf does not.
  void take_clouds_in(std::string sensor_frame) { sensor_frame_ = std::move(sensor_frame); }

  // A new session: the views held are dropped. Returns what was dropped, for the reply.
  std::string start();
  std::string reset() { return start(); }
  // Takes the first cloud that arrives after the call (waiting up to `timeout_s`), in the fixed frame through its
  // pose at its stamp, as the session's next view. Throws Error naming the view when there is none, it is empty,
  // or tf has no pose for it at its stamp. Returns a summary.
  std::string add_view(double timeout_s);
  // Fuses the views held; throws Error when there are none, a cloud taken as a view was refused, or the fusion
  // refuses one. Keeps the result; with every cloud a view, the clouds after it wait for the next start.
  PointCloud finish(const scan::FusionOptions& options, scan::FusionReport& report);

  // The cloud a request names: "fused"/"" the last fused one, "latest" the latest cloud on the topic (in the
  // fixed frame); Error when there is none yet.
  PointCloud cloud_named(const std::string& name) const;
  const std::string& fixed_frame() const { return fixed_frame_; }
  size_t views() const;

 private:
  scan::ScanView view_of(const sensor_msgs::PointCloud2& msg, const std::string& name) const;
  void take_as_view(const sensor_msgs::PointCloud2& msg);

  const tf2_ros::Buffer& tf_;
  const std::string fixed_frame_;
  const double transform_timeout_;
  std::string sensor_frame_;
  mutable std::mutex mutex_;
  std::mutex taking_;  // held while a cloud becomes a view (its pose awaited), so finish waits for it
  std::condition_variable arrived_;
  sensor_msgs::PointCloud2::ConstPtr latest_;
  uint64_t received_ = 0;
  std::vector<scan::ScanView> views_;
  bool every_cloud_ = false;
  size_t max_views_ = 0;
  bool finished_ = false;  // take_every_cloud: finish closes the session to further clouds until start
  std::string refused_;  // why a cloud taken as a view was refused (take_every_cloud)
  std::optional<PointCloud> fused_;
};

}  // namespace rosmill::edge
