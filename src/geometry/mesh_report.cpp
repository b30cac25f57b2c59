#include "rosmill/geometry/mesh_report.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"

namespace rosmill::core {
namespace {

// Divergence theorem: sum of signed tetrahedra against the bbox centre (centring keeps the sum accurate).
double signed_volume(const std::vector<Vec3>& vertices, const std::vector<Mesh::Face>& faces, const Box3& bbox) {
  const Vec3 c = bbox.empty() ? Vec3::Zero() : Vec3(0.5 * (bbox.min + bbox.max));
  double six_v = 0.0;
  for (const auto& t : faces) {
    const Vec3 a = vertices[t[0]] - c, b = vertices[t[1]] - c, d = vertices[t[2]] - c;
    six_v += a.dot(b.cross(d));
  }
  return six_v / 6.0;
}

// Box, area, degenerate faces and volume: one pass over the faces, summed in face order as report(Mesh) sums the
// Mesh's areas, so that both give the same bits. A face's area is Mesh's (half its corners' cross product, zero
// when two corners share a vertex).
void add_surface(const IndexedTriangles& m, MeshReport& r) {
  for (const Vec3& v : m.vertices) r.bbox.add(v);
  for (const Mesh::Face& t : m.faces) {
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    const Vec3& p = m.vertices[t[0]];
    const double len = (m.vertices[t[1]] - p).cross(m.vertices[t[2]] - p).norm();
    const double area = repeated || !(len > 0.0) ? 0.0 : 0.5 * len;
    r.area += area;
    if (area == 0.0) ++r.degenerate;
  }
  r.volume = signed_volume(m.vertices, m.faces, r.bbox);
}

// From this many faces on, the report's passes run on both cores.
constexpr size_t kParallelFaces = 50000;

struct EdgeCounts {
  size_t open = 0, nonmanifold = 0, inconsistent = 0;
};

void compare_exchange(uint32_t& a, uint32_t& b) {
  const uint32_t lo = std::min(a, b), hi = std::max(a, b);
  a = lo, b = hi;
}

// Sorts eight values by the 19-comparator network for eight inputs (Knuth, The Art of Computer Programming,
// vol. 3, 5.3.4): no branch on the data. Most vertices' lists hold about six half-edges in no order a branch
// predictor can learn, so an insertion sort mispredicts at every other step.
void sort8(uint32_t* v) {
  compare_exchange(v[0], v[2]), compare_exchange(v[1], v[3]), compare_exchange(v[4], v[6]);
  compare_exchange(v[5], v[7]);
  compare_exchange(v[0], v[4]), compare_exchange(v[1], v[5]), compare_exchange(v[2], v[6]);
  compare_exchange(v[3], v[7]);
  compare_exchange(v[0], v[1]), compare_exchange(v[2], v[3]), compare_exchange(v[4], v[5]);
  compare_exchange(v[6], v[7]);
  compare_exchange(v[2], v[4]), compare_exchange(v[3], v[5]);
  compare_exchange(v[1], v[4]), compare_exchange(v[3], v[6]);
  compare_exchange(v[1], v[2]), compare_exchange(v[3], v[4]), compare_exchange(v[5], v[6]);
}

// The edges of one vertex's sorted list of half-edges.
void count_sorted(const uint32_t* first, const uint32_t* last, EdgeCounts& n) {
  for (const uint32_t* i = first; i < last;) {
    const uint32_t* j = i + 1;
    while (j < last && (*j >> 1) == (*i >> 1)) ++j;
    if (j - i == 1) ++n.open;
    if (j - i > 2) ++n.nonmanifold;
    if (j - i == 2 && i[0] == i[1]) ++n.inconsistent;
    i = j;
  }
}

// Edges from the half-edges grouped on their lower vertex by a counting sort (the grouping Mesh's edges are built
// with), each stored as its higher vertex << 1 | direction (1: run from lower to higher). Within a vertex's short
// list, sorting brings an edge's half-edges together: one of them is an open edge, more than two a non-manifold
// one, and two with the same direction bit an inconsistently oriented one. Needs vertices < 2^31.
//
// The vertices [first, last) only: the half-edges of their edges alone are held, so a large mesh is counted in
// slices (count_edges) in the memory of one slice, which the next reuses; fresh pages are dear (heap_reuse.hpp).
void count_edge_slice(const std::vector<Mesh::Face>& faces, uint32_t first, uint32_t last, EdgeCounts& counts) {
  const size_t nv = last - first;
  std::vector<uint32_t> end(nv + 1, 0);  // after the scatter: end[v - first] is where v's list begins
  const auto each_half = [&](const auto& f) {
    for (const Mesh::Face& t : faces)
      for (int c = 0; c < 3; ++c) {
        const uint32_t from = t[c], to = t[(c + 1) % 3], lo = std::min(from, to);
        if (lo >= first && lo < last) f(lo - first, std::max(from, to) << 1 | uint32_t(from < to));
      }
  };
  each_half([&](uint32_t v, uint32_t) { ++end[v]; });
  for (size_t v = 1; v <= nv; ++v) end[v] += end[v - 1];
  std::vector<uint32_t> half(end[nv]);
  each_half([&](uint32_t v, uint32_t h) { half[--end[v]] = h; });
  // Vertex ranges on both cores (from kParallelFaces on), each chunk one task; the counts are integers, so their
  // sum does not depend on the order the chunks end in.
  const int chunks = faces.size() > kParallelFaces ? 16 : 1;
  std::atomic<size_t> open{0}, nonmanifold{0}, inconsistent{0};
  const auto count_chunk = [&](int k) {
    EdgeCounts n;
    for (size_t v = nv * size_t(k) / size_t(chunks); v < nv * size_t(k + 1) / size_t(chunks); ++v) {
      uint32_t* begin = half.data() + end[v];
      uint32_t* stop = half.data() + end[v + 1];
      const size_t size = size_t(stop - begin);
      if (size <= 8) {
        // Padded with values no half-edge has (vertices < 2^31), which sort last.
        uint32_t list[8] = {~0u, ~0u, ~0u, ~0u, ~0u, ~0u, ~0u, ~0u};
        std::copy(begin, stop, list);
        sort8(list);
        count_sorted(list, list + size, n);
      } else {
        std::sort(begin, stop);
        count_sorted(begin, stop, n);
      }
    }
    open += n.open;
    nonmanifold += n.nonmanifold;
    inconsistent += n.inconsistent;
  };
  for_each_chunk(chunks, count_chunk);
  counts.open += open, counts.nonmanifold += nonmanifold, counts.inconsistent += inconsistent;
}

// A large mesh in kEdgeSlices slices of its vertices (about as many half-edges each: a welded file numbers its
// vertices in the order the faces meet them).
constexpr int kEdgeSlices = 2;

EdgeCounts count_edges(const std::vector<Mesh::Face>& faces, size_t nv) {
  EdgeCounts counts;
  const int slices = faces.size() > kParallelFaces ? kEdgeSlices : 1;
  for (int k = 0; k < slices; ++k)
    count_edge_slice(faces, uint32_t(nv * size_t(k) / size_t(slices)), uint32_t(nv * size_t(k + 1) / size_t(slices)),
                     counts);
  return counts;
}

}  // namespace

MeshReport report(const Mesh& mesh) {
  MeshReport r;
  r.triangles = mesh.faces.size();
  r.vertices = mesh.vertices.size();
  r.bbox = mesh.bbox;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    r.area += mesh.areas[f];
    if (mesh.areas[f] == 0.0) ++r.degenerate;
  }
  for (const MeshEdge& e : mesh.edges) {
    if (e.boundary()) ++r.open_edges;
    if (e.nonmanifold()) ++r.nonmanifold_edges;
    if (e.manifold() && !e.consistent) ++r.inconsistent_edges;
  }
  r.closed = mesh.closed();
  r.volume = signed_volume(mesh.vertices, mesh.faces, r.bbox);
  return r;
}

