#include "rosmill/scan/pose_information.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "rosmill/error.hpp"
#include "rosmill/number_text.hpp"

namespace rosmill::core::scan {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// An eigenvalue below this share of the largest is no information (rounding of a sum of exact zeros).
constexpr double kFree = 1e-10;

// A pair's row in scaled principal coordinates: (turn * L, slide), as the unknowns of the linearised fit.
Vector6 row(const PlanePair& p, const Vec3& centre, const Eigen::Matrix3d& axes, double radius) {
  const Vec3 n = axes.transpose() * p.normal;
  const Vec3 q = axes.transpose() * (p.point - centre);
  Vector6 j;
  j << q.cross(n) / radius, n;
  return j;
}

// "the design's x axis" when the axis lies within 10 degrees of a coordinate axis, else its direction.
std::string axis_name(const Vec3& axis, const std::string& frame) {
  static const char* const kNames[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k)
    if (std::abs(axis[k]) > std::cos(10 * M_PI / 180)) return "the " + frame + "'s " + kNames[k] + " axis";
  return "(" + decimal_text(axis.x(), 3) + ", " + decimal_text(axis.y(), 3) + ", " + decimal_text(axis.z(), 3) + ") in the " + frame +
         "'s frame";
}

// The linearised estimate's spread along u (scaled coordinates): the surface pairs' noise through the sandwich
// H+ Hs H+ (Censi 2007 with the outline rows carrying no noise of their own), the residuals equicorrelated (a
// variance rms^2 (1 + rho (N - 1)) for N pairs: the pairs share errors -- a facet paired with its neighbour's
// samples, the tessellation -- that no number of points averages out); the outline pairs' residuals all
// biased the same way, each by its own size plus half the sampling spacing as far as the outlines carry u (which
// sample of an unseen wall a point pairs with: the sum of |u^T H+ J_i| (|r_i| + share * spacing / 2)); and the
// floor.
struct Spread {
  const Matrix6& vectors;
  const Vector6& values;
  const Matrix6& surface;
  const std::vector<Vector6>& rows;
  const std::vector<PlanePair>& pairs;
  const Matrix6& all;
  double noise, floor, spacing, correlation, surface_pairs;

  double operator()(const Vector6& u) const {
    const double largest = values[5];
    Vector6 w = Vector6::Zero();
    for (int k = 0; k < 6; ++k) {
      const double along = vectors.col(k).dot(u);
      if (!(values[k] > kFree * largest)) {
        if (std::abs(along) > 1e-6) return kInfinity;  // u moves along a free direction
        continue;
      }
      w += vectors.col(k) * (along / values[k]);
    }
    const double spread = std::max(0.0, w.dot(surface * w)), total = w.dot(all * w);
    const double outline_share = total > 0 ? std::clamp(1 - spread / total, 0.0, 1.0) : 0.0;
    double bias = 0;
    for (size_t i = 0; i < rows.size(); ++i)
      if (pairs[i].outline)
        bias += std::abs(w.dot(rows[i])) * (std::abs(pairs[i].residual) + outline_share * spacing / 2);
    return std::sqrt(noise * noise * (1 + correlation * std::max(0.0, surface_pairs - 1)) * spread + bias * bias +
                     floor * floor);
  }
};

}  // namespace

void PoseInformationOptions::check() const {
  const auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw Error(std::string("pose information option ") + name, "must be a positive number");
  };
  positive(max_sigma, "max_sigma");
  positive(floor, "floor");
  if (!(correlation >= 0 && correlation <= 1)) throw Error("pose information option correlation", "must lie in [0, 1]");
  if (!(floor_share_of_rms >= 0) || !std::isfinite(floor_share_of_rms))
    throw Error("pose information option floor_share_of_rms", "must be a number >= 0");
  if (!(outline_degrees > 0 && outline_degrees < 90))
    throw Error("pose information option outline_degrees", "must lie in (0, 90)");
}

bool normals_disagree(const Vec3& a, const Vec3& b, double degrees) {
  return std::abs(a.dot(b)) < std::cos(degrees * M_PI / 180);
}

