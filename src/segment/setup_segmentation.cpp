// Phase 2: prune each patch's EGI with the setup filter, split the patches that straddle it into connected
// reachable and unreachable parts, and recombine the small parts (preferring a neighbour of the same patch).
#include "rosmill/segment/setup_segmentation.hpp"

#include <cmath>

#include "labelling.hpp"

namespace rosmill::segment {
namespace {

enum class Verdict : uint8_t { Unreachable = 0, Reachable = 1, Mixed = 2 };

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
// it does not cut a segment in two.
void settle_degenerate(const SurfacePatches& patches, std::vector<uint8_t>& reach) {
  const Mesh& mesh = patches.mesh();
  if (patches.notes().degenerate_facets == 0) return;
  for (uint32_t f = 0; f < mesh.face_count(); ++f) {
    if (detail::has_area(mesh, f)) continue;
    for (int i = 0; i < 3; ++i) {
      const uint32_t g = mesh.neighbour(f, i);
      if (g != kNone && detail::has_area(mesh, g) && patches.label(g) == patches.label(f)) {
        reach[f] = reach[g];
        break;
      }
    }
  }
}

// Labels the connected parts of equal reachability, part by part (so without a union-find over every facet): a
// patch that is all reachable or all not stays one part; a mixed one is flooded across its manifold edges, and
// the edges between its parts join `edges`. Returns the number of parts.
uint32_t split_by_reach(const SurfacePatches& patches, const std::vector<uint8_t>& reach,
                        std::vector<uint32_t>& labels, std::vector<uint32_t>& edges) {
  const Mesh& mesh = patches.mesh();
  labels.assign(mesh.face_count(), kNone);
  std::vector<uint32_t> stack;
  uint32_t count = 0;
  for (const Patch& p : patches.patches()) {
    const uint32_t* begin = patches.facets_begin(p);
    const uint32_t* end = patches.facets_end(p);
    bool mixed = false;
    for (const uint32_t* f = begin; f != end && !mixed; ++f) mixed = reach[*f] != reach[*begin];
    if (!mixed) {
      for (const uint32_t* f = begin; f != end; ++f) labels[*f] = count;
      ++count;
      continue;
    }
    for (const uint32_t* seed = begin; seed != end; ++seed) {
      if (labels[*seed] != kNone) continue;
      labels[*seed] = count;
      stack.assign(1, *seed);
      while (!stack.empty()) {
        const uint32_t f = stack.back();
        stack.pop_back();
        for (int i = 0; i < 3; ++i) {
          const uint32_t g = mesh.neighbour(f, i);
          if (g == kNone || patches.label(g) != p.id) continue;
          if (reach[g] != reach[f]) {
            if (f < g) edges.push_back(mesh.face_edges[f][i]);
          } else if (labels[g] == kNone) {
            labels[g] = count;
            stack.push_back(g);
          }
        }
      }
      ++count;
    }
  }
  return count;
}

}  // namespace

std::vector<uint8_t> reachable_facets(const EgiSet& egis, const SetupFilter& filter, size_t* whole) {
  const SurfacePatches& patches = egis.patches();
  const Mesh& mesh = patches.mesh();
  const std::vector<Verdict> verdict = patch_verdicts(egis, filter, whole);
  const int64_t n = int64_t(mesh.face_count());
  std::vector<uint8_t> reach(n);
  const uint32_t* label = patches.labels().data();
  const ReachTest reaches(filter);
#pragma omp parallel for schedule(static) if (n > 20000)
  for (int64_t f = 0; f < n; ++f) {
    const Verdict v = verdict[label[f]];
    reach[f] = v == Verdict::Mixed ? uint8_t(reaches(mesh.normals[f])) : uint8_t(v);
  }
  return reach;
}

double SetupSegmentation::reachable_fraction() const {
  const double total = patches_->total_area();
  return total > 0.0 ? reachable_area_ / total : 0.0;
}

SetupSegmentation segment_setup(const EgiSet& egis, const SetupFilter& filter, const SizeRule* small) {
  const SurfacePatches& patches = egis.patches();
  const Mesh& mesh = patches.mesh();
  SetupSegmentation out;
  out.patches_ = &patches;
  out.filter_ = filter;
  out.reachable_ = reachable_facets(egis, filter, &out.decided_by_egi_);
  settle_degenerate(patches, out.reachable_);
  std::vector<uint8_t>& reach = out.reachable_;

  std::vector<uint32_t> edges = patches.cut_edges();
  uint32_t count = split_by_reach(patches, reach, out.labels_, edges);

  // Recombination, preferring a neighbour cut from the same patch.
  std::vector<uint32_t> group(count);
  for (uint32_t f = 0; f < mesh.face_count(); ++f) group[out.labels_[f]] = patches.label(f);
  std::vector<detail::LabelPair> pairs;
  count = detail::recombine(mesh, out.labels_, count, edges, small ? *small : patches.options().small,
                            patches.total_area(), pairs, &group);

  std::vector<Patch> shapes;
  detail::describe_patches(mesh, out.labels_, count, edges, pairs, shapes, out.facet_order_);
  out.segments_.resize(count);
  for (uint32_t f = 0; f < mesh.face_count(); ++f) {
    if (!reach[f]) continue;
    out.segments_[out.labels_[f]].reachable_area += mesh.areas[f];
    out.reachable_area_ += mesh.areas[f];
  }
  for (uint32_t s = 0; s < count; ++s) {
    Segment& seg = out.segments_[s];
    seg.shape = std::move(shapes[s]);
    seg.patch = patches.label(out.facet_order_[seg.shape.first_facet]);
    seg.reachable = seg.reachable_area >= 0.5 * seg.shape.area && seg.shape.area > 0.0 ? true
                    : seg.shape.area > 0.0                                             ? false
                                                                                       : true;
  }
  return out;
}

}  // namespace rosmill::segment
