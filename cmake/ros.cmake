# catkin: the ROS interface of the package (messages, services, actions). The nodes, the conversion library and
# the rostests are in ros_targets.cmake, included after the core library exists.
#
# Only the C++ and Python generators run (ROS_LANG_DISABLE; the only other one installed is Lisp): Lisp would cost build
# time for
# nothing. Python messages are kept for rostest scripts and rosbag tooling written in Python.
# rosbag pulls in pluginlib, which runs ament's templates with the first python3 on PATH (a pyenv one
# without the ROS modules): point it at the system interpreter catkin uses.
if(PYTHON_EXECUTABLE AND NOT Python3_EXECUTABLE)
  set(Python3_EXECUTABLE ${PYTHON_EXECUTABLE} CACHE FILEPATH "python3 with the ROS modules")
endif()
set(ENV{ROS_LANG_DISABLE} "genlisp")
set(ROSMILL_ROS_COMPONENTS
  roscpp std_msgs std_srvs geometry_msgs sensor_msgs shape_msgs visualization_msgs diagnostic_msgs
  actionlib_msgs actionlib tf2 tf2_ros tf2_eigen pcl_conversions diagnostic_updater rosbag topic_tools rostest)
find_package(catkin REQUIRED COMPONENTS message_generation ${ROSMILL_ROS_COMPONENTS})

file(GLOB ROSMILL_MSG_FILES RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/msg CONFIGURE_DEPENDS msg/*.msg)
file(GLOB ROSMILL_SRV_FILES RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/srv CONFIGURE_DEPENDS srv/*.srv)
file(GLOB ROSMILL_ACTION_FILES RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/action CONFIGURE_DEPENDS action/*.action)
add_message_files(DIRECTORY msg FILES ${ROSMILL_MSG_FILES})
add_service_files(DIRECTORY srv FILES ${ROSMILL_SRV_FILES})
add_action_files(DIRECTORY action FILES ${ROSMILL_ACTION_FILES})
generate_messages(DEPENDENCIES std_msgs geometry_msgs actionlib_msgs)

catkin_package(
  INCLUDE_DIRS include
  CATKIN_DEPENDS message_runtime roscpp std_msgs std_srvs geometry_msgs sensor_msgs shape_msgs visualization_msgs
    actionlib_msgs actionlib)
