// The steps of phase 2 after the per-facet reachability, shared by setup_segmentation.cpp and the files that
// lay out its result: patch by patch (assemble_segments.cpp) or in one recombination across patches
// (segments_across_patches.cpp).
#pragma once
#include <cstdint>
#include <vector>

#include "patch_parts.hpp"
#include "rosmill/segment/setup_segmentation.hpp"

namespace rosmill::core::segment::detail {

// A patch's verdict from its EGI: every occupied bin inside the setup's reach, outside it, or some of each.
enum class Verdict : uint8_t { Unreachable = 0, Reachable = 1, Mixed = 2 };

// Segment fields that follow from its shape and reachable area.
void finish_segment(Segment& seg, uint32_t patch, double reachable_area);

// The segments as one recombination over every part of every patch (a neighbour of the same patch first). Used
// when something small may have to join another patch: a phase 1 patch smaller than this rule, a part touching
// no sibling; and on non-manifold meshes, whose inner edges the patch-local split does not see.
void segment_across_patches(const SurfacePatches& patches, const std::vector<uint8_t>& reach, const SizeRule& rule,
                            std::vector<uint32_t>& labels, std::vector<uint32_t>& facet_order,
                            std::vector<Segment>& segments);

// Numbers the whole patches and the parts of the split ones in the order of their first facets (as the labels
// of a recombination are numbered) and lays out labels, facet order and segments.
void assemble_segments(const SurfacePatches& patches, const std::vector<Verdict>& verdict,
                       std::vector<PatchParts>& split, std::vector<uint32_t>& labels,
                       std::vector<uint32_t>& facet_order, std::vector<Segment>& segments);

}  // namespace rosmill::core::segment::detail
