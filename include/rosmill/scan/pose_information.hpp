// How well a point-to-plane fit fixes each of the six degrees of freedom of a pose, and how far the pose may be
// off along each. Gelfand et al., "Geometrically stable sampling for the ICP algorithm" (2003): the 6x6 matrix
// sum J^T J of the rows J = [((p - c) x n) / L, n] (rotations about the fixed surface's centroid c, scaled by a
// characteristic radius L so that a turn compares with a slide as the displacement it makes at that radius) has
// small eigenvalues along the motions the surface leaves free: a plane's slides and turn about its normal, a
// cylinder's slide along and turn about its axis. Censi, "An accurate closed-form estimate of ICP's covariance"
// (2007): the pose's covariance from the same matrix and the residuals.
//
// A pure covariance (residual variance times the inverse information) assumes every residual is independent noise.
// Neighbouring pairs share errors (a facet paired with its neighbour's samples, a reference point's noisy normal):
// the surface pairs' pull is summed within cells before it is squared (the cluster-robust sandwich), over cells
// from a few sampling spacings to the radius, the largest spread kept. Three errors the residuals at the estimate
// do not show are added: nearest-sample pairing on a curved surface (each pair's tangent plane stands off the
// surface by a sagitta, with the curvature's sign over whole regions: the signed sum of their pull); the outline
// pairs' (points on a face that ends at an outline where the fixed surface turns away: a plate's top seen from
// above, paired near its border with samples of the unseen side walls), half the fixed surface's sampling spacing
// each as far as outlines carry the direction, all in the same sense (which sample of the unseen wall a point
// pairs with) when the fixed surface is a design; against another view's cloud, their residuals signed (a bias of
// one sense along a whole border cancels against the opposite border) and half a spacing of independent scatter
// each, a crease's pairs still taken whole; and, for normals estimated from noisy points, a direction held by no more information than their
// random tilt makes is taken as held only as far as a pair's residual moves by its RMS. A floor covers the ICP's
// last step. A direction is weak when its sigma exceeds a bound; free when no pair constrains it at all. When an
// alignment kept a given pose along the weakest motions, every direction carries that pose's error as far as it
// reaches along them.
#pragma once
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rosmill/geometry/types.hpp"

