#include "rosmill/ros/scan_session.hpp"

#include <tf2_eigen/tf2_eigen.h>

#include <chrono>

#include "rosmill/error.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/transform_wait.hpp"

namespace rosmill::edge {

void ScanSession::on_cloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    latest_ = msg;
    ++received_;
  }
  arrived_.notify_all();
  if (every_cloud_) take_as_view(*msg);
}

void ScanSession::take_every_cloud(size_t max_views) {
  std::lock_guard<std::mutex> lock(mutex_);
  every_cloud_ = true;
  max_views_ = max_views;
}

// Runs in the subscriber's callback: ROS calls one subscription's callbacks one at a time, so the views keep the
// order of the clouds, and finish (a service, on another thread) waits for the one being taken through mutex_.
void ScanSession::take_as_view(const sensor_msgs::PointCloud2& msg) {
  std::string name;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_ || !refused_.empty() || (max_views_ && views_.size() >= max_views_)) return;
    name = "view " + std::to_string(views_.size() + 1);
  }
  std::unique_lock<std::mutex> taking(taking_);
  try {
    scan::ScanView view = view_of(msg, name);
    std::lock_guard<std::mutex> lock(mutex_);
    views_.push_back(std::move(view));
    fused_.reset();
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    refused_ = e.what();
  }
}

std::string ScanSession::start() {
  std::lock_guard<std::mutex> lock(mutex_);
  const size_t dropped = views_.size();
  views_.clear();
  fused_.reset();
  refused_.clear();
  finished_ = false;
  return "session started" + (dropped ? " (" + std::to_string(dropped) + " views dropped)" : std::string());
}

size_t ScanSession::views() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return views_.size();
}

// The view's points in its sensor frame (mm) and the sensor's pose in the fixed frame at the view's stamp. No
// fallback to the latest pose: the sensor may have moved since (a robot), and a wrong pose fuses a wrong cloud.
scan::ScanView ScanSession::view_of(const sensor_msgs::PointCloud2& msg, const std::string& name) const {
  const std::string frame = sensor_frame_.empty() ? msg.header.frame_id : sensor_frame_;
  if (frame.empty()) throw Error(name, "has no frame_id: the sensor's pose cannot be known");
  scan::ScanView view;
  view.name = name;
  view.cloud = from_cloud_msg(msg, Eigen::Isometry3d::Identity(), name);
  if (view.cloud.points.empty()) throw Error(name, "has no finite points");
  std::string why;
  if (!can_transform_within(tf_, fixed_frame_, frame, msg.header.stamp, transform_timeout_, &why))
    throw Error(name, "no transform from '" + frame + "' to '" + fixed_frame_ + "' at its stamp " +
                          std::to_string(msg.header.stamp.toSec()) + " within " +
                          std::to_string(transform_timeout_) + " s (" + why + ")");
  view.pose = to_mm_pose(
      tf2::transformToEigen(tf_.lookupTransform(fixed_frame_, frame, msg.header.stamp)));
  return view;
}

std::string ScanSession::add_view(double timeout_s) {
  sensor_msgs::PointCloud2::ConstPtr msg;
  size_t index;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    const uint64_t before = received_;
    if (!arrived_.wait_for(lock, std::chrono::duration<double>(timeout_s), [&] { return received_ > before; }))
      throw Error("view " + std::to_string(views_.size() + 1),
                  "no cloud came on the scan topic within " + std::to_string(timeout_s) + " s");
    msg = latest_;
    index = views_.size() + 1;
  }
  scan::ScanView view = view_of(*msg, "view " + std::to_string(index));
  const size_t points = view.cloud.points.size();
  std::lock_guard<std::mutex> lock(mutex_);
  views_.push_back(std::move(view));
  fused_.reset();
  return "view " + std::to_string(views_.size()) + ": " + std::to_string(points) + " points from '" +
         msg->header.frame_id + "'";
}

PointCloud ScanSession::finish(const scan::FusionOptions& options, scan::FusionReport& report) {
  std::vector<scan::ScanView> views;
  {
    std::lock_guard<std::mutex> taken(taking_);  // a view being taken (take_every_cloud) is the session's
    std::lock_guard<std::mutex> lock(mutex_);
    if (!refused_.empty()) throw Error("finish", "a cloud was refused as a view: " + refused_);
    if (views_.empty())
      throw Error("finish", every_cloud_ ? "no views: no cloud has come on the scan topic since the session started"
                                         : "no views: call add_view after start, once per sensor pose");
    views = views_;
    finished_ = every_cloud_;
  }
  PointCloud fused = scan::fuse_views(views, options, &report);
  std::lock_guard<std::mutex> lock(mutex_);
  fused_ = fused;
  return fused;
}

PointCloud ScanSession::cloud_named(const std::string& name) const {
  sensor_msgs::PointCloud2::ConstPtr latest;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (name.empty() || name == "fused") {
      if (!fused_) throw Error("scan 'fused'", "no fused cloud yet: start, add_view, finish first");
      return *fused_;
    }
    latest = latest_;
  }
  if (name != "latest") throw Error("scan", "unknown scan '" + name + "': fused or latest");
  if (!latest) throw Error("scan 'latest'", "no cloud has come on the scan topic yet");
  scan::ScanView view = view_of(*latest, "the latest cloud");
  transform_points(view.pose, view.cloud.points);
  view.cloud.recompute_bbox();
  return std::move(view.cloud);
}

}  // namespace rosmill::edge
