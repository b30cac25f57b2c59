// rostest: one job run both ways, `rosmill job --json` as a process and the planner's plan_job action (see
// job_both_ways.test), gives the same report field by field. The machine keeps links 5 mm over the stock, not the
// 2 mm of a job without one, so a front end that builds the job's options without the machine's clearance differs
// in every link.
#include <actionlib/client/simple_action_client.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <ros/ros.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "rosmill/PlanJobAction.h"
#include "rostest_support.hpp"

using Client = actionlib::SimpleActionClient<rosmill::PlanJobAction>;

namespace {

const std::string kJob = std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/box_cube.yaml";
const std::string kConfig = std::string(ROSMILL_SOURCE_DIR) + "/config/";

// The report's fields that measure how long the run took on this computer, not what the job does: the only ones
// left out of the comparison.
const std::set<std::string> kTimings = {"plan_seconds", "engagement_seconds", "remove_seconds", "verify_seconds",
                                        "seconds"};

struct CliReport {
  int status = -1;
  nlohmann::json report;
};

// `rosmill job JOB --json` with the machine, tools and presets the planner node was given.
CliReport cli_report(const std::string& job, const std::string& machine) {
  const std::string command = std::string(ROSMILL_CLI) + " job '" + job + "' --json --machine '" + machine +
                              "' --tools '" + kConfig + "tools.yaml' --presets '" + kConfig + "presets.yaml'";
  FILE* pipe = ::popen(command.c_str(), "r");
  CliReport r;
  if (!pipe) return r;
  std::string out;
  char buffer[65536];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  const int status = ::pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.report = nlohmann::json::parse(out, nullptr, /*allow_exceptions=*/false);
  return r;
}

// Every place where `a` and `b` differ, as "path: a vs b", the timing fields left out. Numbers agree within a
// part in 10^9 (one program: the same arithmetic gives the same bits, the margin only allows for a different
// order of a parallel sum).
void differences(const nlohmann::json& a, const nlohmann::json& b, const std::string& path,
                 std::vector<std::string>& out) {
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    if (!(std::abs(x - y) <= 1e-9 * std::max({1.0, std::abs(x), std::abs(y)})))
      out.push_back(path + ": " + a.dump() + " vs " + b.dump());
    return;
  }
  if (a.type() != b.type()) {
    out.push_back(path + ": " + a.dump() + " vs " + b.dump());
    return;
  }
  if (a.is_object()) {
    for (const auto& [key, value] : a.items()) {
      if (kTimings.count(key)) continue;
      if (!b.contains(key)) out.push_back(path + "." + key + ": only in the first");
      else differences(value, b[key], path + "." + key, out);
    }
    for (const auto& [key, value] : b.items())
      if (!kTimings.count(key) && !a.contains(key)) out.push_back(path + "." + key + ": only in the second");
    return;
  }
  if (a.is_array()) {
    if (a.size() != b.size()) {
      out.push_back(path + ": " + std::to_string(a.size()) + " vs " + std::to_string(b.size()) + " entries");
      return;
    }
    for (size_t k = 0; k < a.size(); ++k) differences(a[k], b[k], path + "[" + std::to_string(k) + "]", out);
    return;
  }
  if (a != b) out.push_back(path + ": " + a.dump() + " vs " + b.dump());
}

std::vector<std::string> differences(const nlohmann::json& a, const nlohmann::json& b) {
  std::vector<std::string> out;
  differences(a, b, "report", out);
  return out;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& l : lines) text += l + "\n";
  return text;
}

// The comparison itself finds what it should: the timings alone may differ, anything else is named with its path.
TEST(JobBothWays, ComparisonNamesEveryDifferenceButTheTimings) {
  const nlohmann::json a = nlohmann::json::parse(
      R"({"time_s": 10, "operations": [{"plan_seconds": 1.5, "moves": 7, "engagement": {"seconds": 2}}]})");
  nlohmann::json b = a;
  b["operations"][0]["plan_seconds"] = 9.0;
  b["operations"][0]["engagement"]["seconds"] = 0.1;
  EXPECT_TRUE(differences(a, b).empty()) << joined(differences(a, b));
  b["time_s"] = 10.5;
  b["operations"][0]["moves"] = 8;
  b["operations"][0]["extra"] = true;
  // In the order of the keys (nlohmann::json keeps an object's keys sorted).
  EXPECT_EQ(differences(a, b), (std::vector<std::string>{"report.operations[0].moves: 7 vs 8",
                                                         "report.operations[0].extra: only in the second",
                                                         "report.time_s: 10 vs 10.5"}));
}

// The same job, the same machine, tools and presets: the action's report is the CLI's, field for field.
TEST(JobBothWays, ActionReportIsTheCliReport) {
  const std::string machine = rosmill::rostest::param("machine");
  const CliReport cli = cli_report(kJob, machine);
  ASSERT_EQ(cli.status, 0) << "rosmill job failed";
  ASSERT_TRUE(cli.report.is_object()) << "rosmill job --json printed no JSON object";

  Client client("plan_job", true);
  ASSERT_TRUE(client.waitForServer(ros::Duration(20.0)));
  rosmill::PlanJobGoal goal;
  goal.job_file = kJob;
  client.sendGoal(goal);
  ASSERT_TRUE(client.waitForResult(ros::Duration(150.0)));
  const auto result = client.getResult();
  ASSERT_TRUE(result->success) << result->message;
  const nlohmann::json action = nlohmann::json::parse(result->report_json);

  ASSERT_EQ(action["operations"].size(), 3u);  // rough, finish, walls: a report with something in it
  EXPECT_GT(cli.report["removed_mm3"].get<double>(), 0.0);
  const std::vector<std::string> differ = differences(cli.report, action);
  EXPECT_TRUE(differ.empty()) << "the CLI's report vs the action's:\n" << joined(differ);

  // The machine's clearance reaches the report: on the same machine with links 2 mm over the stock (as a job keeps
  // without a machine) the job's report differs, so the comparison above catches a front end that loses it.
  const std::string two_mm = std::string(::testing::TempDir()) + "machine_clearance_2.yaml";
  {
    std::ifstream in(machine);
    std::stringstream text;
    text << in.rdbuf();
    std::string yaml = text.str();
    const size_t at = yaml.find("clearance_over_stock: 5");
    ASSERT_NE(at, std::string::npos);
    yaml.replace(at, std::string("clearance_over_stock: 5").size(), "clearance_over_stock: 2");
    std::ofstream(two_mm) << yaml;
  }
  const CliReport two = cli_report(kJob, two_mm);
  ASSERT_EQ(two.status, 0);
  const std::vector<std::string> by_clearance = differences(two.report, cli.report);
  EXPECT_FALSE(by_clearance.empty());
  std::printf("links at 2 mm instead of 5 change:\n%s", joined(by_clearance).c_str());
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_job_both_ways");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
