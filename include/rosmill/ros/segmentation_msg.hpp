// A segmentation (core, mm) as a message (m) and as coloured patches in rviz.
#pragma once
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include "rosmill/ros/namespaces.hpp"
#include "rosmill/Segmentation.h"
#include "rosmill/segment/setup_segmentation.hpp"

namespace rosmill::edge {

// `setup_name` is how the setup was asked for ("+Z", "4axis:x", "custom").
msg::Segmentation to_segmentation_msg(const segment::SetupSegmentation& seg, const std::string& setup_name,
                                    const std_msgs::Header& header);

// One TRIANGLE_LIST per patch (id = label): reachable patches in namespace "reachable", each in its own label
// colour; unreachable ones in "unreachable", dark and translucent, so rviz can show either set alone. Starts with
// a DELETEALL so the patches of the previous setup vanish.
visualization_msgs::MarkerArray segmentation_markers(const segment::SetupSegmentation& seg,
                                                     const std_msgs::Header& header);

}  // namespace rosmill::edge
