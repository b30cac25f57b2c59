// Patch records from a label per facet: facets grouped by patch (a counting sort), area, area-weighted mean
// normal, neighbouring patches and the boundary loops. Only the edges that may separate patches are visited
// for neighbours and loops, so the cost is one pass over the facets plus the patch borders.
#include <algorithm>

#include "labelling.hpp"
#include "rosmill/parallel.hpp"

namespace rosmill::core::segment::detail {
namespace {

// The corner of face f whose edge (corner -> next corner) is e.
int corner_of_edge(const Mesh& mesh, uint32_t f, uint32_t e) {
  for (int i = 0; i < 3; ++i)
    if (mesh.face_edges[f][i] == e) return i;
  return 0;
}

// Directed edges, in each facet's winding, that lie on the border of the facet's patch, grouped by patch (a
// counting sort; within a patch in the order of `edges`). group_start[l] is where patch l's half-edges begin.
std::vector<HalfEdge> border_half_edges(const Mesh& mesh, const std::vector<uint32_t>& labels, uint32_t count,
                                        const std::vector<uint32_t>& edges, std::vector<uint32_t>& group_start) {
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
  group_start.assign(count + 1, 0);
  for (const HalfEdge& h : half) ++group_start[h.label + 1];
  for (uint32_t l = 0; l < count; ++l) group_start[l + 1] += group_start[l];
  std::vector<HalfEdge> grouped(half.size());
  std::vector<uint32_t> fill(group_start.begin(), group_start.end() - 1);
  for (const HalfEdge& h : half) grouped[fill[h.label]++] = h;
  return grouped;
}

}  // namespace

// Each closed loop starts at its smallest vertex and the loops are listed by their first vertex, so the output
// does not depend on the order of the half-edges (phase 2 lists them in another order than phase 1).
void chain_loops(const HalfEdge* begin, const HalfEdge* end, std::vector<uint32_t>& head, std::vector<uint32_t>& link,
                 std::vector<BoundaryLoop>& loops) {
  const uint32_t n = uint32_t(end - begin);
  const size_t first_loop = loops.size();
  link.assign(n, kNone);
  for (uint32_t i = n; i-- > 0;) {  // lists in half-edge order
    link[i] = head[begin[i].from];
    head[begin[i].from] = i;
  }
  auto take_from = [&](uint32_t v) -> uint32_t {  // the first unused half-edge leaving v
    const uint32_t i = head[v];
    if (i != kNone) head[v] = link[i];
    return i;
  };
  for (uint32_t s = 0; s < n; ++s) {
    // Unused when still listed at its vertex (used ones are unlinked from the front of their list).
    uint32_t first = kNone;
    for (uint32_t i = head[begin[s].from]; i != kNone; i = link[i])
      if (i == s) first = s;
    if (first == kNone) continue;
    // Unlink s (it may not be at the front when its vertex has several outgoing half-edges).
    if (head[begin[s].from] == s) {
      head[begin[s].from] = link[s];
    } else {
      for (uint32_t i = head[begin[s].from]; i != kNone; i = link[i])
        if (link[i] == s) link[i] = link[s];
    }
    BoundaryLoop loop;
    loop.mesh_border = true;
    const HalfEdge* h = begin + s;
    // Gathered in a buffer of the thread's, so that each loop allocates once (both cores describe patches).
    thread_local std::vector<uint32_t> chain;
    chain.clear();
    for (;;) {
      chain.push_back(h->from);
      loop.mesh_border = loop.mesh_border && h->open;
      if (h->to == begin[s].from) break;
      const uint32_t next = take_from(h->to);
      if (next == kNone) {  // broken orientation or a non-manifold vertex: report the chain open
        chain.push_back(h->to);
        loop.closed = false;
        break;
      }
      h = begin + next;
    }
    loop.vertices.assign(chain.begin(), chain.end());
    if (loop.closed) {
      std::rotate(loop.vertices.begin(), std::min_element(loop.vertices.begin(), loop.vertices.end()),
                  loop.vertices.end());
    }
    loops.push_back(std::move(loop));
  }
  for (const HalfEdge* h = begin; h != end; ++h) head[h->from] = kNone;
  // By vertices (first vertex first): a total order, as no two loops run the same half-edges.
  if (loops.size() - first_loop > 1)
    std::sort(loops.begin() + first_loop, loops.end(),
              [](const BoundaryLoop& a, const BoundaryLoop& b) { return a.vertices < b.vertices; });
}

void describe_patches(const Mesh& mesh, const std::vector<uint32_t>& labels, uint32_t count,
                      const std::vector<uint32_t>& edges, const std::vector<LabelPair>& pairs,
                      std::vector<Patch>& patches, std::vector<uint32_t>& facet_order) {
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
    p.normal = mean_normal(normal_sum[i], p.area);
  }
  // Counting sort of the facets by patch.
  facet_order.resize(labels.size());
  std::vector<uint32_t> fill(count);
  for (uint32_t i = 0; i < count; ++i) fill[i] = patches[i].first_facet;
  for (size_t f = 0; f < labels.size(); ++f) facet_order[fill[labels[f]]++] = uint32_t(f);

  for (const LabelPair& pair : pairs) {
    patches[pair.a].neighbours.push_back(pair.b);
    patches[pair.b].neighbours.push_back(pair.a);
  }
  for (Patch& p : patches) std::sort(p.neighbours.begin(), p.neighbours.end());

  // Each patch's loops on its own: both cores when the borders are long and the patches many enough to share out
  // (each thread lists vertices in a head array of its own, one entry per mesh vertex).
  std::vector<uint32_t> group_start;
  const std::vector<HalfEdge> half = border_half_edges(mesh, labels, count, edges, group_start);
  struct Scratch {
    std::vector<uint32_t> head, link;
  };
  auto fresh = [&] { return Scratch{std::vector<uint32_t>(mesh.vertex_count(), kNone), {}}; };
  auto loops_of = [&](uint32_t l, Scratch& s) {
    chain_loops(half.data() + group_start[l], half.data() + group_start[l + 1], s.head, s.link, patches[l].loops);
  };
  if (half.size() > 20000 && count >= 16) {  // one patch at a time to whichever core is free
    PerThread<Scratch> scratch(fresh);
    for_each_chunk(count, [&](uint32_t l) { loops_of(l, scratch.local()); });
  } else {
    Scratch scratch = fresh();
    for (uint32_t l = 0; l < count; ++l) loops_of(l, scratch);
  }
}

}  // namespace rosmill::core::segment::detail
