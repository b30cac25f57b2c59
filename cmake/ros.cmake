# catkin: the ROS interface of the package (messages, services, actions). The nodes are in ros_targets.cmake,
# after the core library exists.
find_package(catkin REQUIRED COMPONENTS roscpp std_msgs)
catkin_package()
