// Rays against a triangle mesh: the first facet a ray meets, through a bounding volume hierarchy over the facets
// (boxes split at the median of their centroids along their longest side, eight facets or fewer a leaf), each facet
// tested by Woop, Benthin and Wald's watertight ray/triangle intersection (2013): a ray through a shared edge or
// corner of a closed mesh does not slip between its facets. What the account of the
// material left on a part needs: how far a line off a face runs before it meets the part again; and a ball swept
// along a tilted tool's axis, where five-axis finishing puts its cutter locations.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core {

class MeshRays {
 public:
  explicit MeshRays(const Mesh& mesh);

  // The least t in (t_min, t_max] at which origin + t * direction lies on a facet, +infinity when there is none.
  // `direction` need not be unit (t is then in its units); `face`, when given, receives the facet met. Thread-safe:
  // the hierarchy is read only.
  double first_hit(const Vec3& origin, const Vec3& direction, double t_min, double t_max,
                   uint32_t* face = nullptr) const;
  // The least t in [t_min, t_max] at which a sphere of `radius` centred at origin + t * direction touches a facet
  // (geometry/sphere_sweep.hpp); t_min when it already does there, +infinity when it never does. `direction` unit.
  double first_sphere_contact(const Vec3& origin, const Vec3& direction, double radius, double t_min,
                              double t_max) const;

 private:
  struct Node {
    double lo[3], hi[3];
    uint32_t first = 0;  // a leaf's first facet in order_, or an inner node's right child (the left is next)
    uint32_t count = 0;  // facets of a leaf; 0 for an inner node
  };
  uint32_t build(uint32_t begin, uint32_t end, const std::vector<Vec3>& centroids);
  template <class Leaf>
  double walk(const Vec3& o, const Vec3& d, double grow, double t_min, double t_max, Leaf&& leaf) const;

  const Mesh& mesh_;
  std::vector<Node> nodes_;
  std::vector<uint32_t> order_;
};

}  // namespace rosmill::core