namespace rosmill::core::scan {

// One point-to-plane pair of the estimator that ran, in the fixed surface's frame.
struct PlanePair {
  Vec3 point = Vec3::Zero();   // the moving point, at the estimated pose
  Vec3 normal = Vec3::UnitZ(); // the fixed surface's unit normal at its pair
  double residual = 0;         // signed distance of the point to the pair's tangent plane, mm
  bool outline = false;        // the moving point's own surface turns away from its pair's (see above)
  bool crease = false;         // an outline pair because its fixed sample's normal is no face's (a step's edge)
  // mm, signed like the residual: how far the pair's tangent plane stands off the surface at the point where it
  // bends between them (half the turn of the normal from the pair's to the point's times their offset along the
  // plane: a circle's sagitta). Nearest-sample pairing on a curved surface biases residuals by it, with the sign
  // of the curvature over whole regions, a bias the residuals at the estimate do not show.
  double bend = 0;
};

// A motion of the pose: a slide along `axis` or a turn about `axis` through the centre (fixed surface's frame).
struct PoseDirection {
  bool rotation = false;
  Vec3 axis = Vec3::UnitX();
  std::string name;                  // "translation along the design's x axis", "rotation about (0.6, 0.8, 0)"
  double surface_information = 0;    // of the surface pairs along it, per pair, scaled (mm^2 per mm^2)
  double outline_information = 0;    // what the outline pairs add
  double sigma = 0;                  // 1 sigma: mm for a slide, degrees for a turn; infinity when free
  bool weak = false;                 // sigma above the bound, or free
  bool free = false;                 // no pair constrains it
  bool outline_only = false;         // the surface pairs leave it free; only outlines fix it
};

struct PoseInformationOptions {
  double max_sigma = 0.1;         // mm: 1-sigma displacement (a turn's at the radius) above which a direction is weak
  double floor = 0.001;           // mm: the least sigma of any direction (what no term models: the ICP's last step)
  double normal_error = 0;        // rad: 1-sigma tilt of the fixed surface's normals (0: exact, a design's faces)
  double outline_degrees = 60;    // a pair is an outline pair when the two normals' lines differ by more
  // An alignment that keeps a given pose along the motions fixed no better than `lock_sigma` mm (0: none kept;
  // view_fusion.hpp): those motions' error is the given pose's, 1 sigma `given_mm` per slide and `given_deg` per
  // turn, and every direction that mixes them carries it.
  double lock_sigma = 0;
  // The fixed surface is another view's cloud, not a design's sampling: its outline pairs' bias is read from
  // their residuals, signed (see pose_information.cpp, Spread), rather than half the spacing each in one sense.
  bool cloud_reference = false;
  double given_mm = 0, given_deg = 0;
  void check() const;             // Error naming the option out of range
};

struct PoseInformation {
  Vec3 centre = Vec3::Zero();                          // the rotations' centre (the fixed surface's centroid)
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // the principal axes, columns, in the fixed frame
  double radius = 1;                                   // mm: the characteristic radius L
  double spacing = 0;                                  // mm: the fixed surface's sampling spacing
  size_t surface_pairs = 0, outline_pairs = 0;
  double surface_rms = 0;                              // mm: RMS residual of the surface pairs
  std::array<PoseDirection, 6> dofs;                   // slides along axes 1, 2, 3, then turns about them
  std::vector<PoseDirection> weak;                     // the weak motions (eigen-directions), weakest first
  // The eigen-directions of the information as motions: columns (turn in radians, slide in mm; turns about
  // `centre`) in the fixed frame, each with its sigma (mm: a turn's displacement at the radius; infinity: free).
  Eigen::Matrix<double, 6, 6> motions = Eigen::Matrix<double, 6, 6>::Identity();
  Eigen::Matrix<double, 6, 1> motion_sigma = Eigen::Matrix<double, 6, 1>::Zero();
  // The motions whose sigma (the overlap's own, before any given pose's) is within `bound` mm, as columns: an alignment restricted to them (plane_icp.hpp,
  // IcpMotions) keeps the pose where it started along the others.
  Eigen::Matrix<double, 6, Eigen::Dynamic> fixed_motions(double bound) const;
  double translation_sigma = 0, rotation_sigma_deg = 0;  // the largest of the dofs'
  bool ambiguous() const { return !weak.empty(); }
  double max_sigma = 0;                                // mm: the bound the weak ones exceed
  // "translation along the design's x axis (1 sigma 0.3 mm, fixed only by outlines); ...: weak beyond ...".
  std::string describe() const;
};

// The pairs' information and sigmas in the frame (centre, principal axes as columns) at radius `radius`, the fixed
// surface sampled at `spacing` mm (PlaneIcp::spacing()). Throws Error when `radius` is not positive.
PoseInformation pose_information(const std::vector<PlanePair>& pairs, const Vec3& centre, const Eigen::Matrix3d& axes,
                                 double radius, double spacing, const PoseInformationOptions& options,
                                 const std::string& frame_name = "design");

// A turn of `degrees` about `axis` (fixed frame) maps the fixed surface onto itself: the pairs cannot tell poses
// that far apart about it, and the fit lands anywhere within one such step (the facet kinks of a turned part,
// finer than the sampling, hold it only by chance). The turn about the principal axis within 10 degrees of it gets
// at least the spread of a uniform error over one step, degrees / sqrt(12), and is weak beyond the bound.
void widen_for_symmetry(PoseInformation& info, const Vec3& axis, double degrees);

// The per-direction table as text, a line a direction ("  translation along ...: sigma 0.0012 mm, information
// surface 0.31 + outlines 0.002 per pair").
std::string format_pose_information(const PoseInformation& info);

// Whether two unit normals (signs arbitrary) differ by more than `degrees` in their lines.
bool normals_disagree(const Vec3& a, const Vec3& b, double degrees);

}  // namespace rosmill::core::scan
