// rostest node for test/ros/bridge.test: the G-code bridge refuses bad requests with their reason, runs a job into
// a folder, and streams a job to LinuxCNC's simulator with the status at >= 5 Hz, pause, resume, abort and cancel.
#include <actionlib/client/simple_action_client.h>
#include <std_srvs/Trigger.h>

#include <atomic>
#include <memory>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "rosmill/ProgramStatus.h"
#include "rosmill/RunProgramAction.h"
#include "rosmill/ToolpathJob.h"
#include "rosmill/gcode/post.hpp"
#include "rosmill/ros/convert.hpp"
#include "rostest_support.hpp"
#include "square_job.hpp"

using namespace rosmill;
using namespace rosmill::edge;
using rosmill::rostest::Latest;
using rosmill::rostest::call_service;
using rosmill::rostest::node_answers;
using rosmill::rostest::square_job;
using Client = actionlib::SimpleActionClient<RunProgramAction>;
using State = actionlib::SimpleClientGoalState;

namespace {

std_srvs::Trigger trigger(const std::string& name) {
  std_srvs::Trigger srv;
  EXPECT_TRUE(call_service("/gcode_bridge/" + name, srv)) << name << ": the bridge is gone";
  return srv;
}

// Runs a goal to its end; returns the final state.
State run(Client& client, const RunProgramGoal& goal, double timeout_s = 60.0) {
  client.sendGoal(goal);
  EXPECT_TRUE(client.waitForResult(ros::Duration(timeout_s))) << "no result within " << timeout_s << " s";
  return client.getState();
}

// The simulator's URI once linuxcnc_sim_node has it (LinuxCNC starts in ~10 s, longer when another one runs).
std::string simulator_uri(double timeout_s) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  std::string uri;
  while (ros::WallTime::now() < end) {
    if (ros::param::get("/linuxcnc_sim/uri", uri)) return uri;
    ros::WallDuration(0.2).sleep();
  }
  return "failed: no simulator URI within " + std::to_string(timeout_s) + " s";
}

// Waits until the latest status has `state`.
bool wait_state(Latest<msg::ProgramStatus>& status, uint8_t state, double timeout_s) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::WallTime::now() < end) {
    auto s = status.wait(0.1);
    if (s && s->state == state) return true;
    ros::WallDuration(0.02).sleep();
  }
  return false;
}

class Bridge : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(ros::service::waitForService("/gcode_bridge/start", ros::Duration(20.0)));
  }
  void SetUp() override { ASSERT_TRUE(client.waitForServer(ros::Duration(10.0))); }
  ros::NodeHandle nh;
  Client client{"run_program", true};
};

TEST_F(Bridge, NothingToRunYet) {
  std_srvs::Trigger start = trigger("start");
  EXPECT_FALSE(start.response.success);
  EXPECT_NE(start.response.message.find("no job received"), std::string::npos) << start.response.message;
  for (const char* command : {"pause", "resume", "abort"}) {
    std_srvs::Trigger t = trigger(command);
    EXPECT_FALSE(t.response.success) << command;
    EXPECT_NE(t.response.message.find("no program is running"), std::string::npos) << t.response.message;
  }
  EXPECT_EQ(run(client, RunProgramGoal()), State::ABORTED);
  EXPECT_NE(client.getResult()->message.find("has no toolpath"), std::string::npos) << client.getResult()->message;
}

