#include "rosmill/geometry/mesh.hpp"

#include <algorithm>
#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/geometry/vertex_welder.hpp"

namespace rosmill::core {
namespace {

// Integer cell coordinates of the tolerance weld.
struct VertexKey {
  uint64_t x, y, z;
  bool operator==(const VertexKey& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h ^= (k.y + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
    h ^= (k.z + 0x165667B19E3779F9ull) * 0x94D049BB133111EBull;
    return static_cast<size_t>(h ^ (h >> 31));
  }
};

// Tolerance weld on a grid of cells the size of the tolerance: a corner joins the first earlier vertex within
// the tolerance found in its own or a neighbouring cell.
void weld_tolerance(const std::vector<Vec3>& corners, double tol, IndexedTriangles& mesh) {
  std::unordered_map<VertexKey, std::vector<uint32_t>, VertexKeyHash> cells;
  auto cell_of = [tol](double v) { return static_cast<uint64_t>(static_cast<int64_t>(std::floor(v / tol))); };
  mesh.faces.resize(corners.size() / 3);
  const double tol2 = tol * tol;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec3& p = corners[i];
    const uint64_t cx = cell_of(p.x()), cy = cell_of(p.y()), cz = cell_of(p.z());
    uint32_t found = kNone;
    for (int dx = -1; dx <= 1 && found == kNone; ++dx)
      for (int dy = -1; dy <= 1 && found == kNone; ++dy)
        for (int dz = -1; dz <= 1 && found == kNone; ++dz) {
          auto it = cells.find({cx + dx, cy + dy, cz + dz});
          if (it == cells.end()) continue;
          for (uint32_t v : it->second)
            if ((mesh.vertices[v] - p).squaredNorm() <= tol2) {
              found = v;
              break;
            }
        }
    if (found == kNone) {
      found = static_cast<uint32_t>(mesh.vertices.size());
      mesh.vertices.push_back(p);
      cells[{cx, cy, cz}].push_back(found);
    }
    mesh.faces[i / 3][i % 3] = found;
  }
}

void face_geometry(Mesh& mesh, size_t f) {
  const Vec3 c = face_cross(mesh.vertices, mesh.faces[f]);
  const double len = c.norm();
  if (!(len > 0.0)) {
    mesh.normals[f].setZero();
    mesh.areas[f] = 0.0;
  } else {
    mesh.normals[f] = c / len;
    mesh.areas[f] = 0.5 * len;
  }
}

// Both cores from 20,000 faces on: a range no longer than its grain is not split, so smaller meshes stay on the
// calling thread (below that the threads' start costs more than they save). Pieces are taken on demand rather
// than one half per core, so the calling thread goes on while a sleeping worker wakes.
void compute_face_geometry(Mesh& mesh) {
  const size_t n = mesh.faces.size();
  mesh.normals.resize(n);
  mesh.areas.resize(n);
  for_each_piece(size_t(0), n, size_t(20000), [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; ++f) face_geometry(mesh, f);
  });
}

// Edges by a counting sort of the half-edges on their lower vertex, then on the higher one within each vertex's
// (short) list: O(n) with the locality of the vertex order, and the same order as sorting the keys (lo, hi, face).
// The half-edges are sorted in place in edge_faces (as face << 2 | corner) to keep the memory touched small.
namespace edges_detail {

inline uint32_t lower(const Mesh::Face& t, uint32_t c) { return std::min(t[c], t[(c + 1) % 3]); }
inline uint32_t higher(const Mesh::Face& t, uint32_t c) { return std::max(t[c], t[(c + 1) % 3]); }

// Sorts one vertex's half-edges by their higher vertex (stable: faces stay in order); returns its edge count.
uint32_t sort_vertex_list(const Mesh& mesh, uint32_t* first, uint32_t* last,
                          std::vector<std::pair<uint32_t, uint32_t>>& scratch) {
  const size_t k = size_t(last - first);
  scratch.resize(k);
  for (size_t i = 0; i < k; ++i) scratch[i] = {higher(mesh.faces[first[i] >> 2], first[i] & 3), first[i]};
  if (k <= 16) {
    for (size_t i = 1; i < k; ++i)  // insertion sort: most lists hold a handful
      for (size_t j = i; j > 0 && scratch[j].first < scratch[j - 1].first; --j) std::swap(scratch[j], scratch[j - 1]);
  } else {
    std::stable_sort(scratch.begin(), scratch.end(),
                     [](const auto& l, const auto& r) { return l.first < r.first; });
  }
  uint32_t edges = 0;
  for (size_t i = 0; i < k; ++i) {
    first[i] = scratch[i].second;
    edges += i == 0 || scratch[i].first != scratch[i - 1].first;
  }
  return edges;
}

}  // namespace edges_detail

void build_edges(Mesh& mesh) {
  using namespace edges_detail;
  const size_t n = mesh.faces.size(), nv = mesh.vertices.size();
  if (n >= (size_t(1) << 30)) throw Error("mesh", "more than 2^30 triangles");
  std::vector<uint32_t> start(nv + 1, 0);
  for (const Mesh::Face& t : mesh.faces)
    for (uint32_t c = 0; c < 3; ++c) ++start[lower(t, c) + 1];
  for (size_t v = 1; v <= nv; ++v) start[v] += start[v - 1];
  std::vector<uint32_t>& half = mesh.edge_faces;
  half.resize(3 * n);
  for (size_t f = 0; f < n; ++f)  // start[v] runs to the end of v's list, then moves back below
    for (uint32_t c = 0; c < 3; ++c) half[start[lower(mesh.faces[f], c)]++] = uint32_t(f << 2 | c);
  for (size_t v = nv; v > 0; --v) start[v] = start[v - 1];
  start[0] = 0;

  // Two passes over vertex ranges, both cores: sort each list and count its edges, then number and emit them.
  // Each chunk is one task, handed to whichever thread is free (a single chunk runs on the calling thread).
  const int chunks = n > 50000 ? 2 * 8 : 1;
  std::vector<uint32_t> chunk_edges(chunks + 1, 0);
  auto chunk_bound = [&](int k) { return nv * size_t(k) / size_t(chunks); };
  auto each_chunk = [chunks](const auto& work) { for_each_chunk(chunks, work); };
  each_chunk([&](int k) {
    std::vector<std::pair<uint32_t, uint32_t>> scratch;
    uint32_t count = 0;
    for (size_t v = chunk_bound(k); v < chunk_bound(k + 1); ++v)
      count += sort_vertex_list(mesh, half.data() + start[v], half.data() + start[v + 1], scratch);
    chunk_edges[k + 1] = count;
  });
  for (int k = 0; k < chunks; ++k) chunk_edges[k + 1] += chunk_edges[k];
  mesh.edges.resize(chunk_edges[chunks]);
  mesh.face_edges.resize(n);
  auto forward = [&](uint32_t fc) {  // the face runs the edge from its lower to its higher vertex
    const Mesh::Face& t = mesh.faces[fc >> 2];
    return t[fc & 3] < t[((fc & 3) + 1) % 3];
  };
  each_chunk([&](int k) {
    uint32_t id = chunk_edges[k];
    for (size_t v = chunk_bound(k); v < chunk_bound(k + 1); ++v) {
      const uint32_t end = start[v + 1];
      uint32_t i = start[v];
      uint32_t hi = i < end ? higher(mesh.faces[half[i] >> 2], half[i] & 3) : 0;
      while (i < end) {
        MeshEdge& e = mesh.edges[id];
        e.a = uint32_t(v);
        e.b = hi;
        e.first_face = i;
        const uint32_t fc0 = half[i], fc1 = i + 1 < end ? half[i + 1] : 0;
        uint32_t j = i;
        for (;;) {
          mesh.face_edges[half[j] >> 2][half[j] & 3] = id;
          half[j] >>= 2;  // now the face
          if (++j == end) break;
          const uint32_t next = higher(mesh.faces[half[j] >> 2], half[j] & 3);
          if (next != hi) {
            hi = next;
            break;
          }
        }
        e.face_count = j - i;
        e.consistent = e.face_count != 2 || forward(fc0) != forward(fc1);
        ++id;
        i = j;
      }
    }
  });
}

Mesh finish_mesh(Mesh mesh) {
  for (const Vec3& v : mesh.vertices) mesh.bbox.add(v);
  compute_face_geometry(mesh);
  build_edges(mesh);
  return mesh;
}

}  // namespace

