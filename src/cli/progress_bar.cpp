#include "progress_bar.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rosmill::core::cli {
namespace {

constexpr double kRedrawSeconds = 0.1;

int terminal_width() {
  winsize w{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
  return 80;
}

std::string clock_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  if (s >= 3600) std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
  return text;
}

}  // namespace

std::string progress_line(const std::string& step, double fraction, double elapsed_s, int width) {
  const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
  const bool estimate = elapsed_s >= 1.0 && f >= 0.01;
  const std::string left = (estimate ? clock_text(elapsed_s * (1.0 - f) / f) : std::string("--:--")) + " left";
  char percent[8];
  std::snprintf(percent, sizeof percent, "%3d%%", static_cast<int>(std::floor(100 * f)));
  // The step is cut to leave room for a bar of at least 10 characters.
  const int fixed = 2 + 2 + 2 + 4 + 2 + static_cast<int>(left.size());
  const int room = std::max(0, width - 1 - fixed);
  std::string name = step.substr(0, static_cast<size_t>(std::max(0, room - 10)));
  const int bar = std::clamp(room - static_cast<int>(name.size()), 0, 40);
  const int full = static_cast<int>(std::floor(f * bar));
  return name + "  [" + std::string(static_cast<size_t>(full), '#') + std::string(static_cast<size_t>(bar - full), '.') +
         "]  " + percent + "  " + left;
}

ProgressBar::ProgressBar(bool wanted)
    : on_(wanted && isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()), last_(start_) {}

ProgressBar::~ProgressBar() { clear(); }

void ProgressBar::update(const std::string& step, double fraction) {
  if (!on_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && fraction < 1.0 && std::chrono::duration<double>(now - last_).count() < kRedrawSeconds) return;
  last_ = now;
  const std::string line = progress_line(step, fraction, std::chrono::duration<double>(now - start_).count(),
                                         terminal_width());
  // Carriage return, the line, and "erase to the end of the line" (ECMA-48 EL): a shorter line leaves no tail.
  std::fprintf(stderr, "\r%s\033[K", line.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::clear() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace rosmill::core::cli
