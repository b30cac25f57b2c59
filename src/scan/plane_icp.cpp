#include "rosmill/scan/plane_icp.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "rosmill/error.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/scan/point_index.hpp"

namespace rosmill::core::scan {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

// The point-to-plane normal equations of one step, linearised about the current pose (Low, "Linear least-squares
// optimization for point-to-plane ICP surface registration", 2004): a small turn w and shift t move q by
// w x q + t, so the residual n . (q - f) changes by (q x n) . w + n . t.
struct NormalEquations {
  Matrix6 a = Matrix6::Zero();
  Vector6 b = Vector6::Zero();
  size_t pairs = 0;
  void join(const NormalEquations& o) {
    a += o.a;
    b += o.b;
    pairs += o.pairs;
  }
};

// The step that solves the equations in the directions the pairs fix, within the span of `basis` (columns in the
// step's unknowns); a direction they leave free (a plane's slide, a cylinder's turn) is not moved rather than
// thrown to infinity by a near-zero pivot.
Vector6 solve(const NormalEquations& e, const Eigen::MatrixXd& basis) {
  const Matrix6 a = e.a.selfadjointView<Eigen::Lower>();  // the sums fill the lower triangle
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(basis.transpose() * a * basis, Eigen::ComputeEigenvectors);
  const Eigen::Index n = basis.cols();
  const double largest = es.eigenvalues()[n - 1];
  Eigen::VectorXd projected = es.eigenvectors().transpose() * (basis.transpose() * -e.b);
  for (Eigen::Index i = 0; i < n; ++i)
    projected[i] = es.eigenvalues()[i] > 1e-12 * largest ? projected[i] / es.eigenvalues()[i] : 0.0;
  return basis * (es.eigenvectors() * projected);
}

// The allowed motions as the step's unknowns (turns about the fixed surface's centroid `origin`): a turn w about c
// with slide t is the turn w about the origin with slide t + w x (origin - c).
Eigen::MatrixXd step_basis(const IcpMotions* allowed, const Vec3& origin) {
  if (!allowed) return Eigen::MatrixXd::Identity(6, 6);
  Eigen::MatrixXd basis = allowed->motions;
  for (Eigen::Index k = 0; k < basis.cols(); ++k) {
    const Vec3 w = basis.col(k).head<3>();
    basis.col(k).tail<3>() += w.cross(origin - allowed->centre);
  }
  return basis;
}

bool settled(const Eigen::Matrix4d& step) {
  return translation_length(step) < 1e-6 && rotation_angle_deg(step) < 1e-6 * 180 / M_PI;
}

}  // namespace

// Both point sets are handled relative to the fixed surface's centroid, where the linearised rotation is best
// conditioned.
struct PlaneIcp::Impl {
  Vec3 origin = Vec3::Zero();
  std::vector<Vec3> normals;
  std::vector<char> creases;
  std::unique_ptr<PointIndex> index;
};

PlaneIcp::PlaneIcp(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, std::vector<char> creases)
    : impl_(std::make_unique<Impl>()) {
  if (points.empty()) throw Error("point-to-plane ICP", "the fixed surface has no point");
  if (points.size() != normals.size()) throw Error("point-to-plane ICP", "one normal per point is needed");
  if (!creases.empty() && creases.size() != points.size())
    throw Error("point-to-plane ICP", "one crease flag per point (or none) is needed");
  impl_->creases = std::move(creases);
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : points) sum += p;
  impl_->origin = sum / double(points.size());
  std::vector<Vec3> centred;
  centred.reserve(points.size());
  for (const Vec3& p : points) centred.push_back(p - impl_->origin);
  impl_->index = std::make_unique<PointIndex>(std::move(centred));
  impl_->normals = normals;
}

PlaneIcp::~PlaneIcp() = default;

