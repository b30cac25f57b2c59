#include "rosmill/ros/input_diagnostics.hpp"

namespace rosmill::edge {

InputDiagnostics::InputDiagnostics(::ros::NodeHandle& nh, const std::string& what) : updater_(nh) {
  updater_.setHardwareID(::ros::this_node::getName());
  updater_.add(what, this, &InputDiagnostics::diagnose);
  timer_ = nh.createWallTimer(::ros::WallDuration(1.0), [this](const ::ros::WallTimerEvent&) { updater_.update(); });
}

void InputDiagnostics::accepted(const std::string& input, const std::string& summary) {
  record(true, input, summary);
}

void InputDiagnostics::rejected(const std::string& input, const std::string& reason) { record(false, input, reason); }

void InputDiagnostics::record(bool ok, const std::string& input, const std::string& text) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    any_ = true;
    ok_ = ok;
    input_ = input;
    text_ = text;
    ++(ok ? accepted_ : rejected_);
  }
  updater_.force_update();
}

void InputDiagnostics::diagnose(diagnostic_updater::DiagnosticStatusWrapper& d) {
  using diagnostic_msgs::DiagnosticStatus;
  std::lock_guard<std::mutex> lock(mutex_);
  if (!any_)
    d.summary(DiagnosticStatus::OK, "waiting for input");
  else if (ok_)
    d.summary(DiagnosticStatus::OK, "last " + input_ + " accepted: " + text_);
  else
    d.summary(DiagnosticStatus::WARN, "last " + input_ + " rejected: " + text_);
  d.add("accepted", accepted_);
  d.add("rejected", rejected_);
}

}  // namespace rosmill::edge
