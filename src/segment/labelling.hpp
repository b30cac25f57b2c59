// Internal helpers shared by phase 1 (surface patches) and phase 2 (setup segments): both end as a label per
// facet, are recombined by the same step and described by the same Patch records.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/segment/surface_patches.hpp"

namespace rosmill::core::segment::detail {

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
// Sums the lengths of equal pairs in place, keeping the order of first appearance.
void sum_equal_pairs(std::vector<LabelPair>& pairs);

// False when the rule merges nothing (a zero size).
bool is_active(const SizeRule& rule);
bool is_small(const SizeRule& rule, size_t facets, double area, double total_area);

// The rounds of the recombination on a label graph (`graph`: summed pairs; `area`, `facets`: per label): in
// each round every label smaller than the rule picks the neighbour sharing the longest boundary with it (a
// neighbour of the same `group` first, when given), then all picks merge. Returns each label's root; `graph`
// ends as the pairs between roots.
std::vector<uint32_t> merge_small(std::vector<LabelPair>& graph, std::vector<double> area,
                                  std::vector<uint32_t> facets, const SizeRule& rule, double total_area,
                                  const std::vector<uint32_t>* group = nullptr);

// Recombination (Lefebvre & Lauwers, section 3.2.2): every label smaller than the rule merges into the neighbour
// sharing the
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

// A directed edge, in its facet's winding, on the border of the facet's patch; `open` when the mesh edge has no
// other facet.
struct HalfEdge {
  uint32_t label, from, to;
  bool open;
};
// Chains one patch's border half-edges [begin, end) into loops by following each edge's end vertex. `head` (sized
// to the mesh's vertices, kNone everywhere) is left as it was given; `link` is scratch.
void chain_loops(const HalfEdge* begin, const HalfEdge* end, std::vector<uint32_t>& head, std::vector<uint32_t>& link,
                 std::vector<BoundaryLoop>& loops);

// The unit area-weighted mean normal from the sum of area * normal, zero when the normals cancel.
inline Vec3 mean_normal(const Vec3& sum, double area) {
  const double len = sum.norm();
  return len > 1e-12 * std::max(area, 1e-300) ? Vec3(sum / len) : Vec3(Vec3::Zero());
}

// Length of mesh edge e.
inline double edge_length(const Mesh& mesh, uint32_t e) {
  return (mesh.vertices[mesh.edges[e].a] - mesh.vertices[mesh.edges[e].b]).norm();
}

// True when facet f has an area (and so a normal).
inline bool has_area(const Mesh& mesh, size_t f) { return mesh.areas[f] > 0.0; }

}  // namespace rosmill::core::segment::detail
