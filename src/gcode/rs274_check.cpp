#include "rosmill/gcode/rs274_check.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <fstream>
#include <set>
#include <sstream>

#include "rosmill/error.hpp"
#include "rosmill/gcode/arc_fit.hpp"
#include "rosmill/gcode/interpreter.hpp"
#include "rosmill/gcode/lexer.hpp"
#include "rosmill/gcode/number_format.hpp"
#include "rosmill/text_words.hpp"

extern char** environ;

namespace rosmill::core::gcode {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The words of a program line, or nothing when the reader refuses it (rs274 then names the line itself).
std::optional<Block> words_of(const std::string& line) {
  try {
    return lex_line(line, Place{});
  } catch (const Error&) {
    return std::nullopt;
  }
}

// Tool numbers the program selects (its T words), for rs274's tool table.
std::set<int> tools_used(const std::vector<std::string>& lines) {
  std::set<int> tools;
  for (const std::string& l : lines)
    if (const auto b = words_of(l); b && b->has('T') && b->get('T') >= 0) tools.insert(static_cast<int>(b->get('T')));
  return tools;
}

// Numbers between the parentheses of "NAME(a, b, ...)".
std::vector<double> arguments(const std::string& line, size_t open) {
  std::vector<double> v;
  const char* p = line.c_str() + open + 1;
  while (*p && *p != ')') {
    char* end = nullptr;
    const double x = std::strtod(p, &end);
    if (end == p) break;
    v.push_back(x);
    p = end;
    while (*p == ',' || *p == ' ') ++p;
  }
  return v;
}

bool moves_axes(const std::string& line) {
  const auto b = words_of(line);
  return b && b->has_axis();
}

// rs274 ends its complaint with the block it refused. The program line holding that block: the first such line
// after the motion lines it carried out (the same block may occur earlier), else the first anywhere.
size_t offending_line(const std::vector<std::string>& lines, const std::string& message, size_t moves_done) {
  const size_t nl = message.find_last_of('\n');
  const std::string block = trimmed(nl == std::string::npos ? message : message.substr(nl + 1));
  if (block.empty()) return 0;
  size_t motion = 0, first = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (trimmed(lines[i]) == block) {
      if (motion >= moves_done) return i + 1;
      if (!first) first = i + 1;
    }
    motion += moves_axes(lines[i]);
  }
  return first;
}

class TempDir {
 public:
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "rosmill-rs274-XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw Error("rs274", "cannot create a temporary folder");
    path_ = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

}  // namespace

std::vector<CanonMove> parse_canon(const std::string& text) {
  std::vector<CanonMove> moves;
  double feed = 0.0, scale = 1.0;
  Plane plane = Plane::XY;
  Vec3 at = Vec3::Zero();
  uint8_t known = 0;
  std::istringstream in(text);
  std::string line;
  uint32_t n = 0;
  while (std::getline(in, line)) {
    ++n;
    size_t at_call;
    if ((at_call = line.find("SET_FEED_RATE(")) != std::string::npos) {
      auto a = arguments(line, line.find('(', at_call));
      if (!a.empty()) feed = a[0] * scale;
      continue;
    }
    // Canonical numbers are in the program's units (G20 inches, G21 mm) and program coordinates.
    if (line.find("USE_LENGTH_UNITS(") != std::string::npos) {
      scale = line.find("CANON_UNITS_INCHES") != std::string::npos ? 25.4
              : line.find("CANON_UNITS_CM") != std::string::npos ? 10.0 : 1.0;
      continue;
    }
    if (line.find("SELECT_PLANE(") != std::string::npos) {
      plane = line.find("CANON_PLANE_XZ") != std::string::npos   ? Plane::ZX
              : line.find("CANON_PLANE_YZ") != std::string::npos ? Plane::YZ : Plane::XY;
      continue;
    }
    CanonMove m;
    m.source = n;
    if ((at_call = line.find("STRAIGHT_TRAVERSE(")) != std::string::npos) {
      m.rapid = true;
    } else if ((at_call = line.find("STRAIGHT_FEED(")) == std::string::npos &&
               (at_call = line.find("ARC_FEED(")) == std::string::npos) {
      continue;
    }
    const auto a = arguments(line, line.find('(', at_call));
    if (line.compare(at_call, 9, "ARC_FEED(") == 0) {
      if (a.size() < 6) throw Error("rs274 output line " + std::to_string(n), "ARC_FEED with too few arguments");
      // ARC_FEED(first end, second end, first centre, second centre, rotation, axis end, ...) in the plane's axes.
      const PlaneAxes ax = plane_axes(plane);
      m.to[ax.first] = a[0] * scale;
      m.to[ax.second] = a[1] * scale;
      m.to[ax.normal] = a[5] * scale;
      m.centre = Vec2(a[2], a[3]) * scale;
      m.shape = a[4] < 0 ? MoveShape::ArcCW : MoveShape::ArcCCW;
      m.turns = static_cast<uint8_t>(std::abs(a[4]));
      m.plane = plane;
    } else {
      if (a.size() < 3) throw Error("rs274 output line " + std::to_string(n), "move with too few arguments");
      m.to = Vec3(a[0], a[1], a[2]) * scale;
    }
    m.from = at;
    m.known_from = known;
    at = m.to;
    known = 7;
    m.feed = m.rapid ? 0.0f : static_cast<float>(feed);
    moves.push_back(m);
  }
  return moves;
}

