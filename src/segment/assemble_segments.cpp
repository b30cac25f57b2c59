// Phase 2 laid out patch by patch: the whole patches keep their phase 1 records, the split patches bring their
// parts, and both are numbered by first facet, with the neighbours across patches linked at the end.
#include <algorithm>

#include "setup_steps.hpp"

namespace rosmill::segment::detail {

void finish_segment(Segment& seg, uint32_t patch, double reachable_area) {
  seg.patch = patch;
  seg.reachable_area = reachable_area;
  seg.reachable = seg.shape.area > 0.0 ? reachable_area >= 0.5 * seg.shape.area : true;
}

namespace {

// Where a segment comes from: a whole patch (`split` kNone, `index` the patch) or a part of a split patch.
struct SegmentSource {
  uint32_t first_facet, split, index;
};

}  // namespace

void assemble_segments(const SurfacePatches& patches, const std::vector<Verdict>& verdict,
                       std::vector<PatchParts>& split, std::vector<uint32_t>& labels,
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
      PatchParts& parts = split[src.split];
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

}  // namespace rosmill::segment::detail
