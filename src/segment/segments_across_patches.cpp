// Phase 2 as one recombination across patches: every part of every patch labelled, recombined with the parts of
// the same patch preferred, and described from the labels. Taken when something small may have to join another
// patch (see patches_split_alone in setup_segmentation.cpp).
#include <algorithm>

#include "labelling.hpp"
#include "patch_parts.hpp"
#include "setup_steps.hpp"

namespace rosmill::core::segment::detail {
namespace {

// Labels the connected parts of equal reachability, part by part (so without a union-find over every facet): a
// patch that is all reachable or all not stays one part; a mixed one is flooded as the patch-local split floods
// it, and the edges between its parts join `edges`. Returns the number of parts.
uint32_t split_by_reach(const SurfacePatches& patches, const std::vector<uint8_t>& reach,
                        std::vector<uint32_t>& labels, std::vector<uint32_t>& edges) {
  const Mesh& mesh = patches.mesh();
  labels.resize(mesh.face_count());
  PartsScratch scratch;
  uint32_t count = 0;
  for (const Patch& p : patches.patches()) {
    const uint32_t* order = patches.facets_begin(p);
    bool mixed = false;
    for (uint32_t i = 1; i < p.facet_count && !mixed; ++i) mixed = reach[order[i]] != reach[order[0]];
    if (!mixed) {
      for (uint32_t i = 0; i < p.facet_count; ++i) labels[order[i]] = count;
      ++count;
      continue;
    }
    const uint32_t parts = flood_patch(patches, p, reach, scratch);
    for (uint32_t i = 0; i < p.facet_count; ++i) labels[order[i]] = count + scratch.part[i];
    for (uint32_t c : scratch.cross) edges.push_back(mesh.face_edges[order[c / 4]][c % 4]);
    count += parts;
  }
  return count;
}

}  // namespace

void segment_across_patches(const SurfacePatches& patches, const std::vector<uint8_t>& reach, const SizeRule& rule,
                            std::vector<uint32_t>& labels, std::vector<uint32_t>& facet_order,
                            std::vector<Segment>& segments) {
  const Mesh& mesh = patches.mesh();
  std::vector<uint32_t> edges = patches.cut_edges();
  uint32_t count = split_by_reach(patches, reach, labels, edges);
  // A sharp edge inside a patch (joined around it) is a cut edge and may also separate two parts: listed twice,
  // it would count twice in the boundary lengths and give its border two half-edges.
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<uint32_t> group(count);
  for (uint32_t f = 0; f < mesh.face_count(); ++f) group[labels[f]] = patches.label(f);
  std::vector<LabelPair> pairs;
  count = recombine(mesh, labels, count, edges, rule, patches.total_area(), pairs, &group);
  std::vector<Patch> shapes;
  describe_patches(mesh, labels, count, edges, pairs, shapes, facet_order);
  std::vector<double> reachable_area(count, 0.0);
  for (uint32_t f = 0; f < mesh.face_count(); ++f)
    if (reach[f]) reachable_area[labels[f]] += mesh.areas[f];
  segments.resize(count);
  for (uint32_t s = 0; s < count; ++s) {
    segments[s].shape = std::move(shapes[s]);
    finish_segment(segments[s], patches.label(facet_order[segments[s].shape.first_facet]), reachable_area[s]);
  }
}

}  // namespace rosmill::core::segment::detail
