// Runs the rosmill command-line tool (ROSMILL_CLI) from a test: its exit status, what it printed on stdout and on
// stderr. Shared by the tests of the sub-commands.
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

struct CliRun {
  int status = -1;
  std::string out, err;
};

// Runs `ROSMILL_CLI shell_args` through the shell (so `shell_args` may end in a redirection such as 2>&1) and
// captures its stdout and exit status.
inline CliRun run_command(const std::string& command) {
  CliRun run;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return run;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) run.out.append(buf, n);
  const int rc = ::pclose(pipe);
  run.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  return run;
}

inline CliRun run_rosmill_shell(const std::string& shell_args) {
  return run_command(std::string(ROSMILL_CLI) + " " + shell_args);
}

// `ROSMILL_CLI shell_args` run from the folder `dir`.
inline CliRun run_rosmill_in(const std::string& dir, const std::string& shell_args) {
  return run_command("cd '" + dir + "' && " + ROSMILL_CLI + " " + shell_args);
}

// Stdout and stderr apart.
inline CliRun run_rosmill(const std::string& args) {
  const std::string err_path = ::testing::TempDir() + "/rosmill_stderr_" + std::to_string(::getpid()) + ".txt";
  CliRun run = run_rosmill_shell(args + " 2>" + err_path);
  std::ifstream err(err_path);
  std::stringstream ss;
  ss << err.rdbuf();
  run.err = ss.str();
  std::remove(err_path.c_str());
  return run;
}
