// The LinuxCNC driver: linuxcncrsh's text protocol over TCP (see linuxcncrsh(1)). Programs run from files on
// the controller's machine, so the driver writes each program (with its resume preamble) into `program_dir`,
// a folder the controller reads, then opens and runs it; status comes from polling.
#pragma once
#include <chrono>
#include <functional>

#include "rosmill/control/controller.hpp"
#include "rosmill/control/transport.hpp"
#include "rosmill/error.hpp"

namespace rosmill::core::control {

class LinuxcncController : public Controller {
 public:
  // `open` makes the connection; empty: TCP to host:port (a test gives another transport).
  LinuxcncController(std::string host, int port, const ControllerOptions& o,
                     std::function<std::unique_ptr<Transport>()> open = {});

  std::string describe() const override;
  void connect() override;
  void start(const std::vector<std::string>& program, const SendOptions& options) override;
  ControllerStatus poll(double timeout_s) override;
  void feed_hold() override;
  void resume() override;
  void abort() override;
  void disconnect() override;

  // One request and its checked reply: "set <what>" must be acknowledged; "get <what>" returns the value.
  void set(const std::string& what);
  std::string get(const std::string& what);

 private:
  std::string reply_for(const std::string& request, const std::string& key);
  size_t program_line_of(size_t file_line) const;
  void lost(const Error& e);

  std::string host_;
  int port_;
  std::function<std::unique_ptr<Transport>()> open_;
  ControllerOptions opt_;
  std::unique_ptr<Transport> transport_;
  std::unique_ptr<LineReader> reader_;
  ControllerStatus status_;
  size_t preamble_lines_ = 0, from_line_ = 1;
  bool seen_running_ = false;
  int file_counter_ = 0;
};

}  // namespace rosmill::core::control
