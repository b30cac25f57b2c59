#include "rosmill/slice/slicer.hpp"

#include <algorithm>
#include <cmath>

#include "contour_nesting.hpp"
#include "edge_links.hpp"
#include "rosmill/parallel.hpp"

namespace rosmill::core {
namespace {

using slice_detail::build_edge_links;

// The symbolic rule of one plane: which side a vertex exactly on the plane belongs to (see slicer.hpp).
struct PlaneRule {
  double h;
  bool from_above;  // the plane is at (or below) Zmin: section at h + eps, so a vertex on it counts as below
  bool above(double z) const { return from_above ? z > h : z >= h; }
};

// Faces grouped by the planes they cross (CSR): planes[j]'s faces are faces[offsets[j] .. offsets[j+1]).
struct PlaneBuckets {
  std::vector<size_t> offsets;
  std::vector<uint32_t> faces;
};

// The planes a face crosses form one run [first, last) of the sorted heights: zlo < h <= zhi, plus the planes at
// exactly Zmin for faces that rise from it (taken from above).
struct PlaneRun {
  uint32_t first, last;
};

PlaneRun plane_run(const Mesh& mesh, uint32_t f, const std::vector<double>& h, double mesh_zmin) {
  const auto& t = mesh.faces[f];
  const double z0 = mesh.vertices[t[0]].z(), z1 = mesh.vertices[t[1]].z(), z2 = mesh.vertices[t[2]].z();
  const double lo = std::min(z0, std::min(z1, z2)), hi = std::max(z0, std::max(z1, z2));
  if (!(lo < hi)) return {0, 0};
  auto first = std::upper_bound(h.begin(), h.end(), lo);
  if (lo == mesh_zmin) first = std::lower_bound(h.begin(), h.end(), lo);
  const auto last = std::upper_bound(first, h.end(), hi);
  return {uint32_t(first - h.begin()), uint32_t(last - h.begin())};
}

// Counting sort of the faces into the planes they cross: chunks of faces count, then fill their own slots, so
// the result is deterministic and both cores work.
PlaneBuckets bucket_faces(const Mesh& mesh, const std::vector<double>& h) {
  const size_t n = mesh.faces.size(), planes = h.size();
  const size_t chunks = std::max<size_t>(1, std::min<size_t>({16, n / 4096 + 1, (size_t(1) << 24) / (planes + 1)}));
  std::vector<size_t> counts(chunks * planes, 0);
  std::vector<PlaneRun> runs(n);
  const double zmin = mesh.bbox.min.z();
  for_each_index(size_t(0), chunks, [&](size_t c) {
    size_t* count = &counts[c * planes];
    for (size_t f = c * n / chunks, end = (c + 1) * n / chunks; f < end; ++f) {
      runs[f] = plane_run(mesh, uint32_t(f), h, zmin);
      for (uint32_t j = runs[f].first; j < runs[f].last; ++j) ++count[j];
    }
  });
  PlaneBuckets b;
  b.offsets.assign(planes + 1, 0);
  size_t total = 0;
  for (size_t j = 0; j < planes; ++j) {
    b.offsets[j] = total;
    for (size_t c = 0; c < chunks; ++c) {
      const size_t k = counts[c * planes + j];
      counts[c * planes + j] = total;  // becomes the chunk's write position in plane j
      total += k;
    }
  }
  b.offsets[planes] = total;
  b.faces.resize(total);
  for_each_index(size_t(0), chunks, [&](size_t c) {
    size_t* pos = &counts[c * planes];
    for (size_t f = c * n / chunks, end = (c + 1) * n / chunks; f < end; ++f)
      for (uint32_t j = runs[f].first; j < runs[f].last; ++j) b.faces[pos[j]++] = uint32_t(f);
  });
  return b;
}

// Area of the horizontal faces at each exact height, for the layers' flat regions.
struct FlatFaces {
  std::vector<double> z, cumulative_area;  // sorted by z; cumulative_area[i] = sum of areas of faces [0, i)

