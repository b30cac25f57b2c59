// Phase 2 laid out patch by patch: the whole patches keep their phase 1 records, the split patches bring their
// parts, and both are numbered by first facet, with the neighbours across patches linked at the end.
#include <algorithm>

#include "rosmill/parallel.hpp"
#include "setup_steps.hpp"

namespace rosmill::core::segment::detail {

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

// The segments' numbers: in the order of their first facets, as the labels of a recombination are numbered.
struct Numbering {
  std::vector<SegmentSource> sources;          // by segment number
  std::vector<uint32_t> of_patch;              // segment of each whole patch (kNone for split ones)
  std::vector<std::vector<uint32_t>> of_part;  // segment of each part of each split patch
};

Numbering number_segments(const SurfacePatches& patches, const std::vector<Verdict>& verdict,
                          const std::vector<PatchParts>& split) {
  Numbering out;
  for (const Patch& p : patches.patches())
    if (verdict[p.id] != Verdict::Mixed) out.sources.push_back({patches.facet_order()[p.first_facet], kNone, p.id});
  for (uint32_t s = 0; s < split.size(); ++s)
    for (const Patch& part : split[s].parts) out.sources.push_back({split[s].order[part.first_facet], s, part.id});
  std::sort(out.sources.begin(), out.sources.end(),
            [](const SegmentSource& a, const SegmentSource& b) { return a.first_facet < b.first_facet; });
  out.of_patch.assign(patches.count(), kNone);
  out.of_part.resize(split.size());
  for (uint32_t s = 0; s < split.size(); ++s) out.of_part[s].resize(split[s].parts.size());
  for (uint32_t id = 0; id < out.sources.size(); ++id) {
    const SegmentSource& src = out.sources[id];
    (src.split == kNone ? out.of_patch[src.index] : out.of_part[src.split][src.index]) = id;
  }
  return out;
}

// Labels: the whole patches in one pass over the facets (both cores from 20,000 facets on, in pieces taken on
// demand: a range no longer than its grain stays on the calling thread), then the split patches' parts. (Copied
// from the patch labels and renumbered in place: a vector's zero-filling resize is a slow loop for 32-bit words.)
void write_labels(const SurfacePatches& patches, const std::vector<PatchParts>& split, const Numbering& number,
                  std::vector<uint32_t>& labels) {
  labels = patches.labels();
  const uint32_t* of_patch = number.of_patch.data();
  uint32_t* label = labels.data();
  for_each_piece<size_t>(0, labels.size(), 20000, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; ++f) label[f] = of_patch[label[f]];
  });
  for (uint32_t s = 0; s < split.size(); ++s)
    for (const Patch& part : split[s].parts)
      for (uint32_t i = part.first_facet; i < part.first_facet + part.facet_count; ++i)
        labels[split[s].order[i]] = number.of_part[s][part.id];
}

// Neighbours across the split patches' borders, both ways. A part's outer edges come in one run, so a stamp per
// segment keeps each pair once from that side (long borders of tiny facets repeat a pair thousands of times).
void link_across_patches(const Mesh& mesh, const std::vector<PatchParts>& split, const Numbering& number,
                         const std::vector<uint32_t>& labels, std::vector<Segment>& segments) {
  std::vector<uint32_t> stamp(segments.size(), kNone);
  for (uint32_t s = 0; s < split.size(); ++s)
    for (const auto& [part, e] : split[s].outer) {
      const uint32_t a = number.of_part[s][part];
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

void assemble_segments(const SurfacePatches& patches, const std::vector<Verdict>& verdict,
                       std::vector<PatchParts>& split, std::vector<uint32_t>& labels,
                       std::vector<uint32_t>& facet_order, std::vector<Segment>& segments) {
  const Numbering number = number_segments(patches, verdict, split);
  write_labels(patches, split, number, labels);
  facet_order.clear();
  facet_order.reserve(labels.size());
  segments.resize(number.sources.size());
  uint32_t offset = 0;
  for (uint32_t id = 0; id < number.sources.size(); ++id) {
    const SegmentSource& src = number.sources[id];
    Segment& seg = segments[id];
    const uint32_t* from;
    if (src.split == kNone) {  // a whole patch: its phase 1 record, with neighbours among the whole patches
      const Patch& p = patches.patch(src.index);
      seg.shape.area = p.area;
      seg.shape.normal = p.normal;
      seg.shape.loops = p.loops;
      seg.shape.facet_count = p.facet_count;
      for (uint32_t q : p.neighbours)
        if (number.of_patch[q] != kNone) seg.shape.neighbours.push_back(number.of_patch[q]);
      from = patches.facets_begin(p);
      finish_segment(seg, p.id, verdict[p.id] == Verdict::Reachable ? p.area : 0.0);
    } else {  // a part: its record, with its siblings renumbered
      PatchParts& parts = split[src.split];
      seg.shape = std::move(parts.parts[src.index]);
      for (uint32_t& q : seg.shape.neighbours) q = number.of_part[src.split][q];
      from = parts.order.data() + seg.shape.first_facet;
      finish_segment(seg, parts.patch, parts.reachable_area[src.index]);
    }
    seg.shape.id = id;
    seg.shape.first_facet = offset;
    facet_order.insert(facet_order.end(), from, from + seg.shape.facet_count);
    offset += seg.shape.facet_count;
  }
  link_across_patches(patches.mesh(), split, number, labels, segments);
}

}  // namespace rosmill::core::segment::detail
