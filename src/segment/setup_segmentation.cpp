// Phase 2: prune each patch's EGI with the setup filter, split the patches that straddle it into connected
// reachable and unreachable parts, and recombine the small parts (into a part of the same patch first). Whole
// patches keep their phase 1 records; only the split patches are described anew.
#include "rosmill/segment/setup_segmentation.hpp"

#include <algorithm>
#include <cmath>

#include "labelling.hpp"
#include "patch_parts.hpp"

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

// Per facet reachability: the patch's verdict, or the exact test for the facets of mixed patches.
template <typename Test>
void fill_reach(const SurfacePatches& patches, const std::vector<Verdict>& verdict, const Test& test,
                std::vector<uint8_t>& reach) {
  const Mesh& mesh = patches.mesh();
  const int64_t n = int64_t(mesh.face_count());
  const uint32_t* label = patches.labels().data();
  const Vec3* normal = mesh.normals.data();
  const Verdict* v = verdict.data();
#pragma omp parallel for schedule(static) if (n > 20000)
  for (int64_t f = 0; f < n; ++f) {
    const Verdict patch = v[label[f]];
    reach[f] = patch == Verdict::Mixed ? uint8_t(test(normal[f])) : uint8_t(patch);
  }
}

std::vector<uint8_t> facet_reach(const SurfacePatches& patches, const std::vector<Verdict>& verdict,
                                 const SetupFilter& filter) {
  std::vector<uint8_t> reach(patches.mesh().face_count());
  fill_reach(patches, verdict, ReachTest(filter), reach);
  settle_degenerate(patches, verdict, reach);
  return reach;
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

// Segment fields that follow from its shape and reachable area.
void finish_segment(Segment& seg, uint32_t patch, double reachable_area) {
  seg.patch = patch;
  seg.reachable_area = reachable_area;
  seg.reachable = seg.shape.area > 0.0 ? reachable_area >= 0.5 * seg.shape.area : true;
}

// The segments as one recombination over every part of every patch (a neighbour of the same patch first). Used
// when something small may have to join another patch: a phase 1 patch smaller than this rule, a part touching
// no sibling; and on non-manifold meshes, whose inner edges the patch-local split does not see.
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
  std::vector<detail::LabelPair> pairs;
  count = detail::recombine(mesh, labels, count, edges, rule, patches.total_area(), pairs, &group);
  std::vector<Patch> shapes;
  detail::describe_patches(mesh, labels, count, edges, pairs, shapes, facet_order);
  std::vector<double> reachable_area(count, 0.0);
  for (uint32_t f = 0; f < mesh.face_count(); ++f)
    if (reach[f]) reachable_area[labels[f]] += mesh.areas[f];
  segments.resize(count);
  for (uint32_t s = 0; s < count; ++s) {
    segments[s].shape = std::move(shapes[s]);
    finish_segment(segments[s], patches.label(facet_order[segments[s].shape.first_facet]), reachable_area[s]);
  }
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
  const int64_t n = int64_t(mixed.size());
  size_t mixed_facets = 0;
  for (uint32_t p : mixed) mixed_facets += patches.patch(p).facet_count;
#pragma omp parallel if (mixed_facets > 20000 && n > 1)
  {
    detail::PartsScratch scratch;
#pragma omp for schedule(dynamic, 1)
    for (int64_t i = 0; i < n; ++i) detail::split_patch(patches, patches.patch(mixed[i]), reach, rule, scratch, split[i]);
  }
  for (const detail::PatchParts& s : split)
    if (s.small_left) return false;
  return true;
}

// Where a segment comes from: a whole patch (`split` kNone, `index` the patch) or a part of a split patch.
struct SegmentSource {
  uint32_t first_facet, split, index;
};

