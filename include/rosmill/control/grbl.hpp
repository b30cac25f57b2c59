// The GRBL driver (see controller.hpp for the interface, src/control/grbl.cpp for the streaming protocol).
#pragma once
#include <chrono>
#include <deque>
#include <functional>

#include "rosmill/control/controller.hpp"
#include "rosmill/control/transport.hpp"

namespace rosmill::core {
class Error;
}

namespace rosmill::core::control {

class GrblController : public Controller {
 public:
  // `open` makes a new connection (serial port or TCP); called by connect(), again after a lost connection.
  // connect() waits up to `greeting_wait_s` for GRBL's greeting (a serial board resets when its port opens).
  GrblController(std::function<std::unique_ptr<Transport>()> open, std::string describe, const ControllerOptions& o,
                 double greeting_wait_s = 0.5);

  std::string describe() const override;
  void connect() override;
  void start(const std::vector<std::string>& program, const SendOptions& options) override;
  ControllerStatus poll(double timeout_s) override;
  void feed_hold() override;
  void resume() override;
  void abort() override;
  void unlock() override;
  void disconnect() override;

  size_t bytes_in_flight() const { return buffered_; }

 private:
  struct Item {
    std::string text;  // as sent, without the newline
    size_t line;       // program line (1-based); 0 for resume preamble lines
  };
  void pump();
  void forget_buffer();  // GRBL's receive buffer is empty (reset, new connection)
  void handle_line(const std::string& line);
  void parse_status(const std::string& report);
  void read_answers_left();                // after a transport failure: the answers that arrived before it
  void connection_lost(const Error& e);    // the transport failed: count what arrived, report what is unknown

  std::function<std::unique_ptr<Transport>()> open_;
  std::string describe_;
  ControllerOptions opt_;
  std::unique_ptr<Transport> transport_;
  std::unique_ptr<LineReader> reader_;
  std::vector<Item> queue_;
  std::deque<size_t> in_flight_;  // indices into queue_, oldest first
  size_t next_ = 0;
  size_t buffered_ = 0;           // bytes sent and not yet answered
  std::string machine_state_;
  size_t error_line_ = 0;       // program line GRBL refused (error:N); 0: none
  size_t ran_after_error_ = 0;  // last line answered "ok" after the refused one
  std::string error_text_;
  double greeting_wait_s_;
  ControllerStatus status_;
  std::chrono::steady_clock::time_point last_heard_{}, last_status_{};
};

}  // namespace rosmill::core::control
