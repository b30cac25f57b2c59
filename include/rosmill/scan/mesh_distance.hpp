// Exact distance from points to a mesh's surface, signed by the nearest face's outward normal (positive outside:
// material above the design; negative: below it).
//
// Index: a k-d tree (nanoflann) over points covering every face, each within `cover` of any point of its face
// (one centroid for a small face, the centroids of its pieces for a large one). A face at distance d has an index
// point within d + cover, so the faces of the index points within (best exact distance so far) + cover hold the
// nearest surface point; their exact point-triangle distances decide, and the search narrows as it finds nearer
// faces.
#pragma once
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core::scan {

struct SurfaceDistance {
  double signed_distance = 0;  // mm, + outside (along the face normal), - inside
  Vec3 closest = Vec3::Zero();  // the nearest surface point
  uint32_t face = 0;
};

class MeshDistance {
 public:
  // Keeps a reference to `mesh`: it must outlive this. Throws Error when the mesh has no area.
  explicit MeshDistance(const Mesh& mesh);
  ~MeshDistance();
  MeshDistance(const MeshDistance&) = delete;
  MeshDistance& operator=(const MeshDistance&) = delete;

  SurfaceDistance query(const Vec3& p) const;
  // The nearest surface point when it lies within `limit` mm (true, into `out`); false, and quickly, when none does.
  bool query_within(const Vec3& p, double limit, SurfaceDistance& out) const;
  // The unsigned distances of many points (threads of TBB); those farther than `limit` come back as infinity
  // without their exact distance being sought.
  std::vector<double> distances(const std::vector<Vec3>& points,
                                double limit = std::numeric_limits<double>::infinity()) const;
  double cover() const { return cover_; }

 private:
  struct Index;
  struct NearestFace;
  const Mesh& mesh_;
  double cover_ = 0;
  std::unique_ptr<Index> index_;
};

// The closest point of triangle (a, b, c) to p.
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace rosmill::core::scan
