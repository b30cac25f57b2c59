// The main() of every node: init, build the node from its parameters, spin, and turn a start-up Error (a bad
// parameter, a missing file) into one FATAL line naming it and exit status 1 instead of a crash.
#pragma once
#include <ros/ros.h>

#include <exception>

#include "rosmill/ros/namespaces.hpp"
#include "rosmill/heap_reuse.hpp"

namespace rosmill::edge {

// `threads` 1 runs callbacks one at a time (ros::spin); more lets slow work and services overlap.
template <typename Node>
int run_node(int argc, char** argv, const char* name, int threads = 1) {
  keep_freed_memory();  // a node serves job after job: each reuses the memory the last one freed
  ::ros::init(argc, argv, name);
  ::ros::NodeHandle nh, pnh("~");
  try {
    Node node(nh, pnh);
    if (threads <= 1) {
      ::ros::spin();
    } else {
      ::ros::AsyncSpinner spinner(threads);
      spinner.start();
      ::ros::waitForShutdown();
    }
  } catch (const std::exception& e) {
    ROS_FATAL("%s: %s", name, e.what());
    return 1;
  }
  return 0;
}

}  // namespace rosmill::edge