TEST_F(Bridge, BadGoalsAreRefusedWithTheirReason) {
  RunProgramGoal goal;
  goal.job = square_job();
  goal.controller = "telnet://mill:23";
  EXPECT_EQ(run(client, goal), State::ABORTED);
  EXPECT_NE(client.getResult()->message.find("unknown controller kind 'telnet'"), std::string::npos)
      << client.getResult()->message;

  goal.controller = "";
  goal.job = square_job(-80.0);  // below the sim's table (z -50) and its envelope (z >= -50.8)
  EXPECT_EQ(run(client, goal), State::ABORTED);
  EXPECT_NE(client.getResult()->message.find("line"), std::string::npos) << client.getResult()->message;
  EXPECT_NE(client.getResult()->message.find("-80"), std::string::npos) << client.getResult()->message;

  goal.job = square_job();
  goal.job.toolpaths[0].passes[0].moves[2].position.x = std::nan("");
  EXPECT_EQ(run(client, goal), State::ABORTED);
  EXPECT_NE(client.getResult()->message.find("pass 0 move 2"), std::string::npos) << client.getResult()->message;

  goal.job = square_job();
  goal.job.toolpaths[0].passes[0].moves[2].feed_rate = 0;
  EXPECT_EQ(run(client, goal), State::ABORTED);
  EXPECT_NE(client.getResult()->message.find("feed_rate"), std::string::npos) << client.getResult()->message;

  goal.job = square_job();
  goal.job.toolpaths[0].setup_rotation.w = std::nan("");  // a job whose setup is no rotation at all
  EXPECT_EQ(run(client, goal), State::ABORTED);
  EXPECT_NE(client.getResult()->message.find("setup_rotation"), std::string::npos) << client.getResult()->message;

  // A tool axis at every move (five-axis) on this 3-axis machine: refused, naming what it would take.
  goal.job = square_job();
  goal.job.toolpaths[0].passes[0].axes.assign(goal.job.toolpaths[0].passes[0].moves.size(), geometry_msgs::Vector3());
  for (auto& axis : goal.job.toolpaths[0].passes[0].axes) axis.z = 1;
  EXPECT_EQ(run(client, goal), State::ABORTED);
  EXPECT_NE(client.getResult()->message.find("tool-centre-point control"), std::string::npos)
      << client.getResult()->message;

  goal.job = square_job();
  goal.from_line = 10000;
  EXPECT_EQ(run(client, goal), State::ABORTED);
  EXPECT_NE(client.getResult()->message.find("from_line"), std::string::npos) << client.getResult()->message;
  EXPECT_TRUE(node_answers("/gcode_bridge"));
}

// A folder controller: the program is written there whole, the run is done at once.
TEST_F(Bridge, RunIntoAFolder) {
  std::string folder;
  ASSERT_TRUE(ros::param::get("~folder", folder));
  std::filesystem::create_directories(folder);
  std::filesystem::remove(folder + "/rosmill.ngc");
  RunProgramGoal goal;
  goal.job = square_job();
  goal.controller = "file://" + folder;
  ASSERT_EQ(run(client, goal), State::SUCCEEDED) << client.getResult()->message;
  auto result = client.getResult();
  EXPECT_TRUE(result->success);
  EXPECT_EQ(result->status.state, msg::ProgramStatus::DONE);
  EXPECT_EQ(result->acknowledged_line, result->lines);
  const std::vector<std::string> written = gcode::read_program_lines(folder + "/rosmill.ngc");
  const std::vector<std::string> posted = gcode::read_program_lines(result->program);
  EXPECT_EQ(written, posted);
  EXPECT_EQ(posted.size(), result->lines);
  size_t feeds = 0;
  for (const std::string& line : posted) feeds += line.rfind("G1", 0) == 0 || line.find(" G1 ") != std::string::npos;
  EXPECT_GE(feeds, 1u);

  // A goal refused after that run reports its own refusal, not the finished run's state and progress.
  goal.controller = "nonsense://x";
  ASSERT_EQ(run(client, goal), State::ABORTED);
  result = client.getResult();
  EXPECT_FALSE(result->success);
  EXPECT_EQ(result->status.state, msg::ProgramStatus::ERROR);
  EXPECT_EQ(result->status.progress, 0.0f);
  EXPECT_EQ(result->status.acknowledged_line, 0u);
  EXPECT_EQ(result->status.last_error, result->message);
  EXPECT_NE(result->message.find("nonsense"), std::string::npos) << result->message;
}

// Text from a message never becomes a block: a tool name and a strategy and pass name with newlines and G-code in
// them (a G0 into the table) are written as inert comment text (rosmill post's sanitiser for the dialect).
TEST_F(Bridge, NamesCannotInjectBlocks) {
  std::string folder;
  ASSERT_TRUE(ros::param::get("~folder", folder));
  std::filesystem::create_directories(folder);
  RunProgramGoal goal;
  goal.job = square_job();
  goal.job.toolpaths[0].tool.name = "flat\nG0 Z-40\n(";
  goal.job.toolpaths[0].strategy = "raster)\rG0 Z-41\n";
  goal.job.toolpaths[0].passes[0].name = "p\nG0 Z-42;x";
  goal.controller = "file://" + folder;
  ASSERT_EQ(run(client, goal), State::SUCCEEDED) << client.getResult()->message;
  const std::vector<std::string> posted = gcode::read_program_lines(client.getResult()->program);
  ASSERT_FALSE(posted.empty());
  for (const std::string& line : posted) {
    for (const char* injected : {"Z-40", "Z-41", "Z-42"}) {
      const size_t at = line.find(injected);
      if (at == std::string::npos) continue;
      const size_t open = line.rfind('(', at);
      EXPECT_TRUE(open != std::string::npos && line.find(')', open) > at) << "injected text outside a comment: " << line;
    }
    EXPECT_EQ(std::count(line.begin(), line.end(), '('), std::count(line.begin(), line.end(), ')')) << line;
    EXPECT_EQ(line.find_first_of("\r\n;"), std::string::npos) << line;
  }
}

