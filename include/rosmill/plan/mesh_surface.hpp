// The Surface of a triangle mesh: exact drop-cutter (facets, edges, vertices; cutter/contact.hpp) with a
// bounding volume hierarchy over the triangles, searched branch-and-bound: a node is opened only when it lies
// under the cutter's footprint and its highest point could still raise the tip above the best contact so far.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/cutter/contact.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/plan/surface.hpp"

namespace rosmill::core {

class MeshSurface : public Surface {
 public:
  explicit MeshSurface(const Mesh& mesh);

  Box3 bounds() const override { return bounds_; }
  Drop drop(const Cutter& cutter, double x, double y) const override;
  // Parallel over both cores (TBB); consecutive points reuse the previous winner as the first bound.
  void drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const override;
  // Opens only the boxes that could hold the tip above z and stops at the first triangle that does.
  bool held_above(const Cutter& cutter, double x, double y, double z) const override;
  // Gathers at each focus the triangles that could hold the tip above z there; each question then tests those
  // only, the one that held last first.
  std::unique_ptr<LevelProbe> level_probe(const Cutter& cutter, double z) const override;

  size_t triangle_count() const { return tris_.size(); }

  // Drop with a hint: the index of a triangle likely to hold the contact (updated to the winner).
  Drop drop_hinted(const CutterProfile& cp, double x, double y, uint32_t& hint) const;
  bool held_above_hinted(const CutterProfile& cp, double x, double y, double z, uint32_t& hint) const;

 private:
  friend class MeshLevelProbe;
  struct Node {
    double xmin, ymin, xmax, ymax, zmax;
    uint32_t first;  // leaf: first triangle; inner: index of the right child (the left is the next node)
    uint32_t count;  // leaf: triangle count; inner: 0
  };
  struct FaceBox {
    double xmin, xmax, ymin, ymax, zmax;
  };
  double highest_contact(const CutterProfile& cp, double x, double y, double best, double enough,
                         uint32_t& hint) const;
  void build(uint32_t node, uint32_t begin, uint32_t end, const std::vector<FaceBox>& boxes,
             std::vector<uint32_t>& order);

  std::vector<ContactTriangle> tris_;  // in tree order
  std::vector<Node> nodes_;
  Box3 bounds_;
};

}  // namespace rosmill::core
