// The engagement report as `rosmill verify --json` and `rosmill job --json` print it (degrees, mm, mm^3, minutes).
#pragma once
#include "rosmill/verify/engagement.hpp"

namespace rosmill::core::verify {

// Json: nlohmann::json or nlohmann::ordered_json.
template <class Json>
Json engagement_json(const EngagementReport& e) {
  Json j;
  j["max_deg"] = e.max_deg;
  j["p95_deg"] = e.p95_deg;
  j["mrr_mm3_per_min"] = e.mrr_mm3_per_min;
  j["histogram"] = e.histogram_mm;  // radial feed length (mm) per bin of histogram_bin_deg, from 0
  j["histogram_bin_deg"] = kEngagementBinDeg;
  j["radial_mm"] = e.radial_mm;
  j["plunges"] = e.plunges;
  j["plunge_mm"] = e.plunge_mm;
  j["removed_mm3"] = e.removed_mm3;
  j["feed_min"] = e.feed_minutes;
  j["cell_mm"] = e.cell_mm;
  j["tolerance_deg"] = e.tolerance_deg;
  j["seconds"] = e.seconds;
  return j;
}

}  // namespace rosmill::core::verify
