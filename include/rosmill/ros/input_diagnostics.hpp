// What a node last did with its input, on /diagnostics: the last input or request accepted (with a summary) or
// rejected (with the reason), so that a cell's monitoring sees a refused mesh or cloud without reading the log.
// Every node but the bridge (whose diagnostic is its program's state) reports through this.
#pragma once
#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include <mutex>
#include <string>

namespace rosmill::edge {

class InputDiagnostics {
 public:
  // `what` names the diagnostic task ("input"); published once a second and on every change.
  explicit InputDiagnostics(::ros::NodeHandle& nh, const std::string& what = "input");

  void accepted(const std::string& input, const std::string& summary);
  void rejected(const std::string& input, const std::string& reason);

 private:
  void record(bool ok, const std::string& input, const std::string& text);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& d);

  diagnostic_updater::Updater updater_;
  ::ros::WallTimer timer_;
  std::mutex mutex_;
  bool any_ = false, ok_ = true;
  std::string input_, text_;
  size_t accepted_ = 0, rejected_ = 0;
};

}  // namespace rosmill::edge
