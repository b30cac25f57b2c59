#include "rosmill/control/transport.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

#include "rosmill/error.hpp"

namespace rosmill::core::control {
namespace {

int ms(double s) { return s <= 0 ? 0 : static_cast<int>(s * 1000.0 + 0.5); }

// A file descriptor (socket or tty) in non-blocking mode, written and read with poll() timeouts.
class FdTransport : public Transport {
 public:
  FdTransport(int fd, std::string peer) : fd_(fd), peer_(std::move(peer)) {}
  ~FdTransport() override {
    if (fd_ >= 0) ::close(fd_);
  }

  void write(const std::string& bytes) override {
    size_t done = 0;
    while (done < bytes.size()) {
      pollfd p{fd_, POLLOUT, 0};
      const int r = ::poll(&p, 1, 5000);
      if (r == 0) throw Error(peer_, "write timed out after 5 s (the controller does not read)");
      if (r < 0 && errno == EINTR) continue;
      if (r < 0) throw Error(peer_, std::string("poll failed: ") + std::strerror(errno));
      const ssize_t n = send_or_write(bytes.data() + done, bytes.size() - done);
      if (n < 0) {
        if (errno == EAGAIN || errno == EINTR) continue;
        throw Error(peer_, std::string("connection lost while writing: ") + std::strerror(errno));
      }
      done += static_cast<size_t>(n);
    }
  }

  bool read_some(std::string& out, double timeout_s) override {
    pollfd p{fd_, POLLIN, 0};
    int r;
    do {
      r = ::poll(&p, 1, ms(timeout_s));
    } while (r < 0 && errno == EINTR);
    if (r < 0) throw Error(peer_, std::string("poll failed: ") + std::strerror(errno));
    if (r == 0) return false;
    char buf[4096];
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n == 0) throw Error(peer_, "connection closed by the controller");
    if (n < 0) {
      if (errno == EAGAIN || errno == EINTR) return false;
      throw Error(peer_, std::string("connection lost while reading: ") + std::strerror(errno));
    }
    out.append(buf, static_cast<size_t>(n));
    return true;
  }

  const std::string& peer() const override { return peer_; }

 private:
  ssize_t send_or_write(const char* data, size_t len) {
    // MSG_NOSIGNAL: a closed socket must become an error, not a SIGPIPE that ends the program.
    ssize_t n = ::send(fd_, data, len, MSG_NOSIGNAL);
    if (n < 0 && errno == ENOTSOCK) n = ::write(fd_, data, len);
    return n;
  }

  int fd_;
  std::string peer_;
};

speed_t baud_constant(int baud, const std::string& where) {
  switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    default: throw Error(where, "unsupported baud rate " + std::to_string(baud));
  }
}

}  // namespace

void split_host_port(const std::string& text, std::string& host, int& port, const std::string& where) {
  const size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0) throw Error(where, "expected HOST:PORT, got '" + text + "'");
  host = text.substr(0, colon);
  try {
    size_t used = 0;
    port = std::stoi(text.substr(colon + 1), &used);
    if (used != text.size() - colon - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw Error(where, "port is not a number in '" + text + "'");
  }
  if (port <= 0 || port > 65535) throw Error(where, "port out of range in '" + text + "'");
}

std::unique_ptr<Transport> open_tcp(const std::string& host, int port, double connect_timeout_s) {
  const std::string peer = host + ":" + std::to_string(port);
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* res = nullptr;
  if (const int rc = ::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &res); rc != 0)
    throw Error(peer, std::string("cannot resolve host: ") + gai_strerror(rc));
  std::string last = "no address";
  for (addrinfo* a = res; a; a = a->ai_next) {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) continue;
    int r = ::connect(fd, a->ai_addr, a->ai_addrlen);
    if (r < 0 && errno == EINPROGRESS) {
      pollfd p{fd, POLLOUT, 0};
      r = ::poll(&p, 1, ms(connect_timeout_s));
      if (r == 0) {
        last = "connection timed out";
        ::close(fd);
        continue;
      }
      int err = 0;
      socklen_t len = sizeof err;
      ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len);
      r = err ? -1 : 0;
      errno = err;
    }
    if (r < 0) {
      last = std::strerror(errno);
      ::close(fd);
      continue;
    }
    const int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);  // line-at-a-time protocols
    ::freeaddrinfo(res);
    return std::make_unique<FdTransport>(fd, peer);
  }
  ::freeaddrinfo(res);
  throw Error(peer, "cannot connect: " + last);
}

std::unique_ptr<Transport> open_serial(const std::string& device, int baud) {
  const speed_t speed = baud_constant(baud, device);
  const int fd = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw Error(device, std::string("cannot open serial port: ") + std::strerror(errno));
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    ::close(fd);
    throw Error(device, "not a serial port (tcgetattr failed)");
  }
  ::cfmakeraw(&tio);  // 8N1, no echo, no line editing, no flow control characters
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~CRTSCTS;
  ::cfsetispeed(&tio, speed);
  ::cfsetospeed(&tio, speed);
  if (::tcsetattr(fd, TCSANOW, &tio) != 0) {
    ::close(fd);
    throw Error(device, std::string("cannot configure the serial port: ") + std::strerror(errno));
  }
  ::tcflush(fd, TCIOFLUSH);
  return std::make_unique<FdTransport>(fd, device);
}

bool LineReader::next(std::string& line, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    const size_t nl = buf_.find('\n');
    if (nl != std::string::npos) {
      line.assign(buf_, 0, nl);
      buf_.erase(0, nl + 1);
      // Controllers end lines with "\r\n" or (linuxcncrsh's acks) "\n\r": drop carriage returns on both sides.
      line.erase(std::remove(line.begin(), line.end(), '\r'), line.end());
      return true;
    }
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) return false;
    t_.read_some(buf_, left);
  }
}

}  // namespace rosmill::core::control
