// The toolpath: what every planning strategy produces and what the post-processor, the verifier and the ROS layer
// consume. Positions are cutter locations (the tool tip) in millimetres in the workpiece frame (G54).
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

enum class MoveType : uint8_t {
  Rapid,   // G0, no cutting, only above the clearance height or along a known-free retract
  Feed,    // G1 at the pass's cutting feed
  Plunge,  // G1 downwards (or ramping) into material at the plunge feed
};

struct Move {
  Vec3 to;
  MoveType type = MoveType::Feed;
  double feed = 0.0;  // mm/min; 0 for rapids
};

// One pass of a strategy (a layer, a raster line set, a contour set): named so that a viewer can show each alone.
struct ToolpathPass {
  std::string name;
  std::vector<Move> moves;
  // The tool axis at the end of each move (unit, workpiece frame, from the tip towards the spindle), one per move,
  // for a multi-axis pass; empty when the axis is the frame's +Z throughout (3-axis, and 3+2 once indexed).
  std::vector<Vec3> axes = {};
};

struct Toolpath {
  std::string strategy;  // "raster", "waterline", "rough", "contour", "cloud-rough", ...
  Tool tool;
  double safe_z = 0.0;       // retract height between cuts (mm)
  double clearance_z = 0.0;  // height above which rapids are free everywhere (mm)
  Vec3 start = Vec3::Zero(); // where the tool is before the first move (above the part at clearance_z)
  std::vector<ToolpathPass> passes;
  // On a trunnion table (3+2 machining): the rotary axes A and C (degrees) the part is turned to for this toolpath,
  // whose positions are then machine coordinates at that turn; the post indexes the part (a retract in machine
  // coordinates, then G0 A C) where they change.
  bool indexed = false;
  double a = 0, c = 0;
  // The plan's tolerance (mm): how far its chords may stray from the surface. NaN when unknown. The post writes
  // enough decimals that rounding stays within a tenth of it.
  double tolerance = NAN;

  size_t move_count() const;
  // True when a pass carries a tool axis per move (simultaneous four- or five-axis machining).
  bool multi_axis() const;
  Box3 bounds() const;
};

}  // namespace rosmill::core