bool Mesh::closed() const {
  if (faces.empty()) return false;
  for (const MeshEdge& e : edges)
    if (e.face_count != 2) return false;
  return true;
}

IndexedTriangles weld_corners(const std::vector<Vec3>& corners, const WeldOptions& options) {
  IndexedTriangles out;
  if (options.tolerance > 0.0) {
    weld_tolerance(corners, options.tolerance, out);
    return out;
  }
  static_assert(sizeof(Mesh::Face) == 3 * sizeof(uint32_t), "faces are three packed vertex ids");
  out.faces.resize(corners.size() / 3);
  DoubleWelder welder(corners.size() / 5 + 16);  // closed meshes have about one vertex per six corners
  constexpr size_t kBatch = 64;
  DoubleWelder::Key keys[kBatch];
  uint32_t* ids = out.faces.empty() ? nullptr : out.faces[0].data();
  const size_t n = 3 * out.faces.size();
  for (size_t start = 0; start < n; start += kBatch) {
    const size_t m = std::min(kBatch, n - start);
    for (size_t k = 0; k < m; ++k) keys[k] = weld_key(corners[start + k]);
    welder.add_many(keys, m, ids + start);
  }
  out.vertices.reserve(welder.size());
  for (size_t v = 0; v < welder.size(); ++v) out.vertices.push_back(key_position(welder.keys()[v]));
  return out;
}

Mesh build_mesh(const std::vector<Vec3>& corners, const WeldOptions& options) {
  return mesh_from_indexed(weld_corners(corners, options));
}

Mesh mesh_from_indexed(IndexedTriangles triangles) {
  for (const Mesh::Face& t : triangles.faces)
    for (uint32_t v : t)
      if (v >= triangles.vertices.size())
        throw Error("mesh", "a face uses vertex " + std::to_string(v) + " of " +
                                std::to_string(triangles.vertices.size()));
  Mesh mesh;
  mesh.vertices = std::move(triangles.vertices);
  mesh.faces = std::move(triangles.faces);
  return finish_mesh(std::move(mesh));
}

void check_has_area(const Mesh& mesh, const std::string& where) {
  if (mesh.faces.empty()) throw Error(where, "the mesh has no triangles");
  for (const double a : mesh.areas)
    if (a > 0) return;
  throw Error(where, "every one of the mesh's " + std::to_string(mesh.faces.size()) +
                         " triangles is degenerate (zero area): there is no surface");
}

Vec3 face_cross(const std::vector<Vec3>& vertices, const Mesh::Face& t) {
  if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return Vec3::Zero();
  return (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]);
}

}  // namespace rosmill::core
