#include "rosmill/geometry/placement.hpp"

#include "rosmill/error.hpp"

namespace rosmill::core {

bool Placement::identity(double tolerance) const { return pose.matrix().isIdentity(tolerance); }

Placement Placement::inverse() const { return {child, parent, pose.inverse(Eigen::Isometry)}; }

Placement compose(const Placement& outer, const Placement& inner, const std::string& where) {
  if (inner.parent != outer.child)
    throw Error(where, "cannot place frame '" + inner.child + "' in '" + outer.parent + "': it is given in '" +
                           inner.parent + "', the other placement starts from '" + outer.child + "'");
  return {outer.parent, inner.child, outer.pose * inner.pose};
}

Placement placement_of(const std::string& parent, const std::string& child, const Eigen::Quaterniond& rotation,
                       const Vec3& translation) {
  Placement p{parent, child, Eigen::Isometry3d::Identity()};
  p.pose.linear() = rotation.normalized().toRotationMatrix();
  p.pose.translation() = translation;
  return p;
}

void check_placement(const Placement& p, const std::string& where) {
  const Eigen::Matrix4d& m = p.pose.matrix();
  if (!m.allFinite()) throw Error(where, "the placement of '" + p.child + "' in '" + p.parent + "' is not finite");
  const Eigen::Matrix3d r = p.pose.linear();
  if (!(r.transpose() * r).isIdentity(1e-6) || r.determinant() < 0 || !m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1)))
    throw Error(where, "the placement of '" + p.child + "' in '" + p.parent +
                           "' must be rigid (a rotation and a translation, no scale, shear or mirror)");
}

Mesh placed(const Mesh& mesh, const Placement& placement) {
  IndexedTriangles t{mesh.vertices, mesh.faces};
  if (!placement.identity())
    for (Vec3& v : t.vertices) v = placement.point(v);
  return mesh_from_indexed(std::move(t));
}

PointCloud placed(const PointCloud& cloud, const Placement& placement) {
  PointCloud out;
  out.points.reserve(cloud.points.size());
  for (const Vec3& p : cloud.points) out.points.push_back(placement.point(p));
  out.recompute_bbox();
  return out;
}

Box3 placed(const Box3& box, const Placement& placement) {
  Box3 out;
  if (box.empty()) return out;
  for (int k = 0; k < 8; ++k)
    out.add(placement.point(Vec3(k & 1 ? box.max.x() : box.min.x(), k & 2 ? box.max.y() : box.min.y(),
                                 k & 4 ? box.max.z() : box.min.z())));
  return out;
}

}  // namespace rosmill::core
