#include "rosmill/geometry/mesh.hpp"

#include <algorithm>
#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <unordered_map>

namespace rosmill {
namespace {

// Bit pattern of a coordinate with -0 folded into +0, so that exact welding treats them as equal.
uint64_t coord_bits(double v) {
  if (v == 0.0) v = 0.0;
  uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}

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

// Exact weld: one vertex per distinct corner position.
void weld_exact(const std::vector<Vec3>& corners, Mesh& mesh) {
  std::unordered_map<VertexKey, uint32_t, VertexKeyHash> index;
  index.reserve(corners.size() / 2 + 16);
  mesh.faces.resize(corners.size() / 3);
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec3& p = corners[i];
    VertexKey key{coord_bits(p.x()), coord_bits(p.y()), coord_bits(p.z())};
    auto [it, inserted] = index.emplace(key, static_cast<uint32_t>(mesh.vertices.size()));
    if (inserted) mesh.vertices.push_back(p);
    mesh.faces[i / 3][i % 3] = it->second;
  }
}

// Tolerance weld on a grid of cells the size of the tolerance: a corner joins the first earlier vertex within
// the tolerance found in its own or a neighbouring cell.
void weld_tolerance(const std::vector<Vec3>& corners, double tol, Mesh& mesh) {
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

void compute_face_geometry(Mesh& mesh) {
  const size_t n = mesh.faces.size();
  mesh.normals.resize(n);
  mesh.areas.resize(n);
  for (size_t f = 0; f < n; ++f) {
    const auto& t = mesh.faces[f];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    const Vec3 c = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    const double len = c.norm();
    if (repeated || !(len > 0.0)) {
      mesh.normals[f].setZero();
      mesh.areas[f] = 0.0;
    } else {
      mesh.normals[f] = c / len;
      mesh.areas[f] = 0.5 * len;
    }
  }
}

// Edges from half-edges sorted by their undirected key; faces of an edge are grouped in edge_faces.
void build_edges(Mesh& mesh) {
  struct HalfEdge {
    uint64_t key;  // min << 32 | max
    uint32_t face;
    uint8_t corner;
    bool forward;  // runs from min to max
  };
  const size_t n = mesh.faces.size();
  std::vector<HalfEdge> half(3 * n);
  for (size_t f = 0; f < n; ++f)
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = mesh.faces[f][i], b = mesh.faces[f][(i + 1) % 3];
      const uint32_t lo = std::min(a, b), hi = std::max(a, b);
      half[3 * f + i] = {(uint64_t(lo) << 32) | hi, uint32_t(f), uint8_t(i), a < b};
    }
  std::sort(half.begin(), half.end(), [](const HalfEdge& l, const HalfEdge& r) {
    return l.key != r.key ? l.key < r.key : l.face < r.face;
  });
  mesh.face_edges.assign(n, {kNone, kNone, kNone});
  mesh.edges.clear();
  mesh.edge_faces.resize(half.size());
  for (size_t i = 0; i < half.size();) {
    size_t j = i;
    MeshEdge e;
    e.a = uint32_t(half[i].key >> 32);
    e.b = uint32_t(half[i].key & 0xffffffffu);
    e.first_face = uint32_t(i);
    const uint32_t id = uint32_t(mesh.edges.size());
    for (; j < half.size() && half[j].key == half[i].key; ++j) {
      mesh.edge_faces[j] = half[j].face;
      mesh.face_edges[half[j].face][half[j].corner] = id;
    }
    e.face_count = uint32_t(j - i);
    e.consistent = e.face_count != 2 || half[i].forward != half[i + 1].forward;
    mesh.edges.push_back(e);
    i = j;
  }
}

}  // namespace

uint32_t Mesh::neighbour(size_t f, int i) const {
  const MeshEdge& e = edges[face_edges[f][i]];
  if (e.face_count != 2) return kNone;
  const uint32_t f0 = edge_faces[e.first_face], f1 = edge_faces[e.first_face + 1];
  return f0 == f ? f1 : f0;
}

bool Mesh::closed() const {
  if (faces.empty()) return false;
  for (const MeshEdge& e : edges)
    if (e.face_count != 2) return false;
  return true;
}

Mesh build_mesh(const std::vector<Vec3>& corners, const WeldOptions& options) {
  Mesh mesh;
  if (options.tolerance > 0.0)
    weld_tolerance(corners, options.tolerance, mesh);
  else
    weld_exact(corners, mesh);
  for (const Vec3& v : mesh.vertices) mesh.bbox.add(v);
  compute_face_geometry(mesh);
  build_edges(mesh);
  return mesh;
}

void scale_mesh(Mesh& mesh, double factor) {
  if (factor == 1.0) return;
  mesh.bbox = Box3{};
  for (Vec3& v : mesh.vertices) {
    v *= factor;
    mesh.bbox.add(v);
  }
  for (double& a : mesh.areas) a *= factor * factor;
}

}  // namespace rosmill
