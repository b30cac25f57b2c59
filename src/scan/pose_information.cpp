#include "rosmill/scan/pose_information.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
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

// The cells of a grid of `cell` mm that hold the pairs' points: a cell index a pair, and the number of cells.
std::vector<uint32_t> cells_of(const std::vector<PlanePair>& pairs, double cell, size_t* count) {
  std::vector<std::array<int64_t, 3>> keys(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i)
    for (int a = 0; a < 3; ++a) keys[i][size_t(a)] = int64_t(std::floor(pairs[i].point[a] / cell));
  std::vector<size_t> order(pairs.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return keys[a] < keys[b]; });
  std::vector<uint32_t> out(pairs.size());
  uint32_t id = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    if (k && keys[order[k]] != keys[order[k - 1]]) ++id;
    out[order[k]] = id;
  }
  *count = pairs.empty() ? 0 : size_t(id) + 1;
  return out;
}

// The linearised estimate's spread along u (scaled coordinates). The estimate moves by -H+ sum J_i e_i for the
// pairs' errors e_i at the true pose; their residuals at the estimate stand for them. Errors that neighbouring
// pairs share (a facet paired with its neighbour's samples, a reference point's noisy normal, a curvature's bias)
// do not average out as independent noise would: the residuals' pull is summed within cells before it is
// squared, the cluster-robust sandwich (Liang & Zeger, "Longitudinal data analysis using generalized linear
// models", 1986; Censi 2007's covariance for independent errors is its one-pair-a-cell case), H+ (sum_c g_c g_c^T)
// H+ with g_c = sum over the cell's pairs of J_i r_i. The scale over which errors are shared is not known: the
// cells run from a few sampling spacings to a quarter of the radius, and the largest spread is taken, corrected
// for the cells' count (G / (G - 6): the residuals at the estimate pull it nowhere in total). Outline pairs (their
// fixed surface is an unseen wall) add, as far as outlines carry u, half the sampling spacing each, all in the
// same sense (which sample of the wall a point pairs with: a bias no number of points averages out); and the floor.
struct Spread {
  const Matrix6& vectors;
  const Vector6& values;
  const Matrix6& surface;
  const std::vector<Vector6>& rows;
  const std::vector<PlanePair>& pairs;
  const Matrix6& all;
  const std::vector<std::vector<uint32_t>>& cells;  // per scale, a cell a pair
  const std::vector<size_t>& cell_counts;
  double floor, spacing, rms, normal_error;
  bool cloud_reference;

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
    std::vector<double> pull(rows.size());
    double whole = 0, signed_sum = 0, scatter = 0, bend = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
      pull[i] = w.dot(rows[i]);
      if (pairs[i].outline && (pairs[i].crease || !cloud_reference)) {
        whole += std::abs(pull[i]);
      } else if (pairs[i].outline) {
        signed_sum += pull[i] * std::clamp(pairs[i].residual, -spacing / 2, spacing / 2);
        scatter += pull[i] * pull[i];
      } else {
        bend += pull[i] * pairs[i].bend;
      }
    }
    // A design's unseen wall is sampled to its edge: every outline pair stands half a spacing off it in the
    // same sense, and the fit slides until the borders' pulls balance, so the residuals at the estimate no
    // longer show it: taken whole. A cloud's border is where the other view stopped seeing, its spacing is not
    // the design's, and its outline pairs lie on faces the other view saw at a slant: their residuals at the
    // estimate are the bias, signed, and a bias of one sense along a whole border cancels against the opposite
    // border for a slide; each pair's share of a spacing scatters besides (half a spacing each, independent).
    // A crease's tilted normal pulls sideways in its own sense, whichever reference: taken whole.
    const double bias = outline_share * (whole * spacing / 2 + std::hypot(signed_sum, spacing / 2 * std::sqrt(scatter)));
    double variance = 0;
    std::vector<double> sums;
    for (size_t s = 0; s < cells.size(); ++s) {
      const size_t g = cell_counts[s];
      if (g <= 6) continue;
      sums.assign(g, 0.0);
      for (size_t i = 0; i < rows.size(); ++i) sums[cells[s][i]] += pull[i] * pairs[i].residual;
      double sum_sq = 0;
      for (double x : sums) sum_sq += x * x;
      variance = std::max(variance, sum_sq * double(g) / double(g - 6));
    }
    const double sigma = std::sqrt(variance + bias * bias + bend * bend + floor * floor);
    // Normals estimated from noisy points tilt at random by about normal_error: along a direction the shape
    // leaves free (a cylinder's axis, a plate's slides) they alone make an information per pair of about its
    // square, and the fit slides as far as the residuals allow, never converging to the truth. There the spread
    // is the residuals' RMS over the root of the information per pair (how far a pair's residual moves by its RMS).
    const double per_pair = 1 / (double(rows.size()) * std::max(u.dot(w), 1e-300));
    if (per_pair < normal_error * normal_error) return std::max(sigma, rms / std::sqrt(per_pair));
    return sigma;
  }
};

}  // namespace

