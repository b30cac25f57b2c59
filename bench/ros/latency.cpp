// End-to-end latency through the running nodes (issue 8, point 6; target <= 1 s each on this machine kind):
//   cloud: a 300,304-point PointCloud2 (the seed dome on its table, sampled on a 548 x 548 grid) published ->
//          the msg::ToolpathJob that toolpath_planner publishes for it (cloud-rough, 10 mm flat end mill);
//   stl:   a 100,334-triangle binary STL (the wavy solid, n = 221) asked of stl_loader's load_mesh service ->
//          its mesh marker received, and the segmenter's patch markers received.
// The bench starts its own ROS master (rosmaster on a free port) and the node executables, and stops each by its
// PID. Times are wall clock from the publish / the call to the message's arrival here, including transport and
// (de)serialisation. Median of 5 runs, min and max beside it. Usage: bench_ros_latency [runs]
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "rosmill/LoadMesh.h"
#include "rosmill/ToolpathJob.h"
#include "rosmill/testing/wavy_solid.hpp"

extern char** environ;

namespace msg = ::rosmill;

namespace {

// A child process started here and stopped (SIGINT, then SIGKILL) by its PID when this goes away.
class Child {
 public:
  // Its output goes to `log` (the figures stay readable).
  Child(std::vector<std::string> argv, const std::string& log) {
    std::vector<char*> args;
    for (std::string& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&files, 1, 2);
    if (posix_spawn(&pid_, args[0], &files, nullptr, args.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&files);
    if (pid_ < 0) std::fprintf(stderr, "bench: cannot start %s\n", argv[0].c_str());
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() { stop(); }
  bool alive() const { return pid_ > 0 && ::waitpid(pid_, nullptr, WNOHANG) == 0; }
  void stop() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGINT);
    for (int i = 0; i < 100 && ::waitpid(pid_, nullptr, WNOHANG) == 0; ++i) ::usleep(50000);
    if (::waitpid(pid_, nullptr, WNOHANG) == 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    pid_ = -1;
  }

 private:
  pid_t pid_ = -1;
};

bool port_free(int port) {
  const std::string cmd = "(exec 3<>/dev/tcp/127.0.0.1/" + std::to_string(port) + ") 2>/dev/null";
  return std::system(("bash -c '" + cmd + "'").c_str()) != 0;
}

// Counts arrivals of a topic's messages and remembers when the last one came.
template <typename M>
struct Arrivals {
  std::atomic<size_t> count{0};
  std::atomic<double> last{0};
  boost::shared_ptr<const M> message;  // the last one (read after wait_after)
  ros::Subscriber sub;
  Arrivals(ros::NodeHandle& nh, const std::string& topic) {
    sub = nh.subscribe<M>(topic, 1, boost::function<void(const boost::shared_ptr<const M>&)>(
                                        [this](const boost::shared_ptr<const M>& m) {
                                          message = m;
                                          last = ros::WallTime::now().toSec();
                                          ++count;
                                        }));
  }
  // Seconds from `t0` to the arrival after `before` messages; NaN after `timeout_s`.
  double wait_after(size_t before, double t0, double timeout_s) const {
    const double end = ros::WallTime::now().toSec() + timeout_s;
    while (count.load() <= before && ros::WallTime::now().toSec() < end) ros::WallDuration(0.001).sleep();
    return count.load() > before ? last.load() - t0 : NAN;
  }
};

sensor_msgs::PointCloud2 dome_cloud(int n) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header.frame_id = "workpiece";
  sensor_msgs::PointCloud2Modifier mod(cloud);
  mod.setPointCloud2FieldsByString(1, "xyz");
  mod.resize(size_t(n) * n);
  cloud.height = 1;
  cloud.width = n * n;
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
  const double half = 0.06, radius = 0.05;  // m: a 50 mm dome on a 120 mm table square
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j, ++x, ++y, ++z) {
      const double px = -half + 2 * half * i / (n - 1), py = -half + 2 * half * j / (n - 1);
      const double r2 = px * px + py * py;
      *x = float(px);
      *y = float(py);
      *z = float(r2 < radius * radius ? std::sqrt(radius * radius - r2) : 0.0);
    }
  return cloud;
}

void write_binary_stl(const std::string& path, const std::vector<rosmill::core::Vec3>& corners) {
  std::ofstream f(path, std::ios::binary);
  char header[80] = "rosmill bench: wavy solid";
  f.write(header, 80);
  const uint32_t count = uint32_t(corners.size() / 3);
  f.write(reinterpret_cast<const char*>(&count), 4);
  for (size_t t = 0; t < corners.size(); t += 3) {
    const rosmill::core::Vec3 n = (corners[t + 1] - corners[t]).cross(corners[t + 2] - corners[t]).normalized();
    float v[12] = {float(n.x()), float(n.y()), float(n.z())};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) v[3 + 3 * k + c] = float(corners[t + k][c]);
    f.write(reinterpret_cast<const char*>(v), sizeof v);
    const uint16_t attribute = 0;
    f.write(reinterpret_cast<const char*>(&attribute), 2);
  }
}

void report(const char* what, std::vector<double> s) {
  std::sort(s.begin(), s.end());
  const bool ok = !s.empty() && !std::isnan(s.front()) && !std::isnan(s.back());
  if (!ok) {
    std::printf("%-64s FAILED (no message within the timeout)\n", what);
    return;
  }
  std::printf("%-64s median %7.3f s  (min %.3f, max %.3f, %zu runs)  target <= 1 s: %s\n", what, s[s.size() / 2],
              s.front(), s.back(), s.size(), s[s.size() / 2] <= 1.0 ? "met" : "NOT met");
}

