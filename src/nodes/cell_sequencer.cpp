// cell_sequencer: the steps a cell's operator (or its cell controller) takes from scans to a machined part, run
// one after the other on the pipeline's own nodes, so that a recording replays as the cell ran
// (launch/replay.launch). It takes no decision of its own: it waits for the scans on `scan_views` (the
// scan_registrar, with ~every_cloud_a_view, takes each as a view), asks the registrar to fuse them (~finish) and
// to find the design in the fused scan (~register), runs the job on the planner's `plan_job` action, and gives
// each program to the bridge's `run_program` action. What happened at each step, figures and reasons, is latched
// on `cell_run` (rosmill/CellRun), where cell_checker and people read it.
//
// Parameters: ~views (0: every scan until ~quiet s pass without one), ~quiet, ~first_view_timeout, ~job (the job
// file; empty: the sequence ends with the registration), ~part_source ("mesh": the part stl_loader published, the design; "": the part the job names),
// ~output_dir, ~accept_ambiguous, ~run (give the programs to the bridge), ~job_timeout,
// ~program_timeout (s), ~player (a rosbag play started with --pause: the sequencer lets it play once the
// registrar and the sequencer hear its scans, so that no scan goes by unseen). Every wait is in wall time: a
// replay's clock (use_sim_time) stops when its bag ends.
#include <actionlib/client/simple_action_client.h>
#include <ros/ros.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <topic_tools/shape_shifter.h>

#include <algorithm>
#include <atomic>
#include <string>
#include <thread>

#include "rosmill/CellRun.h"
#include "rosmill/PlanJobAction.h"
#include "rosmill/RegisterScan.h"
#include "rosmill/RunProgramAction.h"
#include "rosmill/error.hpp"
#include "rosmill/ros/node_main.hpp"
#include "rosmill/ros/params.hpp"

namespace rosmill::edge {
namespace {

struct Settings {
  int views = 0;
  double quiet = 5, first_view_timeout = 120, job_timeout = 1800, program_timeout = 3600;
  std::string job, part_source, output_dir, player;
  bool accept_ambiguous = false, run = true;
};

Settings read_settings(const ::ros::NodeHandle& pnh) {
  Settings s;
  s.views = int_param(pnh, "views", 0, 0, 10000);
  s.quiet = double_param(pnh, "quiet", s.quiet, 0.1, 3600);
  s.first_view_timeout = double_param(pnh, "first_view_timeout", s.first_view_timeout, 0.1, 86400);
  s.job_timeout = double_param(pnh, "job_timeout", s.job_timeout, 1, 86400);
  s.program_timeout = double_param(pnh, "program_timeout", s.program_timeout, 1, 86400);
  s.job = string_param(pnh, "job", "");  // empty: the sequence ends with the registration
  s.part_source = string_param(pnh, "part_source", "mesh");
  s.output_dir = string_param(pnh, "output_dir", "");
  s.accept_ambiguous = bool_param(pnh, "accept_ambiguous", false);
  s.run = bool_param(pnh, "run", true);
  s.player = string_param(pnh, "player", "");
  return s;
}

double wall_now() { return ::ros::WallTime::now().toSec(); }

// Waits up to `seconds` of wall time for `done`, in short sleeps (callbacks run on the spinner's threads).
template <class Done>
bool wait_wall(double seconds, Done&& done) {
  const double end = wall_now() + seconds;
  while (!done()) {
    if (!::ros::ok() || wall_now() > end) return false;
    ::ros::WallDuration(0.05).sleep();
  }
  return true;
}

class CellSequencer {
 public:
  CellSequencer(::ros::NodeHandle& nh, ::ros::NodeHandle& pnh)
      : settings_(read_settings(pnh)),
        nh_(nh),
        run_pub_(nh.advertise<msg::CellRun>("cell_run", 1, true)),
        // Counted, never read: a scan is not decoded here (a recording's clouds may be large).
        scan_sub_(nh.subscribe<topic_tools::ShapeShifter>("scan_views", 16,
                                                          [this](const topic_tools::ShapeShifter::ConstPtr&) {
                                                            if (scans_++ == 0) first_scan_ = wall_now();
                                                            last_scan_ = wall_now();
                                                          })),
        worker_([this] { sequence(); }) {}
  ~CellSequencer() {
    if (worker_.joinable()) worker_.join();
  }

