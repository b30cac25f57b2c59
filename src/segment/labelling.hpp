// Internal helpers shared by phase 1 (surface patches) and phase 2 (setup segments): both end as a label per
// facet, are recombined by the same step and described by the same Patch records.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/segment/surface_patches.hpp"

namespace rosmill::segment::detail {

// Renumbers labels 0..count-1 in the order of their first facet; returns count.
uint32_t compact_labels(std::vector<uint32_t>& labels, uint32_t label_bound);

// Labels that share an edge, with the length they share. a < b; one entry per pair (lengths summed), in the
// order of the pairs' first edges.
struct LabelPair {
  uint32_t a, b;
  double length;
};
// Pairs over `edges` (the only edges that may separate two labels).
std::vector<LabelPair> label_pairs(const Mesh& mesh, const std::vector<uint32_t>& labels,
                                   const std::vector<uint32_t>& edges);

// Recombination (seed 001, 3.2.2): every label smaller than the rule merges into the neighbour sharing the
// longest boundary with it, in rounds until none is left that has a neighbour. `group` (optional, per label)
// makes a neighbour of the same group win over any other. Relabels compactly and returns the new count;
// `pairs` receives the label pairs of the result (as label_pairs() would give them, in another order).
uint32_t recombine(const Mesh& mesh, std::vector<uint32_t>& labels, uint32_t count,
                   const std::vector<uint32_t>& edges, const SizeRule& rule, double total_area,
                   std::vector<LabelPair>& pairs, const std::vector<uint32_t>* group = nullptr);

// Patch records (facets, area, mean normal, neighbours, boundary loops) for compact labels 0..count-1, whose
// label pairs recombine() gave.
void describe_patches(const Mesh& mesh, const std::vector<uint32_t>& labels, uint32_t count,
                      const std::vector<uint32_t>& edges, const std::vector<LabelPair>& pairs,
                      std::vector<Patch>& patches, std::vector<uint32_t>& facet_order);

// True when facet f has an area (and so a normal).
inline bool has_area(const Mesh& mesh, size_t f) { return mesh.areas[f] > 0.0; }

}  // namespace rosmill::segment::detail
