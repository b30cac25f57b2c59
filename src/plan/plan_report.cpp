#include "rosmill/plan/plan_report.hpp"

#include <cstdio>

namespace rosmill::core {

std::string slot_text(const PlanReport& r) {
  if (!(r.slot_length_mm > 0)) return {};
  char text[200];
  std::snprintf(text, sizeof text,
                "slotted %.1f mm where no pass fitted at the %.0f-degree limit: up to %.0f degrees, at %.0f mm/min and up",
                r.slot_length_mm, r.engagement_limit_deg, r.slot_max_engagement_deg, r.slot_feed);
  return text;
}

std::string uncleared_text(const UnclearedPatch& l) {
  char text[200];
  std::snprintf(text, sizeof text, "left at z %.3f: %.2f mm2 near x %.2f y %.2f, %s", l.z, l.area_mm2, l.x, l.y,
                uncleared_reason_text(l.reason));
  return text;
}

}  // namespace rosmill::core
