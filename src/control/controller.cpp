#include "rosmill/control/controller.hpp"

#include <sys/stat.h>

#include <filesystem>

#include "rosmill/control/grbl.hpp"
#include "rosmill/control/linuxcnc.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/post.hpp"

namespace rosmill::core::control {
namespace {

// file:///DIR: the program is written into a folder a controller loads from (a shared folder, a USB stick).
class FileController : public Controller {
 public:
  FileController(std::string dir, const ControllerOptions& o) : dir_(std::move(dir)), opt_(o) {}
  std::string describe() const override { return "file://" + dir_; }
  void connect() override {
    if (!std::filesystem::is_directory(dir_)) throw Error(describe(), "is not a folder");
    status_.state = RunState::Idle;
  }
  void start(const std::vector<std::string>& program, const SendOptions& o) override {
    const std::string path = dir_ + "/" + (opt_.program_name.empty() ? "rosmill.ngc" : opt_.program_name);
    const std::string tmp = path + ".part";
    gcode::write_program_lines(tmp, resumed_program(program, o, opt_.dialect.empty() ? "linuxcnc" : opt_.dialect));
    // Renamed into place so a controller watching the folder never loads half a program.
    std::filesystem::rename(tmp, path);
    status_.total_lines = status_.acknowledged_line = program.size();
    status_.state = RunState::Finished;
  }
  ControllerStatus poll(double) override { return status_; }
  void feed_hold() override { throw Error(describe(), "a folder cannot hold the feed"); }
  void resume() override { throw Error(describe(), "a folder cannot resume"); }
  void abort() override { status_.state = RunState::Idle; }
  void disconnect() override { status_.state = RunState::Disconnected; }

 private:
  std::string dir_;
  ControllerOptions opt_;
  ControllerStatus status_;
};

}  // namespace

const char* run_state_name(RunState s) {
  switch (s) {
    case RunState::Disconnected: return "disconnected";
    case RunState::Idle: return "idle";
    case RunState::Running: return "running";
    case RunState::Paused: return "paused";
    case RunState::Alarm: return "alarm";
    case RunState::Error: return "error";
    case RunState::Finished: return "finished";
  }
  return "?";
}

std::unique_ptr<Controller> open_controller(const std::string& url, const ControllerOptions& o) {
  const size_t sep = url.find("://");
  if (sep == std::string::npos)
    throw Error("--controller", "expected linuxcnc://HOST:PORT, grbl:///dev/ttyX?baud=N, grbl+tcp://HOST:PORT or "
                                "file:///DIR, got '" + url + "'");
  const std::string scheme = url.substr(0, sep), rest = url.substr(sep + 3);
  if (scheme == "linuxcnc") {
    std::string host;
    int port;
    split_host_port(rest, host, port, "--controller " + url);
    return std::make_unique<LinuxcncController>(host, port, o);
  }
  if (scheme == "grbl+tcp") {
    std::string host;
    int port;
    split_host_port(rest, host, port, "--controller " + url);
    return std::make_unique<GrblController>([host, port] { return open_tcp(host, port); }, url, o);
  }
  if (scheme == "grbl") {
    std::string device = rest;
    int baud = 115200;
    const size_t q = rest.find('?');
    if (q != std::string::npos) {
      device = rest.substr(0, q);
      const std::string query = rest.substr(q + 1);
      if (query.rfind("baud=", 0) != 0) throw Error("--controller " + url, "unknown option '" + query + "' (baud=N)");
      try {
        baud = std::stoi(query.substr(5));
      } catch (const std::exception&) {
        throw Error("--controller " + url, "baud is not a number");
      }
    }
    if (device.empty() || device.front() != '/') throw Error("--controller " + url, "expected a device path like /dev/ttyUSB0");
    return std::make_unique<GrblController>([device, baud] { return open_serial(device, baud); }, url, o, 2.5);
  }
  if (scheme == "file") {
    if (rest.empty() || rest.front() != '/') throw Error("--controller " + url, "expected file:///ABSOLUTE/DIR");
    return std::make_unique<FileController>(rest, o);
  }
  throw Error("--controller " + url, "unknown controller kind '" + scheme + "' (linuxcnc, grbl, grbl+tcp, file)");
}

}  // namespace rosmill::core::control
