// A controller's side of the connection played from the fuzz input: its bytes arrive in small pieces (so the line
// reader sees lines split anywhere), and at their end the peer closes the connection, as a controller that goes
// away does. What the driver writes is counted, not interpreted.
#pragma once
#include <algorithm>
#include <memory>
#include <string>

#include "rosmill/control/transport.hpp"
#include "rosmill/error.hpp"

namespace rosmill::fuzz {

class ScriptedPeer : public core::control::Transport {
 public:
  explicit ScriptedPeer(std::string replies) : replies_(std::move(replies)) {}
  void write(const std::string& bytes) override {
    if (at_ >= replies_.size()) throw core::Error(peer_, "connection closed by the peer");
    written_ += bytes.size();
  }
  bool read_some(std::string& out, double) override {
    if (at_ >= replies_.size()) throw core::Error(peer_, "connection closed by the peer");
    // Piece sizes 1..13 bytes, from the position: deterministic for one input, varied across lines.
    const size_t n = std::min(replies_.size() - at_, size_t(1) + (at_ * 7 + 3) % 13);
    out.append(replies_, at_, n);
    at_ += n;
    return true;
  }
  const std::string& peer() const override { return peer_; }

 private:
  std::string replies_, peer_ = "fuzz peer";
  size_t at_ = 0, written_ = 0;
};

}  // namespace rosmill::fuzz