 private:
  void sequence() {
    try {
      if (!collect_views()) return;
      if (!fuse()) return;
      if (!register_design()) return;
      if (settings_.job.empty()) {
        run_.done = true;
        publish("done", "scans fused and the part registered (no ~job)");
        return;
      }
      if (!run_job()) return;
      if (settings_.run && !run_programs()) return;
      run_.done = true;
      publish("done", "scans fused, the part registered, the job planned" +
                          std::string(settings_.run ? ", every program run" : " (programs not run: ~run is false)"));
    } catch (const std::exception& e) {
      publish(run_.step.empty() ? "views" : run_.step, e.what(), true);
    }
  }

  void publish(const std::string& step, const std::string& message, bool failed = false) {
    run_.step = step;
    run_.message = message;
    run_.failed = failed;
    run_.header.stamp = ::ros::Time::now();
    run_.elapsed = first_scan_ > 0 ? wall_now() - first_scan_ : 0;
    run_pub_.publish(run_);
    if (failed)
      ROS_ERROR("cell_sequencer: %s: %s", step.c_str(), message.c_str());
    else
      ROS_INFO("cell_sequencer: %s: %s", step.c_str(), message.c_str());
  }

  bool fail(const std::string& step, const std::string& why) {
    publish(step, why, true);
    return false;
  }

  // The scans: the first within first_view_timeout, then ~views of them or none for ~quiet s.
  bool collect_views() {
    if (!settings_.player.empty() && !start_player()) return false;
    publish("views", "waiting for scans on " + scan_sub_.getTopic());
    if (!wait_wall(settings_.first_view_timeout, [&] { return scans_ > 0; }))
      return fail("views", "no scan came on " + scan_sub_.getTopic() + " within " +
                               std::to_string(settings_.first_view_timeout) + " s");
    wait_wall(1e9, [&] {
      return (settings_.views > 0 && scans_ >= static_cast<uint64_t>(settings_.views)) ||
             wall_now() - last_scan_ > settings_.quiet;
    });
    if (settings_.views > 0 && scans_ < static_cast<uint64_t>(settings_.views))
      return fail("views", "only " + std::to_string(scans_.load()) + " of the " + std::to_string(settings_.views) +
                               " scans asked for came (none for " + std::to_string(settings_.quiet) + " s)");
    return true;
  }

  // The player waits paused until the scans' subscribers are connected to it.
  bool start_player() {
    const std::string service = settings_.player + "/pause_playback";
    publish("views", "waiting for the player (" + service + ")");
    if (!wait_wall(settings_.first_view_timeout, [&] { return scan_sub_.getNumPublishers() > 0; }))
      return fail("views", "nothing publishes " + scan_sub_.getTopic() + " within " +
                               std::to_string(settings_.first_view_timeout) + " s");
    if (!::ros::service::waitForService("scan_registrar/finish", ::ros::Duration(60)))
      return fail("views", "the scan_registrar is not there");
    ::ros::WallDuration(1.0).sleep();  // the registrar's own link to the player, made at the same time
    std_srvs::SetBool play;
    play.request.data = false;
    if (!call(service, play) || !play.response.success)
      return fail("views", "the player did not start (" + service + "): " + play.response.message);
    return true;
  }

  bool fuse() {
    std_srvs::Trigger t;
    if (!call("scan_registrar/finish", t)) return fail("fusion", "the scan_registrar's finish service is not there");
    run_.fusion = t.response.message;
    if (!t.response.success) return fail("fusion", t.response.message);
    const uint64_t scans = scans_;
    run_.views = static_cast<uint32_t>(settings_.views > 0 ? std::min<uint64_t>(scans, settings_.views) : scans);
    publish("fusion", t.response.message);
    return true;
  }