// Status messages of one run, with their arrival times.
struct StatusLog {
  std::mutex mutex;
  std::vector<std::pair<double, msg::ProgramStatus>> entries;
  void add(const msg::ProgramStatus& m) {
    std::lock_guard<std::mutex> lock(mutex);
    entries.emplace_back(ros::WallTime::now().toSec(), m);
  }
};

// The square streamed to LinuxCNC's simulator: DONE with every line acknowledged, the status at >= 5 Hz while it
// runs with the line advancing, and the tool back at the end point.
TEST_F(Bridge, StreamsToTheLinuxcncSimulator) {
  const std::string uri = simulator_uri(150.0);
  ASSERT_EQ(uri.rfind("linuxcnc://", 0), 0u) << uri;
  StatusLog log;
  ros::Subscriber sub = nh.subscribe<msg::ProgramStatus>(
      "/program_status", 50, boost::function<void(const msg::ProgramStatus::ConstPtr&)>(
                                 [&log](const msg::ProgramStatus::ConstPtr& m) { log.add(*m); }));
  RunProgramGoal goal;
  goal.job = square_job();
  goal.controller = uri;
  // Held by the callback itself: the fixture's client may call it back after this test has returned.
  const auto feedback = std::make_shared<std::atomic<size_t>>(0);
  client.sendGoal(goal, {}, {}, [feedback](const RunProgramFeedbackConstPtr&) { ++*feedback; });
  ASSERT_TRUE(client.waitForResult(ros::Duration(90.0)));
  ASSERT_EQ(client.getState(), State::SUCCEEDED) << client.getResult()->message;
  auto result = client.getResult();
  EXPECT_EQ(result->status.state, msg::ProgramStatus::DONE);
  EXPECT_EQ(result->acknowledged_line, result->lines);
  EXPECT_GT(result->duration, 4.0);  // 80 mm at 1200 mm/min and a 6 mm plunge at 300 take 5.2 s
  EXPECT_TRUE(result->status.position_known);
  // Back up at the last point. LinuxCNC reports the controlled point, which includes the tool length offset of
  // its own tool table (the stock sim's T1: 0.511 mm).
  EXPECT_NEAR(result->status.position.z, 0.020, 0.001);
  EXPECT_NEAR(result->status.position.x, 0.0, 1e-4);
  EXPECT_NEAR(result->status.position.y, 0.0, 1e-4);
  ros::WallDuration(0.3).sleep();

  std::lock_guard<std::mutex> lock(log.mutex);
  std::vector<double> running;
  uint32_t last_line = 0, lines_seen = 0;
  for (const auto& [t, m] : log.entries) {
    if (m.state != msg::ProgramStatus::RUNNING) continue;
    running.push_back(t);
    EXPECT_GE(m.current_line, last_line) << "the line went back";
    if (m.current_line != last_line) ++lines_seen;
    last_line = m.current_line;
    EXPECT_EQ(m.controller, uri);
  }
  ASSERT_GE(running.size(), 2u);
  const double span = running.back() - running.front();
  EXPECT_GE((running.size() - 1) / span, 5.0) << running.size() << " statuses in " << span << " s";
  double gap = 0;
  for (size_t i = 1; i < running.size(); ++i) gap = std::max(gap, running[i] - running[i - 1]);
  EXPECT_LE(gap, 0.4) << "a status gap of " << gap << " s";
  EXPECT_GE(lines_seen, 3u) << "the current line hardly moved";
  EXPECT_GE(feedback->load(), size_t(5 * 4));
}

