# The ROS layer: one conversion unit (src/ros/) and one executable per node (src/nodes/*.cpp).