void PoseInformationOptions::check() const {
  const auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw Error(std::string("pose information option ") + name, "must be a positive number");
  };
  positive(max_sigma, "max_sigma");
  positive(floor, "floor");
  if (!(lock_sigma >= 0 && given_mm >= 0 && given_deg >= 0) || !std::isfinite(lock_sigma + given_mm + given_deg))
    throw Error("pose information options lock_sigma, given_mm, given_deg", "must be numbers >= 0");
  if (!(normal_error >= 0 && normal_error < 1)) throw Error("pose information option normal_error", "must lie in [0, 1)");
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
  // Cells from four sampling spacings (or a 64th of the radius) up, doubling, to a quarter of the radius.
  std::vector<std::vector<uint32_t>> cells;
  std::vector<size_t> cell_counts;
  for (double cell = std::max(4 * spacing, radius / 64); cell <= radius * (1 + 1e-9); cell *= 2) {
    cell_counts.push_back(0);
    cells.push_back(cells_of(pairs, cell, &cell_counts.back()));
  }
  const Spread spread{vectors, values, surface, rows, pairs, all, cells, cell_counts, o.floor, spacing,
                      info.surface_rms, o.normal_error, o.cloud_reference};
  for (int k = 0; k < 6; ++k) {
    const Vector6 v = vectors.col(k);
    info.motions.col(k) << axes * v.head<3>() / radius, axes * v.tail<3>();
    info.motion_sigma[k] = pairs.empty() ? kInfinity : spread(v);
  }
  // An eigen-motion locked at the given pose (Spread's k-th coordinate of the error is then the given pose's
  // along it, independent of the fit) adds its variance to every direction u as far as u reaches along it:
  // u . e = sum_k (u . v_k)(v_k . e), the locked k from the given pose (its turn part at the radius), the others
  // from the fit, as though the locked ones were absent.
  const auto stated = [&](const Vector6& u) {
    if (!(o.lock_sigma > 0)) return spread(u);
    Vector6 fitted = u;
    double locked = 0;
    for (int k = 0; k < 6; ++k) {
      if (info.motion_sigma[k] <= o.lock_sigma) continue;
      const Vector6 v = vectors.col(k);
      const double along = v.dot(u), turn = radius * o.given_deg * M_PI / 180;
      fitted -= along * v;
      locked += along * along * (v.head<3>().squaredNorm() * turn * turn + v.tail<3>().squaredNorm() * o.given_mm * o.given_mm);
    }
    const double fit = fitted.norm() > 1e-9 ? spread(fitted) : o.floor;
    return std::sqrt(fit * fit + locked);
  };
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
    const double s = pairs.empty() ? kInfinity : stated(u);
    d.free = pairs.empty() || !std::isfinite(o.lock_sigma > 0 ? spread(u) : s);
    d.sigma = d.rotation ? s / radius * 180 / M_PI : s;
    d.weak = !(s <= o.max_sigma);
    d.outline_only = !(d.surface_information > kFree * surface_largest * per_pair);
    (d.rotation ? info.rotation_sigma_deg : info.translation_sigma) =
        std::max(d.rotation ? info.rotation_sigma_deg : info.translation_sigma, d.sigma);
    if (d.weak) info.weak.push_back(d);
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

void widen_for_symmetry(PoseInformation& info, const Vec3& axis, double degrees) {
  const double least = degrees / std::sqrt(12.0);
  for (int k = 3; k < 6; ++k) {
    PoseDirection& d = info.dofs[size_t(k)];
    if (std::abs(d.axis.dot(axis.normalized())) < std::cos(10 * M_PI / 180) || !(d.sigma < least)) continue;
    d.sigma = least;
    info.rotation_sigma_deg = std::max(info.rotation_sigma_deg, least);
    if (d.weak || least * M_PI / 180 * info.radius <= info.max_sigma) continue;
    d.weak = true;
    info.weak.push_back(d);
    std::stable_sort(info.weak.begin(), info.weak.end(), [&](const PoseDirection& a, const PoseDirection& b) {
      const auto mm = [&](const PoseDirection& x) { return x.rotation ? x.sigma * M_PI / 180 * info.radius : x.sigma; };
      return mm(a) > mm(b);
    });
  }
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
