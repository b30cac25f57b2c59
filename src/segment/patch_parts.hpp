// Phase 2 inside one patch: a patch the setup reaches only in part is cut into its connected reachable and
// unreachable parts, and the parts too small to machine join the sibling they share the longest boundary with.
// Patches are independent of each other here (both cores take them in turn); segment_setup() then numbers the
// parts among the whole patches and links the neighbours across patches.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "labelling.hpp"

namespace rosmill::core::segment::detail {

struct PatchParts {
  uint32_t patch = 0;
  // The patch's facets grouped by part (ascending within a part).
  std::vector<uint32_t> order;
  // Per part: first_facet indexes `order`; id is the part's number in the patch (parts are numbered by their
  // first facet); neighbours are sibling parts; loops are final.
  std::vector<Patch> parts;
  std::vector<double> reachable_area;
  // (part, mesh edge) of each border half-edge of the patch whose edge has other facets, by part: the neighbours
  // across patches, resolved once every segment has its number.
  std::vector<std::pair<uint32_t, uint32_t>> outer;
  // A part still smaller than the rule (it touches no sibling): only a recombination across patches settles it.
  bool small_left = false;
};

// Buffers reused from patch to patch by one thread.
struct PartsScratch {
  std::vector<uint8_t> reach, part_reach;
  std::vector<uint32_t> part, final_part, stack, cross, fill;
  std::vector<LabelPair> graph;
  // Per part (before recombination): area, facet count, sum of area * normal.
  std::vector<double> area;
  std::vector<uint32_t> facets;
  std::vector<Vec3> normal;
  std::vector<HalfEdge> half, grouped;
  std::vector<std::pair<uint32_t, uint32_t>> outer;
  std::vector<uint32_t> head, link;  // head: one per mesh vertex, kNone between calls
};

// Labels the connected parts of equal reachability (`reach`: per facet, mesh order) of `patch` by flooding across
// its inner edges: s.part per position in the patch (parts numbered by first position), and per part its facet
// count, area, normal sum and reachability. s.cross receives 4 * i + k for each inner edge k of local facet i that
// separates two parts (once per edge: from its lower position). Returns the number of parts.
uint32_t flood_patch(const SurfacePatches& patches, const Patch& patch, const std::vector<uint8_t>& reach,
                     PartsScratch& s);

// Cuts `patch` by the per-facet reachability `reach` (mesh order) and recombines inside it with `rule`.
void split_patch(const SurfacePatches& patches, const Patch& patch, const std::vector<uint8_t>& reach,
                 const SizeRule& rule, PartsScratch& scratch, PatchParts& out);

}  // namespace rosmill::core::segment::detail
