// Phase 2 of the segmentation (Lefebvre & Lauwers, "STL Model Segmentation for Multi-Axis Machining Operations
// Planning", section 3.3): each surface patch is pruned by a setup filter into the parts the
// setup reaches and the parts it does not, then the recombination step runs again. The EGI decides whole
// patches at once (every occupied bin inside or outside the filter); only patches whose EGI straddles the
// filter's border are tested facet by facet, with the exact normal.
//
// A SetupSegmentation refers to the SurfacePatches (and through it the const mesh) and holds only its own labels,
// so the segmentations of any number of setups exist side by side over one unchanged mesh.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/segment/egi.hpp"
#include "rosmill/segment/setup_filter.hpp"
#include "rosmill/segment/surface_patches.hpp"

namespace rosmill::core::segment {

struct Segment {
  Patch shape;               // facets (into SetupSegmentation::facet_order), area, normal, neighbours, loops
  uint32_t patch = 0;        // the phase 1 patch it was cut from (of its first facet, after recombination)
  bool reachable = false;    // most of its area is reachable
  double reachable_area = 0.0;
};

class SetupSegmentation {
 public:
  const SurfacePatches& patches() const { return *patches_; }
  const SetupFilter& filter() const { return filter_; }
  size_t count() const { return segments_.size(); }
  const std::vector<Segment>& segments() const { return segments_; }
  const std::vector<uint32_t>& labels() const { return labels_; }
  const std::vector<uint32_t>& facet_order() const { return facet_order_; }
  // Per facet: 1 when the setup reaches it (exact test, independent of the recombination).
  const std::vector<uint8_t>& reachable() const { return reachable_; }
  double reachable_area() const { return reachable_area_; }
  double reachable_fraction() const;
  // Patches decided whole by their EGI, and patches that needed the facet-by-facet test.
  size_t patches_decided_by_egi() const { return decided_by_egi_; }

 private:
  friend SetupSegmentation segment_setup(const EgiSet&, const SetupFilter&, const SizeRule*);
  const SurfacePatches* patches_ = nullptr;
  SetupFilter filter_;
  std::vector<Segment> segments_;
  std::vector<uint32_t> labels_;
  std::vector<uint32_t> facet_order_;
  std::vector<uint8_t> reachable_;
  double reachable_area_ = 0.0;
  size_t decided_by_egi_ = 0;
};

// Per facet reachability for a filter (1 reachable), pruning the EGI first. `whole` (optional) counts the
// patches decided by their EGI alone.
std::vector<uint8_t> reachable_facets(const EgiSet& egis, const SetupFilter& filter, size_t* whole = nullptr);

// Phase 2 for one setup. `small` defaults to the phase 1 rule.
SetupSegmentation segment_setup(const EgiSet& egis, const SetupFilter& filter, const SizeRule* small = nullptr);

}  // namespace rosmill::core::segment
