// A SIMULATED GRBL controller for tests: a TCP peer that follows GRBL 1.1's documented serial protocol. It is a
// simulation, not firmware: it parses words, moves a point, and answers like GRBL does.
//  - 128-byte receive buffer; a byte arriving when it is full is lost and the overflow is recorded (what a
//    sender that miscounts causes on a real GRBL).
//  - "ok" per line executed, "error:N" for a bad line (1 no letter, 2 bad number, 20 unsupported command, 9 locked
//    by an alarm) after which it goes on with the lines it has buffered, as GRBL does; "ALARM:2" for a move beyond
//    its soft limits: a critical alarm, nothing more is executed or answered until a soft reset (which empties the
//    buffer), and after it every line gets error:9 until "$X".
//  - real-time bytes outside the line stream: '?' status report "<Idle|MPos:x,y,z|FS:f,0|Ln:n>", '!' feed hold,
//    '~' cycle start, 0x18 soft reset (buffer emptied, greeting sent again).
//  - lines execute at a fixed pace, so the buffer fills; a dropped connection can be scheduled after a number
//    of "ok"s, or for when every line received has run (the receive buffer is lost, as a real board's is on a USB
//    reset); nothing runs after the drop, and a test can wait for it (wait_dropped) instead of sleeping.
#pragma once
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace rosmill::core::test {

// How the simulation drops a connection.
enum class GrblDrop {
  // The answers sent before the drop arrive, then the end of the stream; what the sender still writes is read
  // (and ignored) until it closes its end, so its writes never fail (a bridge that closes cleanly).
  Drain,
  // The answers sent before the drop arrive, then the end of the stream, and the socket is closed at once: the
  // sender's next writes fail (broken pipe) while answers may still wait unread on its side (a bridge that hangs
  // up without waiting).
  HangUp,
  // The connection is reset at once (RST): answers still queued or in transit are lost (a cable pulled).
  Reset,
};

struct GrblSimulationConfig {
  double line_period_s = 50e-6;  // time to execute one line
  double soft_limit = 500.0;     // |axis| beyond this is ALARM:2
  long drop_after_oks = -1;      // drop the connection after this many "ok"s (counted over the whole run)
  GrblDrop drop = GrblDrop::Drain;
};

class GrblSimulation {
 public:
  using Config = GrblSimulationConfig;

  explicit GrblSimulation(Config c = {}) : cfg_(c), drop_after_oks_(c.drop_after_oks), drop_kind_(c.drop) {
    listen_fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    const int one = 1;
    ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    ::bind(listen_fd_, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::listen(listen_fd_, 4);
    socklen_t len = sizeof a;
    ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
    thread_ = std::thread([this] { serve(); });
  }
  ~GrblSimulation() {
    stop_ = true;  // also ends a drain that waits for the sender to close
    thread_.join();
    ::close(listen_fd_);
  }

  int port() const { return port_; }
  // Lines executed (answered "ok"), in order, across connections.
  std::vector<std::string> executed() const {
    std::lock_guard<std::mutex> l(mu_);
    return executed_;
  }
  bool overflowed() const { return overflowed_; }
  size_t max_fill() const { return max_fill_; }
  int connections() const { return connections_; }
  int status_queries() const { return status_queries_; }
  bool held() const { return hold_; }
  // Safe to call while a program streams (the settings are read by the simulation's thread).
  void schedule_drop_after(long oks, GrblDrop kind = GrblDrop::Drain) {
    drop_kind_ = kind;
    drop_after_oks_ = oks;
  }
  // Drop as soon as every line received so far has run and been answered, and nothing more is arriving: with
  // the sender held, the drop then comes at a known point (all it sent ran), whatever the machine's load.
  void drop_when_idle(GrblDrop kind) {
    drop_kind_ = kind;
    drop_when_idle_ = true;
  }
  // Waits until the connection has been dropped (and closed, unless it drains); false after `timeout_s` (a
  // bound for a broken test, not a timing assumption).
  bool wait_dropped(double timeout_s) const {
    std::unique_lock<std::mutex> l(mu_);
    return dropped_cv_.wait_for(l, std::chrono::duration<double>(timeout_s), [this] { return dropped_; });
  }

 private:
  void serve() {
    while (!stop_) {
      pollfd p{listen_fd_, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      const int fd = ::accept(listen_fd_, nullptr, nullptr);
      if (fd < 0) continue;
      ++connections_;
      if (session(fd)) ::close(fd);
    }
  }

  void send(int fd, const std::string& s) { ::send(fd, s.data(), s.size(), MSG_NOSIGNAL); }

  // Serves one connection; false when it has closed `fd` itself (a drop that does not drain).
  bool session(int fd) {
    std::string rx;  // the receive buffer
    hold_ = false;
    send(fd, "\r\nGrbl 1.1h ['$' for help]\r\n");
    auto next_exec = std::chrono::steady_clock::now();
    while (!stop_) {
      pollfd p{fd, POLLIN, 0};
      ::poll(&p, 1, rx.find('\n') != std::string::npos ? 0 : 2);
      if (drop_when_idle_ && !(p.revents & (POLLIN | POLLHUP)) && rx.find('\n') == std::string::npos) {
        drop_when_idle_ = false;
        return drop(fd);
      }
      if (p.revents & (POLLIN | POLLHUP)) {
        char buf[512];
        const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
        if (n <= 0) return true;  // the sender went away
        for (ssize_t i = 0; i < n; ++i) {
          const char c = buf[i];
          if (c == '?') {
            ++status_queries_;
            send(fd, status_report(rx));
          } else if (c == '!') {
            hold_ = true;
          } else if (c == '~') {
            hold_ = false;
          } else if (c == '\x18') {
            rx.clear();
            hold_ = false;
            critical_ = false;
            send(fd, "\r\nGrbl 1.1h ['$' for help]\r\n");
          } else if (rx.size() >= 128) {
            overflowed_ = true;  // a real GRBL loses this byte
          } else {
            rx.push_back(c);
            if (rx.size() > max_fill_) max_fill_ = rx.size();
          }
        }
      }
      const auto now = std::chrono::steady_clock::now();
      const size_t nl = rx.find('\n');
      if (nl == std::string::npos || hold_ || critical_ || now < next_exec) continue;
      next_exec = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(cfg_.line_period_s));
      std::string line = rx.substr(0, nl);
      rx.erase(0, nl + 1);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      send(fd, execute(line) + "\r\n");
      const long drop_at = drop_after_oks_;
      if (drop_at >= 0 && oks_ >= drop_at) {
        drop_after_oks_ = -1;
        return drop(fd);  // the receive buffer is lost with the connection
      }
    }
    return true;
  }

  // Called by the session, which returns right after; false when `fd` is closed already.
  bool drop(int fd) {
    const GrblDrop kind = drop_kind_;
    if (kind == GrblDrop::Reset) {
      // close() then sends RST and discards what is still queued to send (answers held back by Nagle).
      const linger reset{1, 0};
      ::setsockopt(fd, SOL_SOCKET, SO_LINGER, &reset, sizeof reset);
    } else {
      ::shutdown(fd, SHUT_WR);  // pushes out the answers still queued, then the end of the stream
    }
    if (kind != GrblDrop::Drain) {
      ::close(fd);
      mark_dropped();
      return false;
    }
    // End of stream after the answers already sent; read what the sender still sends until IT closes, so that
    // close() finds nothing unread (which would reset the connection). No deadline: under load the sender may
    // take long to read the end of the stream, and closing first would break its writes before it has read
    // the answers (the destructor's stop_ bounds the wait).
    mark_dropped();
    char buf[512];
    while (!stop_) {
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, 20) > 0 && ::recv(fd, buf, sizeof buf, 0) <= 0) break;
    }
    return true;
  }

  void mark_dropped() {
    {
      std::lock_guard<std::mutex> l(mu_);
      dropped_ = true;
    }
    dropped_cv_.notify_all();
  }

  std::string status_report(const std::string& rx) const {
    const char* state = alarm_ ? "Alarm" : hold_ ? "Hold:0" : rx.empty() ? "Idle" : "Run";
    char buf[160];
    std::snprintf(buf, sizeof buf, "<%s|MPos:%.3f,%.3f,%.3f|FS:%.0f,0|Ln:%ld>\r\n", state, pos_[0], pos_[1], pos_[2],
                  feed_, last_n_);
    return buf;
  }

  // One line: the reply GRBL gives.
  std::string execute(const std::string& line) {
    if (line.empty()) return "ok";
    if (line[0] == '$') {
      if (line == "$X") {
        alarm_ = false;
        return "[MSG:Caution: Unlocked]\r\nok";
      }
      return "ok";
    }
    if (alarm_) return "error:9";
    double target[3] = {pos_[0], pos_[1], pos_[2]};
    size_t i = 0;
    while (i < line.size()) {
      const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(line[i])));
      if (c == ' ') {
        ++i;
        continue;
      }
      if (c < 'A' || c > 'Z') return "error:1";
      // A number as GRBL reads it: sign, digits, point (no hexadecimal, no exponent).
      size_t j = i + 1;
      if (j < line.size() && (line[j] == '-' || line[j] == '+')) ++j;
      const size_t digits_from = j;
      while (j < line.size() && (std::isdigit(static_cast<unsigned char>(line[j])) || line[j] == '.')) ++j;
      if (j == digits_from) return "error:2";
      const double v = std::atof(line.substr(i + 1, j - i - 1).c_str());
      i = j;
      if (c == 'G' && (v == 64 || v == 43 || v == 41 || v == 42)) return "error:20";
      if (c == 'M' && v == 6) return "error:20";
      if (c == 'X') target[0] = v;
      if (c == 'Y') target[1] = v;
      if (c == 'Z') target[2] = v;
      if (c == 'F') feed_ = v;
      if (c == 'N') last_n_ = static_cast<long>(v);
    }
    for (double t : target)
      if (std::abs(t) > cfg_.soft_limit) {
        alarm_ = critical_ = true;
        return "ALARM:2\r\n[MSG:Reset to continue]";
      }
    for (int a = 0; a < 3; ++a) pos_[a] = target[a];
    {
      std::lock_guard<std::mutex> l(mu_);
      executed_.push_back(line);
    }
    ++oks_;
    return "ok";
  }

  Config cfg_;
  std::atomic<long> drop_after_oks_;
  std::atomic<GrblDrop> drop_kind_;
  std::atomic<bool> drop_when_idle_{false};
  int listen_fd_ = -1;
  int port_ = 0;
  std::thread thread_;
  std::atomic<bool> stop_{false}, overflowed_{false}, hold_{false};
  std::atomic<size_t> max_fill_{0};
  std::atomic<int> connections_{0}, status_queries_{0};
  mutable std::mutex mu_;  // guards executed_ and dropped_
  mutable std::condition_variable dropped_cv_;
  bool dropped_ = false;
  std::vector<std::string> executed_;
  long oks_ = 0, last_n_ = 0;
  bool alarm_ = false;
  std::atomic<bool> critical_{false};  // after ALARM:2, until a soft reset
  double pos_[3] = {0, 0, 0}, feed_ = 0;
};

}  // namespace rosmill::core::test
