// Helpers of the rostest nodes: waiting for a latched message and a gtest main inside a ROS node.
#pragma once
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <ros/network.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <xmlrpcpp/XmlRpcClient.h>
#include <sys/stat.h>

#include "rosmill/ros/namespaces.hpp"

#include <boost/function.hpp>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <string>

namespace rosmill::rostest {
using namespace ::rosmill::core;
namespace msg = ::rosmill;

// A text parameter of the test node (~name); a failure when it is missing.
inline std::string param(const std::string& name) {
  std::string value;
  EXPECT_TRUE(ros::param::get("~" + name, value)) << "no parameter ~" << name;
  return value;
}

// Calls a service over a persistent connection. roscpp's one-shot call (ros::service::call) sometimes reports a
// failure after the server has answered: the server closes the connection as it sends the response, and the client
// can see the hang-up before it reads the answer (ros/ros_comm issue 1976). A persistent link is closed by the client,
// after the answer.
template <typename Service>
bool call_service(const std::string& name, Service& srv) {
  ros::NodeHandle nh;
  ros::ServiceClient client = nh.serviceClient<Service>(name, /*persistent=*/true);
  return client.call(srv);
}

// Keeps the last message of a topic; wait() returns it or nullptr after `timeout` seconds.
template <typename M>
class Latest {
 public:
  Latest(ros::NodeHandle& nh, const std::string& topic) {
    sub_ = nh.subscribe<M>(topic, 1, boost::function<void(const boost::shared_ptr<const M>&)>(
                                         [this](const boost::shared_ptr<const M>& m) {
                                           std::lock_guard<std::mutex> lock(mutex_);
                                           last_ = m;
                                           ++count_;
                                         }));
  }
  // The subscription ends first: roscpp then waits for a callback that is running, which writes the members below
  // (destroyed before sub_ would be, declared after it). Without this a message arriving as a test ends wrote
  // into freed memory ("corrupted double-linked list").
  ~Latest() { sub_.shutdown(); }
  Latest(const Latest&) = delete;
  Latest& operator=(const Latest&) = delete;

  boost::shared_ptr<const M> wait(double timeout, size_t after_count = 0) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < end) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (last_ && count_ > after_count) return last_;
      }
      ros::WallDuration(0.02).sleep();
    }
    return nullptr;
  }
  size_t count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }

 private:
  ros::Subscriber sub_;
  std::mutex mutex_;
  boost::shared_ptr<const M> last_;
  size_t count_ = 0;
  bool seen_ = false;
};

// The process id of a running node from its XML-RPC slave API (getPid, what `rosnode ping` asks), or 0 when it
// does not answer: a crashed node does not, even while the master still lists it. (Not ~get_loggers: on this
// platform a C++ client calling it makes the called node crash in log4cxx when the connection drops.)
inline int node_pid(const std::string& node) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, payload, false)) return 0;
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(std::string(payload), host, port)) return 0;
  XmlRpc::XmlRpcClient client(host.c_str(), int(port), "/");
  XmlRpc::XmlRpcValue ping, reply;
  ping[0] = ros::this_node::getName();
  int pid = 0;
  if (client.execute("getPid", ping, reply) && reply.getType() == XmlRpc::XmlRpcValue::TypeArray &&
      int(reply[0]) == 1)
    pid = int(reply[2]);
  client.close();
  return pid;
}

// True when the node answers (see node_pid).
inline bool node_answers(const std::string& node) { return node_pid(node) > 0; }

// How many inputs a node has taken (accepted or rejected), from its diagnostic on /diagnostics (the
// InputDiagnostics of the node: status "<node>: input" with values "accepted" and "rejected"). A test publishes an
// input and waits for the count to pass what it was before: a condition, not a sleep.
class InputCount {
 public:
  InputCount(ros::NodeHandle& nh, const std::string& status_name) : name_(status_name) {
    sub_ = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
        "/diagnostics", 50,
        boost::function<void(const diagnostic_msgs::DiagnosticArray::ConstPtr&)>(
            [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
              for (const auto& s : m->status) {
                if (s.name != name_) continue;
                size_t n = 0;
                for (const auto& kv : s.values)
                  if (kv.key == "accepted" || kv.key == "rejected") n += std::stoul(kv.value);
                std::lock_guard<std::mutex> lock(mutex_);
                count_ = std::max(count_, n);
                seen_ = true;
              }
            }));
  }
  ~InputCount() { sub_.shutdown(); }  // before the members its callback writes (as Latest)
  InputCount(const InputCount&) = delete;
  InputCount& operator=(const InputCount&) = delete;

  // The count, once the node's diagnostic has been heard (it publishes at least once a second).
  size_t now(double timeout = 10.0) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    for (;;) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (seen_ || !ros::ok() || ros::WallTime::now() > end) return count_;
      }
      ros::WallDuration(0.02).sleep();
    }
  }
  // True once the node has taken more than `before` inputs, within `timeout` seconds.
  bool wait_beyond(size_t before, double timeout = 30.0) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < end) {
      if (now(0.0) > before) return true;
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }

 private:
  std::string name_;
  ros::Subscriber sub_;
  std::mutex mutex_;
  size_t count_ = 0;
  bool seen_ = false;
};


// The peak resident memory of a process in MB (VmHWM of /proc/PID/status), or -1.
inline double peak_rss_mb(int pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return -1.0;
}

// Plays a recorded bag into this test's master once every topic has a subscriber (PLATFORM_NOTES pitfall 5);
// returns rosbag's exit status. A missing file is checked here: rosbag itself exits 0 for it.
inline int play_bag(const std::string& path, double timeout_s = 30.0) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    ADD_FAILURE() << "no bag " << path;
    return -1;
  }
  const std::string cmd = "timeout " + std::to_string(int(timeout_s)) + " rosbag play -q --wait-for-subscribers '" +
                          path + "' >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline int run_all(int argc, char** argv, const char* name) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, name);
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}

}  // namespace rosmill::rostest
