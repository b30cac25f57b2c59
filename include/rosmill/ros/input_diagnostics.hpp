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

  // Runs a service request: `fn` returns its message. The response's success and message are set, and the request
  // recorded as accepted, or as rejected and logged as a warning of `node`. Always true (the call was answered).
  template <class Response, class Fn>
  bool answer(const char* node, const char* what, Response& res, Fn&& fn) {
    try {
      res.message = fn();
      res.success = true;
      accepted(what, res.message);
    } catch (const std::exception& e) {
      res.success = false;
      res.message = e.what();
      ROS_WARN("%s: %s: %s", node, what, e.what());
      rejected(what, e.what());
    }
    return true;
  }

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