  double area_at(double h) const {
    const auto lo = std::lower_bound(z.begin(), z.end(), h), hi = std::upper_bound(lo, z.end(), h);
    return cumulative_area[size_t(hi - z.begin())] - cumulative_area[size_t(lo - z.begin())];
  }
};

FlatFaces flat_faces(const Mesh& mesh) {
  std::vector<std::pair<double, double>> flat;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const double z = mesh.corner(f, 0).z();
    if (mesh.areas[f] > 0.0 && mesh.corner(f, 1).z() == z && mesh.corner(f, 2).z() == z)
      flat.emplace_back(z, mesh.areas[f]);
  }
  std::sort(flat.begin(), flat.end());
  FlatFaces out;
  out.cumulative_area.push_back(0.0);
  for (const auto& [z, a] : flat) {
    out.z.push_back(z);
    out.cumulative_area.push_back(out.cumulative_area.back() + a);
  }
  return out;
}

// Walks the section of one plane through the faces that cross it.
class PlaneWalker {
 public:
  PlaneWalker(const Mesh& mesh, const std::vector<double>& vertex_z, const std::vector<uint32_t>& links,
              std::vector<uint32_t>& visited, uint32_t stamp, PlaneRule rule)
      : mesh_(mesh), z_(vertex_z), links_(links), visited_(visited), stamp_(stamp), rule_(rule) {}

  void run(const uint32_t* faces, size_t count, std::vector<Contour>& out) {
    for (size_t i = 0; i < count; ++i) {
      const uint32_t f = faces[i];
      if (visited_[f] == stamp_) continue;
      Contour c = chain_from(f);
      if (tidy(c)) out.push_back(std::move(c));
    }
  }

 private:
  const Mesh& mesh_;
  const std::vector<double>& z_;  // vertex heights alone: the side tests touch a third of the memory
  const std::vector<uint32_t>& links_;
  std::vector<uint32_t>& visited_;
  uint32_t stamp_;
  PlaneRule rule_;

  bool above(uint32_t v) const { return rule_.above(z_[v]); }

  // The crossing corner of face f other than `entry` (corner i crosses when its two ends are on both sides).
  uint32_t other_crossing(uint32_t f, uint32_t entry) const {
    const auto& t = mesh_.faces[f];
    const bool s[3] = {above(t[0]), above(t[1]), above(t[2])};
    for (uint32_t i = 0; i < 3; ++i)
      if (i != entry && s[i] != s[(i + 1) % 3]) return i;
    return entry;  // a face folded onto one edge crosses it twice
  }

  // Equation 2 of the STL slicing paper for a plane z = h: S = (h - zs) / (ze - zs) from the end below to the end
  // above.
  // A vertex on the plane is returned as is, so every chain through it meets there exactly.
  Vec2 crossing_point(uint32_t half_edge) const {
    const auto& t = mesh_.faces[half_edge / 3];
    uint32_t a = t[half_edge % 3], b = t[(half_edge % 3 + 1) % 3];
    if (above(a)) std::swap(a, b);
    const Vec3& lo = mesh_.vertices[a];
    const Vec3& hi = mesh_.vertices[b];
    if (lo.z() == rule_.h) return lo.head<2>();
    if (hi.z() == rule_.h) return hi.head<2>();
    const double s = (rule_.h - lo.z()) / (hi.z() - lo.z());
    return Vec2(lo.x() + s * (hi.x() - lo.x()), lo.y() + s * (hi.y() - lo.y()));
  }

  // Follows the chain leaving through `exit`, appending the crossing points; true when it came back to `start`.
  bool follow(uint32_t start, uint32_t exit, std::vector<Vec2>& pts) {
    for (;;) {
      pts.push_back(crossing_point(exit));
      const uint32_t next = links_[exit];
      if (next == kNone) return false;
      const uint32_t g = next / 3;
      if (g == start) {
        pts.pop_back();  // the chain's first point, already there
        return true;
      }
      if (visited_[g] == stamp_) return false;
      visited_[g] = stamp_;
      exit = 3 * g + other_crossing(g, next % 3);
    }
  }