// On the simulator: pause holds the tool still, resume goes on, abort stops the program; a cancelled goal aborts it.
TEST_F(Bridge, PauseResumeAbortAndCancelOnTheSimulator) {
  const std::string uri = simulator_uri(150.0);
  ASSERT_EQ(uri.rfind("linuxcnc://", 0), 0u) << uri;
  Latest<msg::ProgramStatus> status(nh, "/program_status");
  RunProgramGoal goal;
  goal.job = square_job();
  goal.controller = uri;
  client.sendGoal(goal);
  ASSERT_TRUE(wait_state(status, msg::ProgramStatus::RUNNING, 30.0))
      << (client.waitForResult(ros::Duration(5.0)) ? client.getResult()->message : "no result");
  ros::WallDuration(1.5).sleep();  // into the square
  std_srvs::Trigger pause = trigger("pause");
  ASSERT_TRUE(pause.response.success) << pause.response.message;
  ASSERT_TRUE(wait_state(status, msg::ProgramStatus::PAUSED, 3.0));
  ros::WallDuration(0.5).sleep();
  auto held = status.wait(1.0);
  ros::WallDuration(1.0).sleep();
  auto still = status.wait(1.0);
  ASSERT_TRUE(held && still && held->position_known);
  EXPECT_NEAR(held->position.x, still->position.x, 1e-6);
  EXPECT_NEAR(held->position.y, still->position.y, 1e-6);
  EXPECT_EQ(still->state, msg::ProgramStatus::PAUSED);

  std_srvs::Trigger resume = trigger("resume");
  ASSERT_TRUE(resume.response.success) << resume.response.message;
  ASSERT_TRUE(wait_state(status, msg::ProgramStatus::RUNNING, 3.0));
  std_srvs::Trigger again = trigger("start");  // one program at a time
  EXPECT_FALSE(again.response.success);
  std_srvs::Trigger abort = trigger("abort");
  ASSERT_TRUE(abort.response.success) << abort.response.message;
  ASSERT_TRUE(client.waitForResult(ros::Duration(10.0)));
  EXPECT_EQ(client.getState(), State::ABORTED);
  auto result = client.getResult();
  EXPECT_EQ(result->status.state, msg::ProgramStatus::ABORTED);
  EXPECT_LT(result->acknowledged_line, result->lines);

  // A cancelled goal aborts the program on the controller.
  client.sendGoal(goal);
  ASSERT_TRUE(wait_state(status, msg::ProgramStatus::RUNNING, 30.0));
  ros::WallDuration(1.0).sleep();
  client.cancelGoal();
  ASSERT_TRUE(client.waitForResult(ros::Duration(10.0)));
  EXPECT_EQ(client.getState(), State::PREEMPTED);
  EXPECT_EQ(client.getResult()->status.state, msg::ProgramStatus::ABORTED);
  EXPECT_TRUE(node_answers("/gcode_bridge"));
}

// The start service runs the last job received on the toolpath topic.
TEST_F(Bridge, StartRunsTheLastPublishedJob) {
  std::string folder;
  ASSERT_TRUE(ros::param::get("~folder", folder));
  ros::Publisher pub = nh.advertise<msg::ToolpathJob>("/toolpath", 1, true);
  // The node's controller parameter is the folder: the program lands there.
  std::filesystem::create_directories(folder);
  pub.publish(square_job(-2.0));
  // Until the bridge has the job, start answers that none came yet: ask again (a condition, not a sleep).
  std_srvs::Trigger start = trigger("start");
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  while (!start.response.success && start.response.message.find("no job received") != std::string::npos &&
         ros::WallTime::now() < end) {
    ros::WallDuration(0.05).sleep();
    start = trigger("start");
  }
  ASSERT_TRUE(start.response.success) << start.response.message;
  Latest<msg::ProgramStatus> status(nh, "/program_status");
  ASSERT_TRUE(wait_state(status, msg::ProgramStatus::DONE, 10.0));
  const std::vector<std::string> lines = gcode::read_program_lines(status.wait(1.0)->program);
  bool deeper = false;
  for (const std::string& l : lines) deeper = deeper || l.find("Z-2") != std::string::npos;
  EXPECT_TRUE(deeper) << "the program is not the published job";
}

}  // namespace

int main(int argc, char** argv) { return rosmill::rostest::run_all(argc, argv, "test_bridge"); }
