// A progress bar for the long commands (job, plan) on a terminal: the step, a bar, the percent and the time left,
// redrawn in place on stderr at most ten times a second. It stays silent when stderr is not a terminal or the
// command prints JSON, so that pipes, logs and scripts see only the command's output. The fractions come from the
// same callbacks the ROS actions turn into feedback (PlanProgress, JobOptions::progress).
#pragma once
#include <chrono>
#include <string>

namespace rosmill::core::cli {

// The bar's text for `step` at `fraction` (0..1) done after `elapsed_s` seconds, at most `width` characters:
// "rough (2/5)  [#######.........]  42%  0:31 left". The time left is the elapsed time scaled by what is left,
// shown once a second has passed and a percent is done ("--:--" before).
std::string progress_line(const std::string& step, double fraction, double elapsed_s, int width);

class ProgressBar {
 public:
  // Shown only when `wanted` and stderr is a terminal.
  explicit ProgressBar(bool wanted);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  bool shown() const { return on_; }
  void update(const std::string& step, double fraction);
  // Clears the bar's line, so that what the command prints next starts on a clean line.
  void clear();

 private:
  bool on_ = false;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace rosmill::core::cli
