// Text that reaches a program cannot become a block: a toolpath file whose tool and strategy names carry
// newlines and G-code posts, for every dialect, to a program in which that text is only ever a comment; words
// that make a comment act (LinuxCNC's MSG, PROBEOPEN; GRBL's real-time characters) are made inert.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.hpp"
#include "rosmill/gcode/comment_text.hpp"
#include "rosmill/gcode/dialect.hpp"
#include "rosmill/gcode/lexer.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"
#include "test_post_jobs.hpp"

using namespace rosmill::core;
using namespace rosmill::core::gcode;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

}  // namespace

TEST(GcodeInjection, NamesWithNewlinesPostAsCommentsOnlyInEveryDialect) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("rosmill_injection_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Toolpath tp = test::raster_toolpath();
  tp.tool.name = "6 mm flat\nG0 Z-40\n(";
  tp.strategy = "raster)\nG1 Z-40 F9999\n";
  const fs::path job = dir / "injected.json";
  write_toolpath_file(job.string(), {tp});
  ASSERT_EQ(read_toolpath_file(job.string()).front().tool.name, tp.tool.name);  // the file carries it as given

  for (const Dialect& d : dialects()) {
    const fs::path program = dir / ("prog_" + d.name + ".ngc");
    const CliRun run = run_rosmill_shell("post " + job.string() + " -o " + program.string() + " --dialect " + d.name +
                                         " --no-limits 2>&1");
    ASSERT_EQ(run.status, 0) << d.name << ": " << run.out;
    size_t mentions = 0;
    for (const std::string& line : lines_of(program)) {
      // The reader sees every line that mentions Z-40 as a comment and nothing else: no word, no motion.
      const Block b = lex_line(line, Place{});
      if (line.find("Z-40") == std::string::npos) continue;
      ++mentions;
      EXPECT_EQ(line.front(), '(') << d.name << ": " << line;
      EXPECT_EQ(b.present, 0u) << d.name << ": " << line;
      EXPECT_EQ(b.g_count + b.m_count, 0) << d.name << ": " << line;
    }
    EXPECT_GE(mentions, 1u) << d.name << ": the names are kept, inert";
  }
  fs::remove_all(dir);
}

TEST(GcodeInjection, EachDialectNeutralisesWhatItsControllerActsOn) {
  const Dialect& linuxcnc = find_dialect("linuxcnc");
  const Dialect& grbl = find_dialect("grbl");
  EXPECT_EQ(comment_line(linuxcnc, "a\r\nG0 Z-40\t(b);c"), "(a  G0 Z-40  b  c)");
  EXPECT_EQ(comment_line(linuxcnc, "msg, stop here"), "(- msg, stop here)");
  EXPECT_EQ(comment_line(linuxcnc, " PROBEOPEN /etc/passwd"), "(-  PROBEOPEN /etc/passwd)");
  EXPECT_EQ(comment_line(linuxcnc, "Message, tool"), "(Message, tool)");  // only the whole word acts
  EXPECT_EQ(comment_line(linuxcnc, "caf\xc3\xa9"), "(caf__)");
  // GRBL takes '?', '!', '~', Ctrl-X and bytes above ASCII from anywhere in the stream.
  EXPECT_EQ(comment_line(grbl, "hold! status? go~ \x18reset \x85jog"), "(hold  status  go   reset _jog)");
  // Cut to the room of an 80-character line.
  EXPECT_EQ(comment_line(grbl, std::string(200, 'x'), 80).size(), 80u);
}