PoseInformation pose_information(const std::vector<PlanePair>& pairs, const Vec3& centre, const Eigen::Matrix3d& axes,
                                 double radius, double spacing, const PoseInformationOptions& o,
                                 const std::string& frame) {
  o.check();
  if (!(radius > 0) || !std::isfinite(radius)) throw Error("pose information", "the radius must be a positive number");
  if (!(spacing >= 0) || !std::isfinite(spacing)) throw Error("pose information", "the spacing must be a number >= 0");
  PoseInformation info;
  info.centre = centre;
  info.axes = axes;
  info.radius = radius;
  info.max_sigma = o.max_sigma;
  info.spacing = spacing;
  Matrix6 all = Matrix6::Zero(), surface = Matrix6::Zero();
  std::vector<Vector6> rows;
  rows.reserve(pairs.size());
  double sum_sq = 0;
  for (const PlanePair& p : pairs) {
    rows.push_back(row(p, centre, axes, radius));
    all += rows.back() * rows.back().transpose();
    if (p.outline) {
      ++info.outline_pairs;
    } else {
      surface += rows.back() * rows.back().transpose();
      sum_sq += p.residual * p.residual;
      ++info.surface_pairs;
    }
  }
  info.surface_rms = info.surface_pairs ? std::sqrt(sum_sq / double(info.surface_pairs)) : 0;
  const Eigen::SelfAdjointEigenSolver<Matrix6> es(all);
  const Vector6 values = es.eigenvalues();
  const Matrix6 vectors = es.eigenvectors();
  const Spread spread{vectors, values, surface, rows, pairs, all, info.surface_rms,
                      std::max(o.floor, o.floor_share_of_rms * info.surface_rms), spacing, o.correlation,
                      double(info.surface_pairs)};
  const double per_pair = pairs.empty() ? 1 : 1.0 / double(pairs.size());
  const double surface_largest = Eigen::SelfAdjointEigenSolver<Matrix6>(surface).eigenvalues()[5];
  for (int k = 0; k < 6; ++k) {
    PoseDirection& d = info.dofs[size_t(k)];
    d.rotation = k >= 3;
    d.axis = axes.col(k % 3);
    d.name = std::string(d.rotation ? "rotation about " : "translation along ") + axis_name(d.axis, frame);
    Vector6 u = Vector6::Zero();
    u[d.rotation ? k - 3 : k + 3] = 1;  // the rows hold the turn first
    d.surface_information = u.dot(surface * u) * per_pair;
    d.outline_information = u.dot((all - surface) * u) * per_pair;
    const double s = pairs.empty() ? kInfinity : spread(u);
    d.free = !std::isfinite(s);
    d.sigma = d.rotation ? s / radius * 180 / M_PI : s;
    d.weak = !(s <= o.max_sigma);
    d.outline_only = !(d.surface_information > kFree * surface_largest * per_pair);
    (d.rotation ? info.rotation_sigma_deg : info.translation_sigma) =
        std::max(d.rotation ? info.rotation_sigma_deg : info.translation_sigma, d.sigma);
    if (d.weak) info.weak.push_back(d);
  }
  for (int k = 0; k < 6; ++k) {
    const Vector6 v = vectors.col(k);
    info.motions.col(k) << axes * v.head<3>() / radius, axes * v.tail<3>();
    info.motion_sigma[k] = pairs.empty() ? kInfinity : spread(v);
  }
  // A weak motion that mixes the axes (a screw, a turn about an axis off the centre) shows in no single one:
  // the eigen-directions of the information catch it.
  if (info.weak.empty())
    for (int k = 0; k < 6 && !pairs.empty(); ++k) {
      const Vector6 v = vectors.col(k);
      const double s = spread(v);
      if (s <= o.max_sigma) continue;
      PoseDirection d;
      d.rotation = v.head<3>().squaredNorm() > 0.5;
      d.axis = axes * Vec3((d.rotation ? v.head<3>() : v.tail<3>()).normalized());
      d.name = std::string(d.rotation ? "a motion mostly a rotation about " : "a motion mostly a translation along ") +
               axis_name(d.axis, frame);
      d.surface_information = v.dot(surface * v) * per_pair;
      d.outline_information = v.dot((all - surface) * v) * per_pair;
      d.free = !std::isfinite(s);
      d.sigma = d.rotation ? s / radius * 180 / M_PI : s;
      d.weak = true;
      d.outline_only = !(d.surface_information > kFree * surface_largest * per_pair);
      info.weak.push_back(d);
    }
  std::stable_sort(info.weak.begin(), info.weak.end(), [&](const PoseDirection& a, const PoseDirection& b) {
    return (a.rotation ? a.sigma * M_PI / 180 * radius : a.sigma) > (b.rotation ? b.sigma * M_PI / 180 * radius : b.sigma);
  });
  return info;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> PoseInformation::fixed_motions(double bound) const {
  Eigen::Matrix<double, 6, Eigen::Dynamic> out(6, 0);
  for (int k = 0; k < 6; ++k)
    if (motion_sigma[k] <= bound) {
      out.conservativeResize(Eigen::NoChange, out.cols() + 1);
      out.col(out.cols() - 1) = motions.col(k);
    }
  return out;
}

std::string PoseInformation::describe() const {
  std::ostringstream s;
  for (size_t i = 0; i < weak.size(); ++i) {
    const PoseDirection& d = weak[i];
    s << (i ? "; " : "") << d.name << " (";
    if (d.free)
      s << "free: nothing seen constrains it";
    else
      s << "1 sigma " << decimal_text(d.sigma, d.rotation ? 3 : 4) << (d.rotation ? " deg" : " mm")
        << (d.outline_only ? ", fixed only by outlines" : "");
    s << ")";
  }
  if (!weak.empty())
    s << ": weak beyond a 1-sigma " << decimal_text(max_sigma, 3) << " mm (a turn's at " << decimal_text(radius, 1)
      << " mm from the centre)";
  return s.str();
}

std::string format_pose_information(const PoseInformation& info) {
  std::ostringstream s;
  s << "degrees of freedom (principal frame, turns about the centroid, information per pair at radius "
    << decimal_text(info.radius, 1) << " mm; " << info.surface_pairs << " surface and " << info.outline_pairs
    << " outline pairs):\n";
  for (const PoseDirection& d : info.dofs) {
    s << "  " << d.name << ": sigma ";
    if (d.free)
      s << "free";
    else
      s << decimal_text(d.sigma, 4) << (d.rotation ? " deg" : " mm");
    s << ", information surface " << decimal_text(d.surface_information, 5) << " + outlines "
      << decimal_text(d.outline_information, 5) << (d.weak ? " (weak)" : "") << "\n";
  }
  return s.str();
}

}  // namespace rosmill::core::scan
