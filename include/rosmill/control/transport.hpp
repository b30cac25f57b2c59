// Byte streams to controllers: TCP sockets and serial ports (termios), with timeouts. Every failure throws
// Error naming the peer; a peer that closes the connection is reported as such, not as an empty read.
#pragma once
#include <memory>
#include <string>

namespace rosmill::core::control {

class Transport {
 public:
  virtual ~Transport() = default;
  // Writes everything or throws (timeout, connection lost).
  virtual void write(const std::string& bytes) = 0;
  // Appends what arrives within `timeout_s` (at least one byte, or nothing on timeout) to `out`; returns false
  // on timeout. Throws Error when the peer closed the connection.
  virtual bool read_some(std::string& out, double timeout_s) = 0;
  virtual const std::string& peer() const = 0;
};

std::unique_ptr<Transport> open_tcp(const std::string& host, int port, double connect_timeout_s = 5.0);
std::unique_ptr<Transport> open_serial(const std::string& device, int baud);

// Splits "HOST:PORT"; throws Error naming `where`.
void split_host_port(const std::string& text, std::string& host, int& port, const std::string& where);

// Reads complete lines (ended by '\n'; '\r' dropped) from a transport.
class LineReader {
 public:
  explicit LineReader(Transport& t) : t_(t) {}
  // The next line, or false when none is complete within `timeout_s`.
  bool next(std::string& line, double timeout_s);

 private:
  Transport& t_;
  std::string buf_;
};

}  // namespace rosmill::core::control