Eigen::Matrix4d PlaneIcp::align(const std::vector<Vec3>& moving, const Eigen::Matrix4d& start, double max_distance,
                                int iterations, IcpOutcome* outcome, const IcpMotions* allowed) const {
  if (moving.size() < 6) throw Error("point-to-plane ICP", "at least 6 moving points are needed");
  if (allowed && (allowed->motions.cols() == 0 || !allowed->motions.allFinite() || !allowed->centre.allFinite()))
    throw Error("point-to-plane ICP", "the allowed motions must be at least one finite column");
  const Eigen::MatrixXd basis = step_basis(allowed, impl_->origin);
  Eigen::Matrix4d shift = Eigen::Matrix4d::Identity();
  shift.topRightCorner<3, 1>() = -impl_->origin;
  Eigen::Matrix4d pose = shift * start;
  const PointIndex& index = *impl_->index;
  const std::vector<Vec3>& fixed = index.points();
  const std::vector<Vec3>& normals = impl_->normals;
  IcpOutcome done;
  std::vector<size_t> paired(moving.size(), PointIndex::no_hint);  // each point's pair at the last step
  std::array<Eigen::Matrix4d, 4> recent;  // the poses before the last steps (in a ring)
  recent.fill(Eigen::Matrix4d::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (; done.steps < iterations && !done.converged; ++done.steps) {
    const Eigen::Matrix3d r = pose.topLeftCorner<3, 3>();
    const Vec3 t = pose.topRightCorner<3, 1>();
    // A deterministic reduction: the same sums in the same order whatever the number of threads.
    const NormalEquations e = reduce_pieces_deterministic(
        size_t(0), moving.size(), size_t(512), NormalEquations(),
        [&](size_t begin, size_t end, NormalEquations sum) {
          for (size_t i = begin; i != end; ++i) {
            const Vec3 q = r * moving[i] + t;
            size_t j;
            double sq;
            if (!index.nearest(q, max_distance, paired[i], j, sq)) continue;
            paired[i] = j;
            const Vec3& n = normals[j];
            Vector6 row;
            row << q.cross(n), n;
            sum.a.selfadjointView<Eigen::Lower>().rankUpdate(row);
            sum.b += row * n.dot(q - fixed[j]);
            ++sum.pairs;
          }
          return sum;
        },
        [](NormalEquations x, const NormalEquations& y) {
          x.join(y);
          return x;
        });
    done.pairs = e.pairs;
    if (e.pairs < 6) break;  // too few pairs to fix a pose: keep the last one
    const Vector6 x = solve(e, basis);
    const double angle = x.head<3>().norm();
    Eigen::Matrix4d increment = Eigen::Matrix4d::Identity();
    if (angle > 0) increment.topLeftCorner<3, 3>() = Eigen::AngleAxisd(angle, x.head<3>() / angle).toRotationMatrix();
    increment.topRightCorner<3, 1>() = x.tail<3>();
    recent[size_t(done.steps) % recent.size()] = pose;
    pose = increment * pose;
    // Converged when the step is below 1e-6 mm and 1e-6 rad, or when it returns to a pose of the last few steps:
    // the pairs then cycle between sets that fit equally well (each step a few 1e-4 mm), and more steps only
    // go round the cycle.
    done.converged = settled(increment) || std::any_of(recent.begin(), recent.end(), [&](const Eigen::Matrix4d& p) {
                       return settled(pose * rigid_inverse(p));  // false for the ring's NaN fill
                     });
  }
  if (outcome) *outcome = done;
  Eigen::Matrix4d unshift = Eigen::Matrix4d::Identity();
  unshift.topRightCorner<3, 1>() = impl_->origin;
  return unshift * pose;
}

std::vector<PlanePair> PlaneIcp::pairs(const std::vector<Vec3>& moving, const std::vector<Vec3>& moving_normals,
                                       const Eigen::Matrix4d& pose, double max_distance, double outline_degrees) const {
  if (moving.size() != moving_normals.size()) throw Error("point-to-plane ICP", "one normal per moving point is needed");
  const Eigen::Matrix3d r = pose.topLeftCorner<3, 3>();
  const Vec3 t = pose.topRightCorner<3, 1>() - impl_->origin;
  std::vector<PlanePair> out(moving.size());
  std::vector<char> found(moving.size(), 0);
  std::vector<size_t> pair_of(moving.size(), 0);
  for_each_piece<size_t>(0, moving.size(), 512, [&](size_t begin, size_t end) {
    for (size_t i = begin; i != end; ++i) {
      const Vec3 q = r * moving[i] + t;
      size_t j;
      double sq;
      if (!impl_->index->nearest(q, max_distance, j, sq)) continue;
      PlanePair& p = out[i];
      p.point = q + impl_->origin;
      p.normal = impl_->normals[j];
      p.residual = p.normal.dot(q - impl_->index->points()[j]);
      const Vec3 own = r * moving_normals[i];
      p.outline = normals_disagree(own, p.normal, outline_degrees);
      // The point's normal turned to agree with its pair's; the offset from the sample along its plane. On a
      // convex surface (outward normals) the normal turns towards the offset and the point lies below the plane.
      const Vec3 offset = q - impl_->index->points()[j] - p.residual * p.normal;
      p.bend = -0.5 * (own.dot(p.normal) < 0 ? -own : own).dot(offset);
      if (!impl_->creases.empty() && impl_->creases[j]) p.outline = p.crease = true;  // and stays one: see below
      pair_of[i] = j;
      found[i] = 1;
    }
  });
  // At a sharp edge whose two faces the moving points both show, a point near it may pair with the other face's
  // sample: that is no outline (the other face is seen, its own points pair with it too). An outline pair's face
  // has no moving point of its own within the reach.
  std::vector<Vec3> moved(moving.size());
  for (size_t i = 0; i < moving.size(); ++i) moved[i] = r * moving[i] + t + impl_->origin;
  const PointIndex seen(moved);
  for_each_piece<size_t>(0, moving.size(), 512, [&](size_t begin, size_t end) {
    constexpr size_t kLook = 16;
    size_t near[kLook];
    double sq[kLook];
    for (size_t i = begin; i != end; ++i) {
      PlanePair& p = out[i];
      if (!found[i] || !p.outline || (!impl_->creases.empty() && impl_->creases[pair_of[i]])) continue;
      const Vec3 on_face = p.point - p.residual * p.normal;  // the point's foot on its pair's tangent plane
      const size_t n = seen.nearest_k(on_face, kLook, near, sq);
      for (size_t k = 0; k < n && sq[k] < max_distance * max_distance && p.outline; ++k)
        p.outline = normals_disagree(r * moving_normals[near[k]], p.normal, outline_degrees);
    }
  });
  std::vector<PlanePair> kept;
  kept.reserve(out.size());
  for (size_t i = 0; i < out.size(); ++i)
    if (found[i]) kept.push_back(out[i]);
  return kept;
}

double PlaneIcp::spacing() const {
  const std::vector<Vec3>& points = impl_->index->points();
  if (points.size() < 2) return 0;
  // A thousand points tell the median.
  const size_t stride = std::max<size_t>(1, points.size() / 1000);
  std::vector<double> nearest;
  for (size_t i = 0; i < points.size(); i += stride) {
    size_t found[2];
    double sq[2];
    if (impl_->index->nearest_k(points[i], 2, found, sq) == 2) nearest.push_back(std::sqrt(sq[1]));
  }
  if (nearest.empty()) return 0;
  std::nth_element(nearest.begin(), nearest.begin() + long(nearest.size() / 2), nearest.end());
  return 2 * nearest[nearest.size() / 2];
}

}  // namespace rosmill::core::scan
