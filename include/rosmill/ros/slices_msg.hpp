// Slices (core, mm) as a message (m) and as contour lines in rviz.
#pragma once
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include "rosmill/ros/namespaces.hpp"
#include "rosmill/Slices.h"
#include "rosmill/slice/slicer.hpp"

namespace rosmill::edge {

// `interval_mm` is the spacing the planes were made with (0 when they were not evenly spaced).
msg::Slices to_slices_msg(const std::vector<core::SliceLayer>& layers, double interval_mm,
                          const std_msgs::Header& header);

// One LINE_LIST per layer (namespace "slices", id = layer index): outer contours blue, holes orange, open chains
// red, so a broken mesh shows where it is open. Starts with a DELETEALL.
visualization_msgs::MarkerArray slice_markers(const std::vector<core::SliceLayer>& layers,
                                              const std_msgs::Header& header);

}  // namespace rosmill::edge