Rs274Result run_rs274(const std::vector<std::string>& lines, const std::string& executable) {
  TempDir dir;
  const fs::path program = dir.path() / "program.ngc", out = dir.path() / "canon.txt", log = dir.path() / "log.txt",
                 table = dir.path() / "tools.tbl";
  {
    // The trunnion's kinematics switches (M428, M429) are remaps of the machine's configuration, which the standalone
    // interpreter cannot run (it stops at them): they are read as comments, one line for one as the program has them.
    std::ofstream p(program);
    for (const auto& l : lines) {
      if (switches_kinematics(l))
        p << "(" << l << ": a kinematics switch the controller runs)\n";
      else
        p << l << '\n';
    }
    std::ofstream t(table);
    for (int id : tools_used(lines)) t << 'T' << id << " P" << id << " Z0 D1 ;rosmill verification\n";
    if (!p || !t) throw Error("rs274", "cannot write into " + dir.path().string());
  }
  const std::string logs = log.string(), dirs = dir.path().string();
  std::vector<std::string> args = {executable, "-t", table.string(), "-g", program.string(), out.string()};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, logs.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawn_file_actions_addchdir_np(&actions, dirs.c_str());
  // LinuxCNC 2.9 keeps the loaded tool table in $HOME/.tool.mmap: runs side by side would read each other's
  // tables, so each run gets its own HOME (the temporary folder).
  std::vector<std::string> env_strings;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "HOME=", 5) != 0) env_strings.emplace_back(*e);
  env_strings.push_back("HOME=" + dirs);
  std::vector<char*> envp;
  for (auto& e : env_strings) envp.push_back(e.data());
  envp.push_back(nullptr);
  pid_t pid;
  const int rc = posix_spawnp(&pid, executable.c_str(), &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0)
    throw Error("rs274", "cannot start '" + executable + "' (package linuxcnc-uspace): " + std::strerror(rc));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  Rs274Result r;
  r.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.moves = parse_canon(slurp(out));
  std::string message = slurp(log);
  // rs274 prints "executing" as it starts; what follows is its complaint and the block it refused.
  for (size_t p; (p = message.find("executing")) != std::string::npos;) message.erase(p, 9);
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.front()))) message.erase(0, 1);
  r.ok = r.exit_status == 0 && message.empty();
  if (!r.ok) {
    r.error = message.empty() ? "rs274 exited with status " + std::to_string(r.exit_status) : message;
    r.error_line = offending_line(lines, message, r.moves.size());
  }
  return r;
}

namespace {

// Walks the toolpath moves in order alongside the program's motion lines.
struct JobCursor {
  const Job& job;
  size_t t = 0, p = 0, k = 0;
  const Move* current() const {
    if (t >= job.size() || p >= job[t].passes.size() || k >= job[t].passes[p].moves.size()) return nullptr;
    return &job[t].passes[p].moves[k];
  }
};

std::string where(const LineOrigin& o) {
  return "toolpath " + std::to_string(o.toolpath) + ", pass " + std::to_string(o.pass) + ", move " +
         std::to_string(o.first_move);
}

}  // namespace

