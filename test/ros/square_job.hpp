// A small job the rostests of the bridge run: a 20 mm square with the 10 mm flat end mill.
#pragma once
#include "rosmill/ToolpathJob.h"
#include "rosmill/ros/convert.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rostest_support.hpp"

namespace rosmill::rostest {

// A 20 mm square cut 1 mm deep with the 10 mm flat end mill, about 7 s on the simulator (mm, mm/min).
inline ::rosmill::ToolpathJob square_job(double depth = -1.0) {
  ::rosmill::core::Toolpath tp;
  tp.strategy = "test-square";
  tp.tool.id = 1;
  tp.tool.name = "10 mm flat end mill";
  tp.tool.cutter = Cutter::flat(10);
  tp.tool.feed = 1200;
  tp.tool.plunge_feed = 300;
  tp.safe_z = 5;
  tp.clearance_z = 20;
  tp.start = Vec3(0, 0, 20);
  ::rosmill::core::ToolpathPass pass;
  pass.name = "square";
  pass.moves = {{Vec3(0, 0, 5), MoveType::Rapid, 0},      {Vec3(0, 0, depth), MoveType::Plunge, 300},
                {Vec3(20, 0, depth), MoveType::Feed, 1200}, {Vec3(20, 20, depth), MoveType::Feed, 1200},
                {Vec3(0, 20, depth), MoveType::Feed, 1200}, {Vec3(0, 0, depth), MoveType::Feed, 1200},
                {Vec3(0, 0, 20), MoveType::Rapid, 0}};
  tp.passes.push_back(pass);
  std_msgs::Header header;
  header.frame_id = "workpiece";
  return edge::to_job_msg({tp}, named_setup("+Z"), header);
}

}  // namespace rosmill::rostest
