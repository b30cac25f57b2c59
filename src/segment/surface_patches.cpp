// Phase 1 surface flooding (Lefebvre & Lauwers, section 3.2.2) as a linear pass: every manifold edge is tested once
// (both cores),
// then a union-find joins the facets across the edges that pass. A patch is then exactly the set of facets a
// flood from any of its facets reaches, including facets first rejected through another edge (figs. 6, 7).
#include <cmath>
#include <functional>
#include <string>

#include "labelling.hpp"
#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "union_find.hpp"

namespace rosmill::core::segment {
namespace {

using detail::has_area;
using detail::UnionFind;

void check_options(const SegmentOptions& o) {
  if (!(o.threshold > 0.0 && o.threshold <= 2.0))
    throw Error("parameter threshold", "must be in (0, 2] (length of a difference of unit normals), got " +
                                           std::to_string(o.threshold));
  if (o.small.kind == SizeRule::Kind::AreaFraction && !(o.small.min_area_fraction >= 0.0 &&
                                                        o.small.min_area_fraction < 1.0))
    throw Error("parameter min_area_fraction", "must be in [0, 1), got " + std::to_string(o.small.min_area_fraction));
}

// Loops over edges and facets run on both cores from 20,000 items on (a range no longer than its grain is not
// split, so smaller meshes stay on the calling thread: their threads' start would cost more), in pieces taken on
// demand rather than one half per core: a worker woken from sleep starts late, and the calling thread goes on.
constexpr size_t kParallelFrom = 20000;

// The open, non-manifold and inconsistent edges of a range of edges.
struct EdgeCounts {
  size_t open = 0, nonmanifold = 0, inconsistent = 0;
  EdgeCounts operator+(const EdgeCounts& o) const {
    return {open + o.open, nonmanifold + o.nonmanifold, inconsistent + o.inconsistent};
  }
};

// Edges [first, last) of the mesh: marks those the flood crosses in `soft` and counts the others by kind. The
// mesh's arrays are read into locals first: a byte stored through `soft` could otherwise be any of them.
EdgeCounts classify_edges(const Mesh& mesh, double t2, size_t first, size_t last, uint8_t* soft) {
  const MeshEdge* edges = mesh.edges.data();
  const uint32_t* edge_faces = mesh.edge_faces.data();
  const double* areas = mesh.areas.data();
  const Vec3* normals = mesh.normals.data();
  EdgeCounts c;
  for (size_t e = first; e < last; ++e) {
    const MeshEdge& edge = edges[e];
    uint8_t pass = 0;
    if (edge.face_count == 2) {
      const uint32_t f0 = edge_faces[edge.first_face], f1 = edge_faces[edge.first_face + 1];
      c.inconsistent += !edge.consistent;
      if (areas[f0] > 0.0 && areas[f1] > 0.0) pass = (normals[f0] - normals[f1]).squaredNorm() < t2;
    } else if (edge.face_count == 1) {
      ++c.open;
    } else {
      ++c.nonmanifold;
    }
    soft[e] = pass;
  }
  return c;
}

// Marks the edges the flood crosses: manifold, both facets with an area, normals closer than the threshold.
// Counts the mesh's open, non-manifold and inconsistent edges on the way.
std::vector<uint8_t> soft_edges(const Mesh& mesh, double threshold, MeshNotes& notes) {
  const double t2 = threshold * threshold;
  std::vector<uint8_t> soft(mesh.edges.size());
  const EdgeCounts counts = reduce_pieces(
      size_t(0), mesh.edges.size(), kParallelFrom, EdgeCounts{},
      [&](size_t begin, size_t end, const EdgeCounts& c) {
        return c + classify_edges(mesh, t2, begin, end, soft.data());
      },
      std::plus<EdgeCounts>());
  notes.open_edges = counts.open;
  notes.nonmanifold_edges = counts.nonmanifold;
  notes.inconsistent_edges = counts.inconsistent;
  return soft;
}

// Joins the facets across soft edges; a non-manifold edge joins each pair of its facets that passes the test.
void flood(const Mesh& mesh, const std::vector<uint8_t>& soft, double threshold, UnionFind& sets,
           std::vector<uint32_t>& cut) {
  const double t2 = threshold * threshold;
  for (uint32_t e = 0; e < soft.size(); ++e) {
    const MeshEdge& edge = mesh.edges[e];
    const uint32_t* faces = mesh.edge_faces.data() + edge.first_face;
    if (soft[e]) {
      sets.unite(faces[0], faces[1]);
      continue;
    }
    cut.push_back(e);
    for (uint32_t i = 0; edge.face_count > 2 && i < edge.face_count; ++i)
      for (uint32_t j = i + 1; j < edge.face_count; ++j)
        if (has_area(mesh, faces[i]) && has_area(mesh, faces[j]) &&
            (mesh.normals[faces[i]] - mesh.normals[faces[j]]).squaredNorm() < t2)
          sets.unite(faces[i], faces[j]);
  }
}

// Zero-area facets have no normal to test: each joins the patch of a neighbour across one of its edges (through
// chains of such facets if need be), and bridges the facets around it whose normals agree with that neighbour,
// so a sliver inside a flat face does not cut it. A group of them touching no real facet joins the largest
// facet's patch. Returns the number of zero-area facets.
size_t attach_degenerate(const Mesh& mesh, double threshold, UnionFind& sets) {
  const double t2 = threshold * threshold;
  std::vector<uint32_t> pending;
  for (uint32_t f = 0; f < mesh.face_count(); ++f)
    if (!has_area(mesh, f)) pending.push_back(f);
  const size_t degenerate = pending.size();
  std::vector<char> attached(mesh.face_count(), 0);
  bool changed = true;
  std::vector<uint32_t> real;
  while (!pending.empty() && changed) {
    changed = false;
    size_t keep = 0;
    for (uint32_t d : pending) {
      real.clear();
      uint32_t via = kNone;
      for (int i = 0; i < 3; ++i) {
        const MeshEdge& edge = mesh.edges[mesh.face_edges[d][i]];
        for (uint32_t k = 0; k < edge.face_count; ++k) {
          const uint32_t g = mesh.edge_faces[edge.first_face + k];
          if (g == d) continue;
          if (has_area(mesh, g)) real.push_back(g);
          else if (attached[g] && via == kNone) via = g;
        }
      }
      if (!real.empty()) via = real.front();
      if (via == kNone) {
        pending[keep++] = d;
        continue;
      }
      sets.unite(d, via);
      attached[d] = 1;
      changed = true;
      for (uint32_t g : real)
        if ((mesh.normals[g] - mesh.normals[real.front()]).squaredNorm() < t2) sets.unite(g, real.front());
    }
    pending.resize(keep);
  }
  if (!pending.empty()) {
    uint32_t largest = kNone;
    for (uint32_t f = 0; f < mesh.face_count(); ++f)
      if (has_area(mesh, f) && (largest == kNone || mesh.areas[f] > mesh.areas[largest])) largest = f;
    for (uint32_t d : pending) sets.unite(d, largest == kNone ? pending.front() : largest);
  }
  return degenerate;
}

// SurfacePatches::inner_neighbours from the manifold edges (both cores): an edge whose two facets share a patch
// links each facet's corner slot of that edge to the other's position. Each (facet, corner) slot belongs to one
// edge, so the threads never write the same slot; a facet listing one edge twice (a repeated corner) gets it in
// both slots.
std::vector<std::array<uint32_t, 3>> inner_neighbours(const Mesh& mesh, const std::vector<uint32_t>& labels,
                                                      const std::vector<uint32_t>& facet_order) {
  const int64_t n = int64_t(facet_order.size()), edge_count = int64_t(mesh.edges.size());
  std::vector<uint32_t> position(n);
  std::vector<std::array<uint32_t, 3>> inner(n, {kNone, kNone, kNone});
  auto link = [&](uint32_t f, uint32_t e, uint32_t to) {
    for (int k = 0; k < 3; ++k)
      if (mesh.face_edges[f][k] == e) inner[position[f]][k] = to;
  };
  // Both loops on both cores when the facets are many (the edges, about 1.5 per facet, follow the facets' choice).
  auto each = [parallel = n > int64_t(kParallelFrom)](int64_t count, const auto& body) {
    if (parallel)
      for_each_index(int64_t(0), count, body);
    else
      for (int64_t i = 0; i < count; ++i) body(i);
  };
  each(n, [&](int64_t i) { position[facet_order[i]] = uint32_t(i); });
  each(edge_count, [&](int64_t e) {
    const MeshEdge& edge = mesh.edges[e];
    if (edge.face_count != 2) return;
    const uint32_t f0 = mesh.edge_faces[edge.first_face], f1 = mesh.edge_faces[edge.first_face + 1];
    if (labels[f0] != labels[f1]) return;
    link(f0, uint32_t(e), position[f1]);
    link(f1, uint32_t(e), position[f0]);
  });
  return inner;
}

}  // namespace

SurfacePatches segment_surface(const Mesh& mesh, const SegmentOptions& options) {
  check_options(options);
  check_has_area(mesh, "segmentation: the part");
  SurfacePatches out;
  out.mesh_ = &mesh;
  out.options_ = options;
  const size_t n = mesh.face_count();
  for (double a : mesh.areas) out.total_area_ += a;

  const std::vector<uint8_t> soft = soft_edges(mesh, options.threshold, out.notes_);
  UnionFind sets(n);
  flood(mesh, soft, options.threshold, sets, out.cut_edges_);
  out.notes_.degenerate_facets = attach_degenerate(mesh, options.threshold, sets);

  out.labels_.resize(n);
  for (uint32_t f = 0; f < n; ++f) out.labels_[f] = sets.find(f);
  uint32_t count = detail::compact_labels(out.labels_, uint32_t(n));
  out.notes_.patches_before_recombination = count;
  std::vector<detail::LabelPair> pairs;
  count = detail::recombine(mesh, out.labels_, count, out.cut_edges_, options.small, out.total_area_, pairs);
  detail::describe_patches(mesh, out.labels_, count, out.cut_edges_, pairs, out.patches_, out.facet_order_);
  out.inner_neighbours_ = inner_neighbours(mesh, out.labels_, out.facet_order_);
  return out;
}

}  // namespace rosmill::core::segment