std::string node(const char* name) { return std::string(ROSMILL_NODE_DIR) + "/" + name; }

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  int port = 11511;
  while (port < 11700 && !port_free(port)) ++port;
  const std::string home = std::filesystem::temp_directory_path() / ("rosmill_bench_ros." + std::to_string(::getpid()));
  std::filesystem::create_directories(home);
  ::setenv("ROS_MASTER_URI", ("http://localhost:" + std::to_string(port)).c_str(), 1);
  ::setenv("ROS_HOSTNAME", "localhost", 1);
  ::setenv("ROS_HOME", home.c_str(), 1);
  ::setenv("ROS_LOG_DIR", (home + "/log").c_str(), 1);
  const std::string log = home + "/nodes.log";
  Child master({"/usr/bin/rosmaster", "--core", "-p", std::to_string(port)}, log);
  ros::init(argc, argv, "bench_ros_latency", ros::init_options::NoSigintHandler);
  for (int i = 0; i < 100 && !ros::master::check(); ++i) ros::WallDuration(0.1).sleep();
  if (!ros::master::check()) {
    std::fprintf(stderr, "bench: the master did not start on port %d\n", port);
    return 1;
  }
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const std::string quiet = "__log:=" + home + "/log/node.log";
  int failures = 0;

  {  // cloud -> toolpath
    Child planner({node("toolpath_planner"), "__name:=toolpath_planner", quiet,
                   "_tool_table:=" ROSMILL_SOURCE_DIR "/config/tools.yaml", "_cloud_strategy:=cloud-rough",
                   "_tool_id:=1", "_frame_id:=workpiece"},
                  log);
    Arrivals<msg::ToolpathJob> jobs(nh, "toolpath");
    ros::Publisher pub = nh.advertise<sensor_msgs::PointCloud2>("cloud", 1);
    for (int i = 0; i < 200 && pub.getNumSubscribers() == 0; ++i) ros::WallDuration(0.05).sleep();
    sensor_msgs::PointCloud2 cloud = dome_cloud(548);
    std::vector<double> seconds;
    for (int r = 0; r < runs && planner.alive(); ++r) {
      cloud.header.stamp = ros::Time::now();
      const size_t before = jobs.count.load();
      const double t0 = ros::WallTime::now().toSec();
      pub.publish(cloud);
      seconds.push_back(jobs.wait_after(before, t0, 60.0));
    }
    size_t moves = 0;
    if (jobs.message)
      for (const auto& tp : jobs.message->toolpaths)
        for (const auto& pass : tp.passes) moves += pass.moves.size();
    char what[128];
    std::snprintf(what, sizeof what, "cloud %u points -> toolpath (cloud-rough, T1, %zu moves)", cloud.width, moves);
    report(what, seconds);
    failures += seconds.empty() || std::isnan(seconds.back());
  }

  {  // STL -> markers
    const std::string stl = home + "/wavy_100k.stl";
    const std::vector<rosmill::core::Vec3> corners = rosmill::core::wavy_solid_corners(221, 100.0);
    write_binary_stl(stl, corners);
    Child loader({node("stl_loader"), "__name:=stl_loader", quiet}, log);
    Child segmenter({node("segmenter"), "__name:=segmenter", quiet}, log);
    Arrivals<visualization_msgs::Marker> mesh_markers(nh, "mesh_marker");
    Arrivals<visualization_msgs::MarkerArray> patch_markers(nh, "segmentation_markers");
    if (!ros::service::waitForService("load_mesh", ros::Duration(20.0))) {
      std::fprintf(stderr, "bench: stl_loader's load_mesh service did not come\n");
      return 1;
    }
    for (int i = 0; i < 200 && patch_markers.sub.getNumPublishers() == 0; ++i) ros::WallDuration(0.05).sleep();
    std::vector<double> marker_s, patch_s;
    for (int r = 0; r < runs; ++r) {
      rosmill::LoadMesh srv;
      srv.request.path = stl;
      srv.request.units = "mm";
      const size_t before_mesh = mesh_markers.count.load(), before_patch = patch_markers.count.load();
      const double t0 = ros::WallTime::now().toSec();
      if (!ros::service::call("load_mesh", srv) || !srv.response.success) {
        std::fprintf(stderr, "bench: load_mesh failed: %s\n", srv.response.message.c_str());
        return 1;
      }
      marker_s.push_back(mesh_markers.wait_after(before_mesh, t0, 60.0));
      patch_s.push_back(patch_markers.wait_after(before_patch, t0, 60.0));
    }
    char what[128];
    std::snprintf(what, sizeof what, "STL %zu triangles -> mesh marker (stl_loader)", corners.size() / 3);
    report(what, marker_s);
    std::snprintf(what, sizeof what, "STL %zu triangles -> patch markers (+ segmenter)", corners.size() / 3);
    report(what, patch_s);
    failures += marker_s.empty() || std::isnan(marker_s.back()) || std::isnan(patch_s.back());
  }
  spinner.stop();
  ros::shutdown();
  master.stop();
  std::filesystem::remove_all(home);
  return failures == 0 ? 0 : 1;
}