VerifyReport compare_with_job(const Program& program, const Job& job, const Rs274Result& rs, double arc_tolerance) {
  VerifyReport rep;
  rep.canon_moves = rs.moves.size();
  for (const Toolpath& tp : job) rep.toolpath_moves += tp.move_count();
  if (!rs.ok) {
    rep.problem = "rs274 refused the program: " + rs.error;
    return rep;
  }
  // Written numbers are rounded to the program's decimals; rs274 prints four decimals.
  const double precision = 0.5 / static_cast<double>(decimal_scale(program.decimals)) + 0.5e-4 + 1e-9;
  // Every line that moves the machine yields one canonical move, in rs274's output as in the reader's.
  size_t c = 0;
  Vec3 at = Vec3::Constant(NAN);
  auto fail = [&](size_t line, const std::string& what) {
    rep.problem = "program line " + std::to_string(line + 1) + " (" + program.lines[line] + "): " + what;
    return rep;
  };
  std::vector<std::vector<bool>> done;  // per toolpath, flattened moves carried out
  for (const Toolpath& tp : job) done.emplace_back(tp.move_count(), false);
  auto flat_index = [&](int t, int p, int k) {
    size_t i = 0;
    for (int q = 0; q < p; ++q) i += job[t].passes[q].moves.size();
    return i + static_cast<size_t>(k);
  };
  Interpreter reader;
  for (size_t i = 0; i < program.lines.size(); ++i) {
    reader.read(program.lines[i], i + 1);
    const LineOrigin& o = program.origin[i];
    if (!reader.moved()) {
      // A move in machine coordinates (G53, the retract before a trunnion indexes): rs274 traverses there; the
      // reader leaves the position unknown. Nothing of a toolpath to compare.
      if (reader.block().has_g(530) && reader.block().has_axis()) {
        if (c >= rs.moves.size()) return fail(i, "rs274 produced no move for this line");
        at = rs.moves[c++].to;
      }
      continue;
    }
    if (c >= rs.moves.size()) return fail(i, "rs274 produced no move for this line");
    const CanonMove& m = rs.moves[c++];
    if (o.first_move >= 0) {
      const auto& moves = job[o.toolpath].passes[o.pass].moves;
      const Move& last = moves[o.last_move];
      const double dev = (m.to - last.to).cwiseAbs().maxCoeff();
      rep.max_deviation = std::max(rep.max_deviation, dev);
      if (dev > precision)
        return fail(i, "ends " + std::to_string(dev) + " mm from the toolpath point (" + where(o) + ")");
      const bool rapid = last.type == MoveType::Rapid;
      if (reader.state().feed_mode == 93) {
        // Inverse time (a multi-axis program): every move a feed, none faster at the tip than the toolpath's feed
        // (slower where the table's joints need the time); rs274 prints F times the length.
        if (m.rapid) return fail(i, "a rapid under inverse time (G93)");
        if (!rapid && m.feed > last.feed * (1 + 1e-3) + 0.05)
          return fail(i, "feed " + std::to_string(m.feed) + " over the toolpath's " + std::to_string(last.feed));
      } else if (rapid != m.rapid) {
        return fail(i, "rapid/feed kind differs from " + where(o));
      } else if (!rapid && std::abs(m.feed - last.feed) > 0.05 + 1e-9) {
        return fail(i, "feed " + std::to_string(m.feed) + " differs from the toolpath's " + std::to_string(last.feed));
      }
      if (m.is_arc()) {
        if (!std::isfinite(at.x())) return fail(i, "arc from an unknown position");
        for (int k = o.first_move; k < o.last_move; ++k) {
          const double d =
              distance_to_arc(moves[k].to.head<2>(), at.head<2>(), m.to.head<2>(), m.centre, m.clockwise());
          rep.max_deviation = std::max(rep.max_deviation, d);
          if (d > arc_tolerance + 2 * precision || std::abs(moves[k].to.z() - m.to.z()) > precision)
            return fail(i, "the arc passes " + std::to_string(d) + " mm from toolpath move " + std::to_string(k));
        }
      } else if (o.first_move != o.last_move) {
        return fail(i, "a straight move stands for several toolpath moves");
      }
      for (int k = o.first_move; k <= o.last_move; ++k) done[o.toolpath][flat_index(o.toolpath, o.pass, k)] = true;
    }
    at = m.to;
  }
  if (c != rs.moves.size()) {
    rep.problem =
        "rs274 produced " + std::to_string(rs.moves.size() - c) + " more moves than the program has motion lines";
    return rep;
  }
  // Moves shorter than the precision are left out of the program; any other toolpath move must be there.
  for (size_t t = 0; t < job.size(); ++t) {
    size_t flat = 0;
    Vec3 prev = job[t].start;
    for (size_t p = 0; p < job[t].passes.size(); ++p)
      for (size_t k = 0; k < job[t].passes[p].moves.size(); ++k, ++flat) {
        const Vec3& to = job[t].passes[p].moves[k].to;
        if (!done[t][flat] && (to - prev).cwiseAbs().maxCoeff() > 2 * precision) {
          rep.problem = "toolpath " + std::to_string(t) + ", pass " + std::to_string(p) + ", move " +
                        std::to_string(k) + " is missing from the program";
          return rep;
        }
        prev = to;
      }
  }
  rep.ok = true;
  return rep;
}

}  // namespace rosmill::core::gcode
