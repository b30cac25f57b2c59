// What a strategy did, for reports and tests: its lines and levels, drop-cutter queries, and the cutter locations
// the sampling policy added (step_error.hpp) or left out (a surface's skipped regions).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace rosmill::core {

// Why a strategy left material standing at a level that is not the part's.
enum class UnclearedReason {
  kNarrowerThanTheTool,  // no centre of the cutter out of the part reaches it: a gap narrower than the tool, an
                         // inner corner tighter than its radius
  kHolder,               // the cutter reaches it only where the shank or the holder would meet material left above
  kEngagement,           // reached, but no pass got to it at the engagement limit and the turn radius
};

inline const char* uncleared_reason_text(UnclearedReason r) {
  switch (r) {
    case UnclearedReason::kNarrowerThanTheTool: return "narrower than the tool";
    case UnclearedReason::kHolder: return "the holder would meet the material above";
    case UnclearedReason::kEngagement: return "no pass reached it within the engagement limit";
  }
  return "";
}

// One connected patch of material a level left: at height z, its area, a place inside or near it (its centroid).
struct UnclearedPatch {
  double z = 0.0;         // mm
  double area_mm2 = 0.0;
  double x = 0.0, y = 0.0;  // mm
  UnclearedReason reason = UnclearedReason::kEngagement;
};

struct PlanReport {
  std::string strategy;
  size_t lines = 0;            // raster lines
  size_t levels = 0;           // z levels (roughing)
  size_t samples = 0;          // drop-cutter queries of the sampling
  size_t cl_points = 0;        // moves written
  size_t buffer_points = 0;    // step-error sampling: locations inserted by the interpolation (error > t/2)
  size_t checked_points = 0;   // step-error sampling: locations inserted by the check of the moves
  size_t skipped_samples = 0;  // positions left out where the surface skips (Surface::skips)
  double sample_step = 0.0;    // mm
  // Adaptive clearing (adaptive.hpp): the radial engagement it keeps to and the largest its own bookkeeping found
  // on a move at a level (entries excluded: a helix or ramp cuts with the whole end), the smallest radius its
  // steered passes and their links turn on (each step turns by at most step / radius), the passes, entries, lifts
  // and links that turn on the spot it made, and the area of material it left at the levels more than two cells
  // off the walls (inner corners tighter than the turn radius, gaps narrower than the tool).
  double engagement_limit_deg = 0.0;
  double max_engagement_deg = 0.0;
  double min_turn_radius = 0.0;  // mm
  size_t passes = 0, helices = 0, ramps = 0, lifts = 0;
  size_t corner_links = 0;  // links at the level that turn on the spot: no curve of the turn radius fitted (each
                            // straight piece of an air link counts as one)
  size_t air_links = 0;     // links at the level round what stands between, through the air cleared, for a lift
  size_t short_passes = 0;  // passes that cut for fewer than 3 steps of R / 10 (made only where no longer one can)
  double left_area_mm2 = 0.0;
  // Where no pass reached the material at the limit, the wall pass cut it as a slot: its length over the limit, the
  // largest engagement there and the lowest feed it ran at (chip thinning keeps the chip load; mm/min).
  double slot_length_mm = 0.0;
  double slot_max_engagement_deg = 0.0;
  double slot_feed = 0.0;
  // What it left, patch by patch (the material the cutter cannot reach too, which left_area_mm2 does not count),
  // and why; patches under R^2 / 20 are not listed (the skin the chords of a curved wall leave).
  std::vector<UnclearedPatch> uncleared;
  // Five-axis finishing (five_axis_finish.hpp): the tool axis's largest angle from +Z and largest change per mm
  // along a pass, the cutter locations whose axis was turned off the lead-and-tilt rule so that tool and holder
  // clear the part, those no axis in the cone reaches (left out: the pass breaks there), and the most material
  // left on the surface at a cutter location kept (a ball pushed back along its axis by what stands beside it).
  double max_tilt_deg = 0.0;
  double max_axis_rate_deg_per_mm = 0.0;
  size_t axes_turned_to_clear = 0;
  size_t unreachable_points = 0;
  double max_left_mm = 0.0;
};

// "slotted 61.7 mm where no pass fitted at the 53-degree limit: up to 136 degrees, at 980 mm/min and up"; empty
// when the strategy cut no slot.
std::string slot_text(const PlanReport& r);
// "left at z -3.000: 6.50 mm2 near x 1.00 y 2.00, narrower than the tool" (the plan's frame).
std::string uncleared_text(const UnclearedPatch& l);

// The patches as a JSON array of {z, area_mm2, x, y, reason} (Json: nlohmann::json, kept out of this header).
template <class Json>
Json uncleared_json(const std::vector<UnclearedPatch>& left) {
  Json out = Json::array();
  for (const UnclearedPatch& l : left)
    out.push_back({{"z", l.z}, {"area_mm2", l.area_mm2}, {"x", l.x}, {"y", l.y}, {"reason", uncleared_reason_text(l.reason)}});
  return out;
}

}  // namespace rosmill::core