MeshReport report(const IndexedTriangles& triangles) {
  const size_t nv = triangles.vertices.size();
  // The half-edge values keep a direction bit beside the vertex: beyond 2^31 vertices, the full Mesh.
  if (nv >= (size_t(1) << 31)) return report(mesh_from_indexed(triangles));
  if (triangles.faces.size() >= (size_t(1) << 30)) throw Error("mesh", "more than 2^30 triangles");
  uint32_t highest = 0;  // a vectorized scan; the first bad face is looked for only when there is one
  for (const Mesh::Face& t : triangles.faces) highest = std::max({highest, t[0], t[1], t[2]});
  if (!triangles.faces.empty() && highest >= nv)
    for (const Mesh::Face& t : triangles.faces)
      for (uint32_t v : t)
        if (v >= nv) throw Error("mesh", "a face uses vertex " + std::to_string(v) + " of " + std::to_string(nv));
  MeshReport r;
  r.triangles = triangles.faces.size();
  r.vertices = nv;
  EdgeCounts edges;
  // The surface pass (floating point) beside the edge pass (integers): one core each. A small mesh stays on this
  // thread: starting the thread pool (its libraries, a worker) costs more than the passes, and is most of the
  // start-up of `rosmill info` on a small file.
  const auto surface = [&] { add_surface(triangles, r); };
  const auto edge_pass = [&] { edges = count_edges(triangles.faces, nv); };
  if (triangles.faces.size() > kParallelFaces) {
    run_both(surface, edge_pass);
  } else {
    surface();
    edge_pass();
  }
  r.open_edges = edges.open;
  r.nonmanifold_edges = edges.nonmanifold;
  r.inconsistent_edges = edges.inconsistent;
  r.closed = !triangles.faces.empty() && edges.open == 0 && edges.nonmanifold == 0;
  return r;
}

}  // namespace rosmill::core