// Numbers the whole patches and the parts of the split ones in the order of their first facets (as the labels
// of a recombination are numbered) and lays out labels, facet order and segments.
void assemble_segments(const SurfacePatches& patches, const std::vector<Verdict>& verdict,
                       std::vector<detail::PatchParts>& split, std::vector<uint32_t>& labels,
                       std::vector<uint32_t>& facet_order, std::vector<Segment>& segments) {
  const Mesh& mesh = patches.mesh();
  std::vector<SegmentSource> sources;
  for (const Patch& p : patches.patches())
    if (verdict[p.id] != Verdict::Mixed) sources.push_back({patches.facet_order()[p.first_facet], kNone, p.id});
  for (uint32_t s = 0; s < split.size(); ++s)
    for (const Patch& part : split[s].parts) sources.push_back({split[s].order[part.first_facet], s, part.id});
  std::sort(sources.begin(), sources.end(),
            [](const SegmentSource& a, const SegmentSource& b) { return a.first_facet < b.first_facet; });

  std::vector<uint32_t> of_patch(patches.count(), kNone);
  std::vector<std::vector<uint32_t>> of_part(split.size());
  for (uint32_t s = 0; s < split.size(); ++s) of_part[s].resize(split[s].parts.size());
  for (uint32_t id = 0; id < sources.size(); ++id)
    (sources[id].split == kNone ? of_patch[sources[id].index] : of_part[sources[id].split][sources[id].index]) = id;

  // Labels: whole patches in one pass over the facets, then the split patches' parts.
  const int64_t n = int64_t(mesh.face_count());
  labels.resize(n);
  const uint32_t* label = patches.labels().data();
#pragma omp parallel for schedule(static) if (n > 20000)
  for (int64_t f = 0; f < n; ++f) labels[f] = of_patch[label[f]];
  for (uint32_t s = 0; s < split.size(); ++s)
    for (const Patch& part : split[s].parts)
      for (uint32_t i = part.first_facet; i < part.first_facet + part.facet_count; ++i)
        labels[split[s].order[i]] = of_part[s][part.id];

  facet_order.resize(n);
  segments.resize(sources.size());
  uint32_t offset = 0;
  for (uint32_t id = 0; id < sources.size(); ++id) {
    const SegmentSource& src = sources[id];
    Segment& seg = segments[id];
    const uint32_t* from;
    if (src.split == kNone) {
      const Patch& p = patches.patch(src.index);
      seg.shape.area = p.area;
      seg.shape.normal = p.normal;
      seg.shape.loops = p.loops;
      seg.shape.facet_count = p.facet_count;
      for (uint32_t q : p.neighbours)
        if (of_patch[q] != kNone) seg.shape.neighbours.push_back(of_patch[q]);
      from = patches.facets_begin(p);
      finish_segment(seg, p.id, verdict[p.id] == Verdict::Reachable ? p.area : 0.0);
    } else {
      detail::PatchParts& parts = split[src.split];
      Patch& part = parts.parts[src.index];
      seg.shape = std::move(part);
      for (uint32_t& q : seg.shape.neighbours) q = of_part[src.split][q];
      from = parts.order.data() + seg.shape.first_facet;
      finish_segment(seg, parts.patch, parts.reachable_area[src.index]);
    }
    seg.shape.id = id;
    seg.shape.first_facet = offset;
    std::copy(from, from + seg.shape.facet_count, facet_order.begin() + offset);
    offset += seg.shape.facet_count;
  }
  // Neighbours across the split patches' borders, both ways. A part's outer edges come in one run, so a stamp
  // per segment keeps each pair once from that side (long borders of tiny facets repeat a pair thousands of times).
  std::vector<uint32_t> stamp(segments.size(), kNone);
  for (uint32_t s = 0; s < split.size(); ++s)
    for (const auto& [part, e] : split[s].outer) {
      const uint32_t a = of_part[s][part];
      const MeshEdge& edge = mesh.edges[e];
      for (uint32_t k = 0; k < edge.face_count; ++k) {
        const uint32_t b = labels[mesh.edge_faces[edge.first_face + k]];
        if (b == a || stamp[b] == a) continue;
        stamp[b] = a;
        segments[a].shape.neighbours.push_back(b);
        segments[b].shape.neighbours.push_back(a);
      }
    }
  for (Segment& seg : segments) {
    std::vector<uint32_t>& nb = seg.shape.neighbours;
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  }
}

}  // namespace

std::vector<uint8_t> reachable_facets(const EgiSet& egis, const SetupFilter& filter, size_t* whole) {
  return facet_reach(egis.patches(), patch_verdicts(egis, filter, whole), filter);
}

double SetupSegmentation::reachable_fraction() const {
  const double total = patches_->total_area();
  return total > 0.0 ? reachable_area_ / total : 0.0;
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
    assemble_segments(patches, verdict, split, out.labels_, out.facet_order_, out.segments_);
  else
    segment_across_patches(patches, out.reachable_, rule, out.labels_, out.facet_order_, out.segments_);
  for (const Segment& seg : out.segments_) out.reachable_area_ += seg.reachable_area;
  return out;
}

}  // namespace rosmill::segment
