// Helpers of the rostest nodes: waiting for a latched message and a gtest main inside a ROS node.
#pragma once
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <boost/function.hpp>
#include <mutex>

namespace rosmill::rostest {

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
};

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
