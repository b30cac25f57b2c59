// The long commands' progress bar: drawn on a terminal (a pseudo-terminal here, as a person's shell gives),
// with the operation, the percent and the time left; silent when stderr is a pipe or the output is JSON.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

#include "cli_run.hpp"

namespace {

// Runs `rosmill args` with stderr on a new pseudo-terminal (stdout to /dev/null); what the terminal received.
std::string stderr_on_terminal(const std::string& args, int& status) {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0) return "no pseudo-terminal";
  const std::string slave = ptsname(master);
  const pid_t child = fork();
  if (child == 0) {
    setsid();
    const int tty = open(slave.c_str(), O_RDWR);
    const int null = open("/dev/null", O_WRONLY);
    if (tty < 0 || null < 0) _exit(127);
    dup2(tty, STDERR_FILENO);
    dup2(null, STDOUT_FILENO);
    execl("/bin/sh", "sh", "-c", (std::string(ROSMILL_CLI) + " " + args).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  std::string got;
  char buf[4096];
  for (;;) {
    pollfd p{master, POLLIN, 0};
    if (poll(&p, 1, 200) > 0) {
      const ssize_t n = read(master, buf, sizeof buf);
      if (n > 0) {
        got.append(buf, static_cast<size_t>(n));
        continue;
      }
    }
    int st = 0;
    if (waitpid(child, &st, WNOHANG) == child) {
      // Drain what is still buffered in the terminal.
      while (poll(&p, 1, 100) > 0) {
        const ssize_t n = read(master, buf, sizeof buf);
        if (n <= 0) break;
        got.append(buf, static_cast<size_t>(n));
      }
      status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
      break;
    }
  }
  close(master);
  return got;
}

const std::string kJob = std::string("'") + ROSMILL_SOURCE_DIR + "/config/jobs/rest_pocket.yaml'";

}  // namespace

TEST(CliProgress, JobDrawsABarOnATerminal) {
  int status = -1;
  const std::string tty = stderr_on_terminal("job " + kJob, status);
  EXPECT_EQ(status, 0) << tty;
  // Redrawn in place: a carriage return, the operation by name and number, a percent, the time left, and the
  // line cleared at the end.
  EXPECT_NE(tty.find('\r'), std::string::npos) << tty;
  EXPECT_NE(tty.find("rough (1/3"), std::string::npos) << tty;
  EXPECT_NE(tty.find("rest (3/3"), std::string::npos) << tty;
  EXPECT_NE(tty.find("%"), std::string::npos) << tty;
  EXPECT_NE(tty.find(" left"), std::string::npos) << tty;
  EXPECT_NE(tty.rfind("\r\033[K"), std::string::npos) << tty;
}

TEST(CliProgress, SilentOnAPipeAndWithJson) {
  const CliRun piped = run_rosmill("job " + kJob);
  EXPECT_EQ(piped.status, 0) << piped.err;
  EXPECT_EQ(piped.err.find('\r'), std::string::npos) << piped.err;
  EXPECT_EQ(piped.err.find(" left"), std::string::npos) << piped.err;
  int status = -1;
  const std::string tty = stderr_on_terminal("job " + kJob + " --json", status);
  EXPECT_EQ(status, 0) << tty;
  EXPECT_EQ(tty.find('\r'), std::string::npos) << tty;
}