  bool register_design() {
    RegisterScan r;
    r.request.scan = "fused";
    r.request.accept_ambiguous = settings_.accept_ambiguous;
    if (!call("scan_registrar/register", r))
      return fail("registration", "the scan_registrar's register service is not there");
    const auto& a = r.response;
    run_.registered = a.success;
    run_.ambiguous = a.ambiguous;
    run_.ambiguity = a.ambiguity;
    run_.rms = a.rms;
    run_.inlier_share = a.inlier_share;
    run_.overlap = a.overlap;
    run_.translation_sigma = a.translation_sigma;
    run_.rotation_sigma = a.rotation_sigma;
    run_.pose = a.transform;
    run_.registration_json = a.report_json;
    if (!a.success) return fail("registration", a.message);
    publish("registration", a.message);
    return true;
  }

  bool run_job() {
    actionlib::SimpleActionClient<PlanJobAction> client(nh_, "plan_job", true);
    if (!wait_wall(60, [&] { return client.isServerConnected(); }))
      return fail("job", "the planner's plan_job action is not there");
    PlanJobGoal goal;
    goal.job_file = settings_.job;
    goal.part_source = settings_.part_source;
    goal.output_dir = settings_.output_dir;
    publish("job", "running " + settings_.job);
    client.sendGoal(goal);
    if (!wait_wall(settings_.job_timeout, [&] { return client.getState().isDone(); })) {
      client.cancelGoal();
      return fail("job", "the job did not end within " + std::to_string(settings_.job_timeout) + " s");
    }
    run_.job = *client.getResult();
    run_.job_done = true;
    if (!run_.job.success) return fail("job", run_.job.message);
    publish("job", run_.job.message);
    return true;
  }

  bool run_programs() {
    actionlib::SimpleActionClient<RunProgramAction> client(nh_, "run_program", true);
    if (!wait_wall(60, [&] { return client.isServerConnected(); }))
      return fail("programs", "the bridge's run_program action is not there");
    for (size_t k = 0; k < run_.job.programs.size(); ++k) {
      const std::string which = "program " + std::to_string(k + 1) + " of " + std::to_string(run_.job.programs.size());
      RunProgramGoal goal;
      goal.job = run_.job.programs[k];
      publish("programs", "running " + which);
      client.sendGoal(goal);
      if (!wait_wall(settings_.program_timeout, [&] { return client.getState().isDone(); })) {
        client.cancelGoal();
        return fail("programs", which + " did not end within " + std::to_string(settings_.program_timeout) + " s");
      }
      run_.runs.push_back(*client.getResult());
      if (!run_.runs.back().success) return fail("programs", which + ": " + run_.runs.back().message);
    }
    if (run_.job.programs.empty()) return fail("programs", "the job wrote no program");
    return true;
  }

  // Over a persistent link: a one-shot call can see the server hang up before it reads the answer
  // (ros/ros_comm issue 1976), and a fusion or a registration is not to be asked twice.
  template <class Service>
  bool call(const std::string& name, Service& srv) {
    if (!::ros::service::waitForService(name, ::ros::Duration(60))) return false;
    ::ros::ServiceClient client = nh_.serviceClient<Service>(name, /*persistent=*/true);
    return client.call(srv);
  }

  const Settings settings_;
  ::ros::NodeHandle nh_;
  ::ros::Publisher run_pub_;
  std::atomic<uint64_t> scans_{0};
  std::atomic<double> first_scan_{0}, last_scan_{0};
  ::ros::Subscriber scan_sub_;
  msg::CellRun run_;
  std::thread worker_;
};

}  // namespace
}  // namespace rosmill::edge

int main(int argc, char** argv) {
  // Two threads: the scans are counted and the action clients hear their results while the sequence waits.
  return rosmill::edge::run_node<rosmill::edge::CellSequencer>(argc, argv, "cell_sequencer", 2);
}
