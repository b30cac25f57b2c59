// GRBL over a serial port or TCP: character-counting streaming (the documented way to keep GRBL's 128-byte
// receive buffer full without overflowing it): the sender counts the bytes of every line sent and not yet
// answered, and sends the next line only when it fits. Every "ok" or "error:N" answers the oldest such line.
#include "rosmill/control/grbl.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>

#include "rosmill/error.hpp"
#include "rosmill/gcode/lexer.hpp"
#include "rosmill/seconds_since.hpp"

namespace rosmill::core::control {
namespace {

using Clock = std::chrono::steady_clock;

// GRBL's receive buffer holds the line's code: the reader's first step (comments and spaces out) saves room.
std::string compact(const std::string& line, const std::string& where) {
  return gcode::code_of(line, gcode::Place{where, 0});
}

// x,y,z of a status report's position field ("1.000,2.000,3.000", more axes after them ignored). A field cut short
// or garbled is not a position: false, and the position stays what it was, rather than numbers read past it.
bool read_position(const std::string& field, Vec3& position) {
  const char* p = field.c_str();
  for (int a = 0; a < 3; ++a) {
    char* end = nullptr;
    position[a] = std::strtod(p, &end);
    if (end == p || !std::isfinite(position[a])) return false;
    if (*end != (a < 2 ? ',' : '\0') && !(a == 2 && *end == ',')) return false;
    p = end + 1;
  }
  return true;
}

}  // namespace

GrblController::GrblController(std::function<std::unique_ptr<Transport>()> open, std::string describe,
                               const ControllerOptions& o, double greeting_wait_s)
    : open_(std::move(open)), describe_(std::move(describe)), opt_(o), greeting_wait_s_(greeting_wait_s) {}

std::string GrblController::describe() const { return describe_; }

void GrblController::connect() {
  transport_ = open_();
  reader_ = std::make_unique<LineReader>(*transport_);
  status_ = ControllerStatus{};
  status_.state = RunState::Idle;
  forget_buffer();
  // A serial GRBL resets when the port opens (its bootloader waits about a second) and greets with
  // "Grbl 1.1x ['$' for help]"; a TCP bridge may not greet at all. A greeting that came only once a program
  // streams would read as a reset in the middle of it, so wait for it here.
  std::string line;
  const auto start = Clock::now();
  while (seconds_since(start) < greeting_wait_s_ && reader_->next(line, greeting_wait_s_ - seconds_since(start))) {
    handle_line(line);
    if (line.rfind("Grbl ", 0) == 0) break;
  }
}

void GrblController::forget_buffer() {
  in_flight_.clear();
  buffered_ = 0;
}

void GrblController::start(const std::vector<std::string>& program, const SendOptions& o) {
  if (!transport_) throw Error(describe_, "not connected");
  // Lines of an earlier program still in GRBL's buffer would take this program's first answers.
  if (!in_flight_.empty())
    throw Error(describe_, std::to_string(in_flight_.size()) +
                               " lines of the previous program are still unanswered: abort (soft reset) first");
  queue_.clear();
  next_ = 0;
  error_line_ = 0;
  ran_after_error_ = 0;
  for (const std::string& pre : resume_preamble(program, o, opt_.dialect.empty() ? "grbl" : opt_.dialect)) {
    const std::string text = compact(pre, describe_ + " resume preamble");
    if (!text.empty()) queue_.push_back({text, 0});
  }
  const std::vector<std::string> rest = resumed_rest(program, o.from_line);
  for (size_t i = o.from_line; i <= program.size(); ++i) {
    const std::string text = compact(rest[i - o.from_line], describe_ + " line " + std::to_string(i));
    if (text.empty() || text == "%") continue;  // nothing for GRBL to answer
    if (text.size() + 1 > opt_.rx_buffer)
      throw Error(describe_ + " line " + std::to_string(i), "longer than GRBL's receive buffer: " + text);
    queue_.push_back({text, i});
  }
  status_.total_lines = program.size();
  status_.acknowledged_line = o.from_line - 1;
  status_.current_line = 0;
  status_.error.clear();
  status_.state = RunState::Running;
  last_heard_ = Clock::now();
  try {
    pump();
  } catch (const Error& e) {
    connection_lost(e);
  }
}

void GrblController::pump() {
  // Character counting: send while the line fits in what GRBL's buffer has free.
  std::string batch;
  while (next_ < queue_.size() && status_.state == RunState::Running) {
    const size_t need = queue_[next_].text.size() + 1;
    if (buffered_ + need > opt_.rx_buffer) break;
    batch += queue_[next_].text;
    batch.push_back('\n');
    in_flight_.push_back(next_);
    buffered_ += need;
    ++next_;
  }
  if (!batch.empty()) transport_->write(batch);
}

void GrblController::handle_line(const std::string& line) {
  if (line.empty()) return;
  last_heard_ = Clock::now();
  if (line == "ok" || line.rfind("error:", 0) == 0) {
    if (in_flight_.empty()) {
      if (line != "ok") status_.error = "GRBL " + line + " for a line rosmill did not send";
      return;  // an "ok" for a command outside the stream ($X)
    }
    machine_state_.clear();  // only a status report after this answer tells whether the machine is done
    const Item& item = queue_[in_flight_.front()];
    buffered_ -= item.text.size() + 1;
    in_flight_.pop_front();
    if (line == "ok") {
      // After a refused line GRBL goes on with what it had buffered; those lines ran, but "acknowledged" means
      // every line up to it was accepted, so it stays before the refused one.
      if (error_line_) ran_after_error_ = std::max(ran_after_error_, item.line);
      else if (item.line > 0) status_.acknowledged_line = item.line;
    } else if (status_.state != RunState::Alarm && !error_line_) {  // after an alarm GRBL refuses all (error:9)
      status_.state = RunState::Error;
      error_line_ = item.line ? item.line : status_.acknowledged_line + 1;
      error_text_ = "GRBL " + line + (item.line ? " at program line " + std::to_string(item.line) : " in the resume preamble") +
                    ": " + item.text;
      status_.error = error_text_;
    }
    return;
  }
  if (line.rfind("ALARM:", 0) == 0) {
    status_.state = RunState::Alarm;
    status_.error = "GRBL " + line + " after program line " + std::to_string(status_.acknowledged_line) +
                    " (unlock with $X only once the machine is safe)";
    return;
  }
  if (line.front() == '<') {
    parse_status(line);
    return;
  }
  if (line.rfind("Grbl ", 0) == 0) {
    // A greeting means the controller reset: what it had buffered is gone and will never be answered.
    forget_buffer();
    if (status_.state == RunState::Running || status_.state == RunState::Paused) {
      status_.state = RunState::Error;
      status_.error = "GRBL reset while running (after program line " + std::to_string(status_.acknowledged_line) + ")";
    }
  }
}

void GrblController::parse_status(const std::string& s) {
  // <Idle|MPos:1.000,2.000,3.000|FS:0,0|...>
  const size_t bar = s.find('|');
  const std::string state = s.substr(1, (bar == std::string::npos ? s.size() - 1 : bar) - 1);
  machine_state_ = state.substr(0, state.find(':'));
  if (machine_state_ == "Hold" && status_.state == RunState::Running) status_.state = RunState::Paused;
  if (machine_state_ == "Alarm") status_.state = RunState::Alarm;
  for (const char* key : {"MPos:", "WPos:"}) {
    const size_t at = s.find(key);
    if (at == std::string::npos) continue;
    Vec3 position;
    if (!read_position(s.substr(at + 5, s.find_first_of("|>", at) - (at + 5)), position)) continue;
    status_.position = position;
    status_.position_known = true;
  }
  const size_t ln = s.find("Ln:");
  if (ln != std::string::npos) status_.current_line = std::strtoul(s.c_str() + ln + 3, nullptr, 10);
  else status_.current_line = status_.acknowledged_line < status_.total_lines ? status_.acknowledged_line + 1 : 0;
}

ControllerStatus GrblController::poll(double timeout_s) {
  if (!transport_) {
    status_.state = RunState::Disconnected;
    return status_;
  }
  const auto start = Clock::now();
  try {
    if (seconds_since(last_status_) >= opt_.status_interval_s) {
      transport_->write("?");  // real-time: not part of the buffer count
      last_status_ = Clock::now();
    }
    std::string line;
    while (reader_->next(line, std::max(0.0, timeout_s - seconds_since(start)))) {
      handle_line(line);
      if (status_.state == RunState::Running) pump();
      if (seconds_since(start) >= timeout_s) break;
    }
    if (status_.state == RunState::Running) pump();
  } catch (const Error& e) {
    connection_lost(e);
    return status_;
  }
  if (error_line_ && ran_after_error_ > error_line_)
    status_.error = error_text_ + "; lines " + std::to_string(error_line_ + 1) + ".." + std::to_string(ran_after_error_) +
                    " were already in GRBL's buffer and ran";
  const bool all_answered = next_ == queue_.size() && in_flight_.empty();
  if ((status_.state == RunState::Running || status_.state == RunState::Paused) && all_answered &&
      machine_state_ == "Idle") {
    status_.state = RunState::Finished;
    status_.acknowledged_line = status_.total_lines;
  }
  if (status_.state == RunState::Running && !in_flight_.empty() && seconds_since(last_heard_) > opt_.reply_timeout_s) {
    status_.state = RunState::Error;
    status_.error = "GRBL did not answer for " + std::to_string(opt_.reply_timeout_s) + " s (after program line " +
                    std::to_string(status_.acknowledged_line) + ")";
  }
  return status_;
}

void GrblController::read_answers_left() {
  // Bounded: a peer that is gone ends the stream at once; one that still talks (a write that timed out) gets
  // a short while, never an endless wait.
  const auto start = Clock::now();
  std::string line;
  try {
    while (seconds_since(start) < 0.5 && reader_->next(line, 0.05)) handle_line(line);
  } catch (const Error&) {
    // The end of the stream or the reset itself: nothing more will arrive.
  }
}

void GrblController::connection_lost(const Error& e) {
  // The failure is often found by a write (broken pipe) while answers GRBL sent before the drop still wait to be
  // read. Each of them is a line that ran: count it, or resuming would send that line, and run it, twice.
  read_answers_left();
  // What is still unanswered was sent and may or may not have run: GRBL's protocol cannot tell. Resuming from
  // the first of them is the only choice that loses nothing; say plainly that it may repeat them.
  size_t first = 0, last = 0, preamble = 0;
  for (size_t i : in_flight_) {
    const size_t line = queue_[i].line;
    if (line == 0) ++preamble;
    else if (!first) first = line;
    if (line) last = line;
  }
  std::string unknown;
  if (first)
    unknown = "; program lines " + std::to_string(first) + ".." + std::to_string(last) +
              " were sent but not answered: they may have run, check the machine before resuming";
  else if (preamble)
    unknown = "; " + std::to_string(preamble) + " resume preamble lines were sent but not answered";
  const std::string earlier = status_.state == RunState::Error || status_.state == RunState::Alarm ? status_.error : "";
  transport_.reset();
  reader_.reset();
  forget_buffer();
  status_.state = RunState::Disconnected;
  status_.error = std::string(e.what()) + " (after program line " + std::to_string(status_.acknowledged_line) +
                  " was acknowledged)" + unknown + (earlier.empty() ? "" : "; before that: " + earlier);
}

void GrblController::feed_hold() {
  if (transport_) transport_->write("!");
  if (status_.state == RunState::Running) status_.state = RunState::Paused;
}

void GrblController::resume() {
  if (transport_) transport_->write("~");
  if (status_.state == RunState::Paused) status_.state = RunState::Running;
}

void GrblController::abort() {
  // Soft reset (0x18): GRBL stops at once and empties its buffers; nothing of ours is in flight any more.
  forget_buffer();
  next_ = queue_.size();
  status_.state = RunState::Idle;
  if (!transport_) return;
  transport_->write(std::string(1, '\x18'));
  // GRBL greets again after the reset; wait for it so it is not taken for a reset during the next program.
  std::string line;
  const auto start = Clock::now();
  while (seconds_since(start) < opt_.reply_timeout_s) {
    if (!reader_->next(line, opt_.reply_timeout_s - seconds_since(start))) break;
    if (line.rfind("Grbl ", 0) == 0) return;
  }
  throw Error(describe_, "no greeting after the soft reset within " + std::to_string(opt_.reply_timeout_s) + " s");
}

void GrblController::unlock() {
  if (!transport_) throw Error(describe_, "not connected");
  if (!in_flight_.empty()) throw Error(describe_, "cannot unlock while program lines are unanswered: abort first");
  // Outside the stream: wait for its answer here, so that it is not taken for the next program line's.
  transport_->write("$X\n");
  std::string line;
  const auto start = Clock::now();
  while (seconds_since(start) < opt_.reply_timeout_s && reader_->next(line, opt_.reply_timeout_s - seconds_since(start))) {
    if (line == "ok") {
      if (status_.state == RunState::Alarm) status_.state = RunState::Idle;
      return;
    }
    if (line.rfind("error:", 0) == 0) throw Error(describe_, "GRBL refused the unlock ($X): " + line);
    handle_line(line);
  }
  throw Error(describe_, "no answer to the unlock ($X) within " + std::to_string(opt_.reply_timeout_s) + " s");
}

void GrblController::disconnect() {
  transport_.reset();
  reader_.reset();
  status_.state = RunState::Disconnected;
}

}  // namespace rosmill::core::control
