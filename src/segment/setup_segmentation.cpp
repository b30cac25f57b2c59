// Phase 2: prune each patch's EGI with the setup filter, split the patches that straddle it into connected
// reachable and unreachable parts, and recombine the small parts (into a part of the same patch first). Whole
// patches keep their phase 1 records; only the split patches are described anew.
#include "rosmill/segment/setup_segmentation.hpp"

#include <algorithm>
#include <cmath>

#include "labelling.hpp"
#include "patch_parts.hpp"
#include "rosmill/parallel.hpp"
#include "setup_steps.hpp"

namespace rosmill::core::segment {
namespace {

using detail::Verdict;

// Whole-patch verdict from the EGI: every occupied bin lies inside (or outside) the filter's reach.
Verdict patch_verdict(const EgiSet& egis, const PatchEgi& egi, const SetupFilter& filter) {
  if (egi.bins.empty()) return Verdict::Reachable;  // only zero-area facets
  const double limit = filter.max_angle_deg * M_PI / 180.0;
  bool all_in = true, all_out = true;
  for (uint32_t b : egi.bins) {
    const double d = filter.angle_to_allowed(egis.bins().centre(b)), r = egis.bins().radius(b);
    all_in = all_in && d + r < limit;
    all_out = all_out && d - r > limit;
    if (!all_in && !all_out) return Verdict::Mixed;
  }
  return all_in ? Verdict::Reachable : Verdict::Unreachable;
}

std::vector<Verdict> patch_verdicts(const EgiSet& egis, const SetupFilter& filter, size_t* whole) {
  const SurfacePatches& patches = egis.patches();
  std::vector<Verdict> verdict(patches.count());
  size_t decided = 0;
  for (size_t p = 0; p < patches.count(); ++p) {
    verdict[p] = patch_verdict(egis, egis.egi(p), filter);
    decided += verdict[p] != Verdict::Mixed;
  }
  if (whole) *whole = decided;
  return verdict;
}

// A zero-area facet takes the reachability of a neighbour in the same patch (it has no normal of its own), so
// it does not cut a segment in two. Only mixed patches can hold facets of both kinds.
void settle_degenerate(const SurfacePatches& patches, const std::vector<Verdict>& verdict,
                       std::vector<uint8_t>& reach) {
  if (patches.notes().degenerate_facets == 0) return;
  const Mesh& mesh = patches.mesh();
  const uint32_t* order = patches.facet_order().data();
  for (const Patch& p : patches.patches()) {
    if (verdict[p.id] != Verdict::Mixed) continue;
    for (uint32_t i = p.first_facet; i < p.first_facet + p.facet_count; ++i) {
      if (detail::has_area(mesh, order[i])) continue;
      for (uint32_t j : patches.inner_neighbours()[i]) {
        if (j != kNone && detail::has_area(mesh, order[j])) {
          reach[order[i]] = reach[order[j]];
          break;
        }
      }
    }
  }
}

// Reachability of facets [first, last). Arrays and test come by value: a byte stored through `reach` could
// otherwise be any of them, and every one would be read again from memory after each facet.
template <typename Test>
void reach_of_facets(size_t first, size_t last, const uint32_t* label, const Verdict* verdict, const Vec3* normal,
                     const Test test, uint8_t* reach) {
  for (size_t f = first; f < last; ++f) {
    const Verdict patch = verdict[label[f]];
    reach[f] = patch == Verdict::Mixed ? uint8_t(test(normal[f])) : uint8_t(patch);
  }
}

// Per facet reachability: the patch's verdict, or the exact test for the facets of mixed patches. Both cores
// from 20,000 facets on (a range no longer than its grain stays on the calling thread), in pieces taken on demand.
template <typename Test>
void fill_reach(const SurfacePatches& patches, const std::vector<Verdict>& verdict, const Test& test,
                std::vector<uint8_t>& reach) {
  const Mesh& mesh = patches.mesh();
  for_each_piece<size_t>(0, mesh.face_count(), 20000, [&](size_t begin, size_t end) {
    reach_of_facets(begin, end, patches.labels().data(), verdict.data(), mesh.normals.data(), test, reach.data());
  });
}

std::vector<uint8_t> facet_reach(const SurfacePatches& patches, const std::vector<Verdict>& verdict,
                                 const SetupFilter& filter) {
  std::vector<uint8_t> reach(patches.mesh().face_count());
  fill_reach(patches, verdict, ReachTest(filter), reach);
  settle_degenerate(patches, verdict, reach);
  return reach;
}

// True when no phase 1 patch is smaller than `rule` while having a neighbour (with phase 1's own rule, none is),
// and the mesh is manifold: then segments never merge across patches and each mixed patch is split on its own.
bool patches_split_alone(const SurfacePatches& patches, const SizeRule& rule) {
  if (patches.notes().nonmanifold_edges > 0) return false;
  if (!detail::is_active(rule)) return true;
  for (const Patch& p : patches.patches())
    if (!p.neighbours.empty() && detail::is_small(rule, p.facet_count, p.area, patches.total_area())) return false;
  return true;
}

// Splits every mixed patch (both cores, largest first). Returns false when a part is left small.
bool split_mixed_patches(const SurfacePatches& patches, const std::vector<Verdict>& verdict,
                         const std::vector<uint8_t>& reach, const SizeRule& rule,
                         std::vector<detail::PatchParts>& split) {
  std::vector<uint32_t> mixed;
  for (const Patch& p : patches.patches())
    if (verdict[p.id] == Verdict::Mixed) mixed.push_back(p.id);
  std::stable_sort(mixed.begin(), mixed.end(), [&](uint32_t a, uint32_t b) {
    return patches.patch(a).facet_count > patches.patch(b).facet_count;
  });
  split.resize(mixed.size());
  size_t mixed_facets = 0;
  for (uint32_t p : mixed) mixed_facets += patches.patch(p).facet_count;
  auto split_one = [&](size_t i, detail::PartsScratch& scratch) {
    detail::split_patch(patches, patches.patch(mixed[i]), reach, rule, scratch, split[i]);
  };
  // One patch at a time to whichever core is free, when there are 20,000 facets to split in two patches or more.
  if (mixed_facets > 20000 && mixed.size() > 1) {
    PerThread<detail::PartsScratch> scratch;
    for_each_chunk(mixed.size(), [&](size_t i) { split_one(i, scratch.local()); });
  } else {
    detail::PartsScratch scratch;
    for (size_t i = 0; i < mixed.size(); ++i) split_one(i, scratch);
  }
  for (const detail::PatchParts& s : split)
    if (s.small_left) return false;
  return true;
}

}  // namespace

std::vector<uint8_t> reachable_facets(const EgiSet& egis, const SetupFilter& filter, size_t* whole) {
  return facet_reach(egis.patches(), patch_verdicts(egis, filter, whole), filter);
}

double SetupSegmentation::reachable_fraction() const {
  // One pass over the facets: the whole minus what is out of reach, over the same whole. The segments' areas,
  // summed in another order than the total, gave 1.0000000000000022 (or 0.9999999999999999) when every facet is
  // reachable; here (total - 0) / total is exactly 1, and total - unreachable never exceeds total.
  const std::vector<double>& areas = patches_->mesh().areas;
  double total = 0.0, unreachable = 0.0;
  for (size_t f = 0; f < areas.size(); ++f) {
    total += areas[f];
    if (!reachable_[f]) unreachable += areas[f];
  }
  return total > 0.0 ? (total - unreachable) / total : 0.0;
}

SetupSegmentation segment_setup(const EgiSet& egis, const SetupFilter& filter, const SizeRule* small) {
  const SurfacePatches& patches = egis.patches();
  const SizeRule& rule = small ? *small : patches.options().small;
  SetupSegmentation out;
  out.patches_ = &patches;
  out.filter_ = filter;
  const std::vector<Verdict> verdict = patch_verdicts(egis, filter, &out.decided_by_egi_);
  out.reachable_ = facet_reach(patches, verdict, filter);

  std::vector<detail::PatchParts> split;
  if (patches_split_alone(patches, rule) && split_mixed_patches(patches, verdict, out.reachable_, rule, split))
    detail::assemble_segments(patches, verdict, split, out.labels_, out.facet_order_, out.segments_);
  else
    detail::segment_across_patches(patches, out.reachable_, rule, out.labels_, out.facet_order_, out.segments_);
  for (const Segment& seg : out.segments_) out.reachable_area_ += seg.reachable_area;
  return out;
}

}  // namespace rosmill::core::segment