  Contour chain_from(uint32_t f) {
    visited_[f] = stamp_;
    const auto& t = mesh_.faces[f];
    const bool s[3] = {above(t[0]), above(t[1]), above(t[2])};
    // Along the face's orientation the section runs from the edge going down to the edge going up: then a
    // consistently oriented solid's outline comes out counter-clockwise.
    uint32_t down = 0, up = 0;
    for (uint32_t i = 0; i < 3; ++i) {
      if (s[i] && !s[(i + 1) % 3]) down = i;
      if (!s[i] && s[(i + 1) % 3]) up = i;
    }
    Contour c;
    c.points.push_back(crossing_point(3 * f + down));
    c.closed = follow(f, 3 * f + up, c.points);
    if (!c.closed) {
      std::vector<Vec2> back;
      if (links_[3 * f + down] != kNone) {
        const uint32_t g = links_[3 * f + down] / 3;
        if (visited_[g] != stamp_) {
          visited_[g] = stamp_;
          follow(f, 3 * g + other_crossing(g, links_[3 * f + down] % 3), back);
        }
      }
      std::reverse(back.begin(), back.end());
      back.insert(back.end(), c.points.begin(), c.points.end());
      c.points.swap(back);
    }
    return c;
  }

  // Drops repeated points (a chain passing through a vertex on the plane meets it once per face); false when
  // nothing with extent is left (a section through an apex is a point).
  static bool tidy(Contour& c) {
    auto& p = c.points;
    p.erase(std::unique(p.begin(), p.end()), p.end());
    while (c.closed && p.size() > 1 && p.back() == p.front()) p.pop_back();
    return c.closed ? p.size() >= 3 : p.size() >= 2;
  }
};

}  // namespace

std::vector<SliceLayer> slice_mesh(const Mesh& mesh, const std::vector<double>& planes) {
  std::vector<SliceLayer> layers(planes.size());
  for (size_t j = 0; j < planes.size(); ++j) layers[j].z = planes[j];
  if (mesh.faces.empty() || planes.empty()) return layers;
  if (!std::is_sorted(planes.begin(), planes.end())) {
    // Slice in ascending order and put the layers back where the caller asked.
    std::vector<size_t> order(planes.size());
    for (size_t j = 0; j < order.size(); ++j) order[j] = j;
    std::sort(order.begin(), order.end(), [&](size_t l, size_t r) { return planes[l] < planes[r]; });
    std::vector<double> sorted(planes.size());
    for (size_t j = 0; j < order.size(); ++j) sorted[j] = planes[order[j]];
    std::vector<SliceLayer> done = slice_mesh(mesh, sorted);
    for (size_t j = 0; j < order.size(); ++j) layers[order[j]] = std::move(done[j]);
    return layers;
  }
  std::vector<double> vertex_z(mesh.vertices.size());
  for_each_index(size_t(0), vertex_z.size(), [&](size_t v) { vertex_z[v] = mesh.vertices[v].z(); });
  const PlaneBuckets buckets = bucket_faces(mesh, planes);
  const std::vector<uint32_t> links = build_edge_links(mesh);
  const FlatFaces flat = flat_faces(mesh);
  const double zmin = mesh.bbox.min.z();
  PerThread<std::vector<uint32_t>> visited_per_thread([&] { return std::vector<uint32_t>(mesh.faces.size(), 0); });
  for_each_piece<size_t>(0, planes.size(), 1, [&](size_t begin, size_t end) {
    std::vector<uint32_t>& visited = visited_per_thread.local();
    for (size_t j = begin; j < end; ++j) {
      SliceLayer& layer = layers[j];
      PlaneWalker walker(mesh, vertex_z, links, visited, uint32_t(j + 1), PlaneRule{planes[j], planes[j] <= zmin});
      walker.run(buckets.faces.data() + buckets.offsets[j], buckets.offsets[j + 1] - buckets.offsets[j],
                 layer.contours);
      slice_detail::orient_and_nest(layer.contours);
      layer.flat_area = flat.area_at(planes[j]);
    }
  });
  return layers;
}

}  // namespace rosmill::core
