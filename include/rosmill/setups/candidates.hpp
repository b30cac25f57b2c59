// The tool directions setup selection chooses among: the six axis directions a machinist clamps a part in, the
// normals of the part's large flat faces (each exactly: a tilted face machined square on), and the peaks of the
// part's Extended Gaussian Image (Horn 1984; the whole part's, the sum of its patches' EGIs, Lefebvre and Lauwers
// section 3.3), where much area faces one way without being flat. A direction within `min_separation_deg` of one
// already taken adds nothing a setup would not already reach; the extras are the largest first.
#pragma once
#include <string>
#include <vector>

#include "rosmill/geometry/types.hpp"
#include "rosmill/segment/egi.hpp"

namespace rosmill::core::setups {

struct Candidate {
  Vec3 direction;      // unit, the tool axis in the workpiece frame
  std::string name;    // "+Z", ..., or "custom"
  std::string source;  // "axis", "flat face (patch 7, 800 mm^2)", "EGI peak (12% of the area)"
};

struct CandidateOptions {
  double min_share = 0.02;          // a flat face or an EGI bin must hold this share of the part's area
  double flat_tolerance_deg = 0.5;  // every facet of a flat face within this of its normal
  double min_separation_deg = 10;
  size_t max_extra = 8;             // beyond the six axes
};

std::vector<Candidate> candidate_directions(const segment::EgiSet& egis, const CandidateOptions& options = {});

}  // namespace rosmill::core::setups
