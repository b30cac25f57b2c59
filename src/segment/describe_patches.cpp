// Patch records from a label per facet: facets grouped by patch (a counting sort), area, area-weighted mean
// normal, neighbouring patches and the boundary loops. Only the edges that may separate patches are visited
// for neighbours and loops, so the cost is one pass over the facets plus the patch borders.
#include <algorithm>

#include "labelling.hpp"

namespace rosmill::segment::detail {
namespace {

struct HalfEdge {
  uint32_t label, from, to;
  bool open;
};

// The corner of face f whose edge (corner -> next corner) is e.
int corner_of_edge(const Mesh& mesh, uint32_t f, uint32_t e) {
  for (int i = 0; i < 3; ++i)
    if (mesh.face_edges[f][i] == e) return i;
  return 0;
}

// Directed edges, in each facet's winding, that lie on the border of the facet's patch.
std::vector<HalfEdge> border_half_edges(const Mesh& mesh, const std::vector<uint32_t>& labels,
                                        const std::vector<uint32_t>& edges) {
  std::vector<HalfEdge> half;
  for (uint32_t e : edges) {
    const MeshEdge& edge = mesh.edges[e];
    if (edge.a == edge.b) continue;  // an edge of a facet with a repeated corner
    const uint32_t* faces = mesh.edge_faces.data() + edge.first_face;
    for (uint32_t i = 0; i < edge.face_count; ++i) {
      const uint32_t f = faces[i];
      const bool inside = edge.face_count == 2 && labels[faces[1 - i]] == labels[f];
      if (inside) continue;
      const int c = corner_of_edge(mesh, f, e);
      half.push_back({labels[f], mesh.faces[f][c], mesh.faces[f][(c + 1) % 3], edge.face_count == 1});
    }
  }
  std::sort(half.begin(), half.end(), [](const HalfEdge& l, const HalfEdge& r) {
    if (l.label != r.label) return l.label < r.label;
    return l.from != r.from ? l.from < r.from : l.to < r.to;
  });
  return half;
}

// Chains one patch's border half-edges [begin, end) into loops by following each edge's end vertex.
void chain_loops(const HalfEdge* begin, const HalfEdge* end, std::vector<char>& used, size_t used_base,
                 std::vector<BoundaryLoop>& loops) {
  auto next_from = [&](uint32_t v) -> const HalfEdge* {
    const HalfEdge* it = std::lower_bound(begin, end, v, [](const HalfEdge& h, uint32_t x) { return h.from < x; });
    for (; it != end && it->from == v; ++it)
      if (!used[used_base + (it - begin)]) return it;
    return nullptr;
  };
  for (const HalfEdge* start = begin; start != end; ++start) {
    if (used[used_base + (start - begin)]) continue;
    BoundaryLoop loop;
    loop.mesh_border = true;
    const HalfEdge* h = start;
    for (;;) {
      used[used_base + (h - begin)] = 1;
      loop.vertices.push_back(h->from);
      loop.mesh_border = loop.mesh_border && h->open;
      if (h->to == start->from) break;
      const HalfEdge* next = next_from(h->to);
      if (!next) {  // broken orientation or a non-manifold vertex: report the chain open
        loop.vertices.push_back(h->to);
        loop.closed = false;
        break;
      }
      h = next;
    }
    loops.push_back(std::move(loop));
  }
}

}  // namespace

void describe_patches(const Mesh& mesh, const std::vector<uint32_t>& labels, uint32_t count,
                      const std::vector<uint32_t>& edges, std::vector<Patch>& patches,
                      std::vector<uint32_t>& facet_order) {
  patches.assign(count, Patch{});
  std::vector<Vec3> normal_sum(count, Vec3::Zero());
  for (size_t f = 0; f < labels.size(); ++f) {
    Patch& p = patches[labels[f]];
    ++p.facet_count;
    p.area += mesh.areas[f];
    normal_sum[labels[f]] += mesh.areas[f] * mesh.normals[f];
  }
  uint32_t offset = 0;
  for (uint32_t i = 0; i < count; ++i) {
    Patch& p = patches[i];
    p.id = i;
    p.first_facet = offset;
    offset += p.facet_count;
    const double len = normal_sum[i].norm();
    if (len > 1e-12 * std::max(p.area, 1e-300)) p.normal = normal_sum[i] / len;
  }
  // Counting sort of the facets by patch.
  facet_order.resize(labels.size());
  std::vector<uint32_t> fill(count);
  for (uint32_t i = 0; i < count; ++i) fill[i] = patches[i].first_facet;
  for (size_t f = 0; f < labels.size(); ++f) facet_order[fill[labels[f]]++] = uint32_t(f);

  for (const LabelPair& pair : label_pairs(mesh, labels, edges)) {
    patches[pair.a].neighbours.push_back(pair.b);
    patches[pair.b].neighbours.push_back(pair.a);
  }
  for (Patch& p : patches) std::sort(p.neighbours.begin(), p.neighbours.end());

  const std::vector<HalfEdge> half = border_half_edges(mesh, labels, edges);
  std::vector<char> used(half.size(), 0);
  for (size_t i = 0; i < half.size();) {
    size_t j = i;
    while (j < half.size() && half[j].label == half[i].label) ++j;
    chain_loops(half.data() + i, half.data() + j, used, i, patches[half[i].label].loops);
    i = j;
  }
}

}  // namespace rosmill::segment::detail
