// A ball end mill tilted along any axis against a mesh, for multi-axis finishing: where it touches (the ball pushed
// down its axis onto the facets, an exact contact through geometry/sphere_sweep.hpp), whether the shank and the
// holder clear the part on the way, and whether the ball at a point between two cutter locations goes in or stands
// off. The ball is the same whatever the axis; the axis decides only what it is pushed along and where the shank
// and holder stand. Beyond the part's bounds grown by the tool and a margin nothing can be met: every sweep starts
// there.
#pragma once
#include <array>
#include <functional>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/mesh_ray.hpp"
#include "rosmill/plan/plan_report.hpp"
#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::core {

// One cutter location: the ball's centre, the tool axis, and how far the ball stands off the point it was aimed at.
struct BallLocation {
  bool ok = false;  // the tool reaches it (the shank and holder clear the part on the way)
  Vec3 centre = Vec3::Zero(), axis = Vec3::UnitZ();
  double left = 0;      // mm between the centre and where it would touch the aimed-at facet alone
  bool turned = false;  // the axis is not the strategy's rule's: turned to clear
  Vec3 tip(double radius) const { return centre - radius * axis; }
};

class BallContact {
 public:
  // `allowance`: the ball grown by it (stock left on the surface); `margin` (mm) the free space round the part's
  // bounds where sweeps start.
  BallContact(const Mesh& mesh, const Tool& tool, double allowance, double tolerance, double margin);

  // The first facet a ray from `origin` along `direction` meets from outside (its facet normal against the ray):
  // the point, the facet's normal and the smooth normal there (geometry/corner_normals.hpp).
  bool surface(const Vec3& origin, const Vec3& direction, Vec3& point, Vec3& facet_normal, Vec3& smooth) const;
  // The ball pushed down `axis` from outside onto the mesh, aimed at its centre `target`: how far it stops short
  // (0 when it gets there), +infinity when a shank wider than the ball or the holder meets the part on the way.
  double push(const Vec3& target, const Vec3& axis, Vec3& centre) const;
  // The cutter location aimed at `point` on a facet of normal `facet_normal`, the tool along `axis`.
  BallLocation locate(const Vec3& point, const Vec3& facet_normal, const Vec3& axis) const;
  // A sphere of radius r swept down `axis` from outside to centre `end` meets nothing on the way.
  bool swept_clear(const Vec3& end, const Vec3& axis, double r) const;
  // The ball (grown by the allowance) centred at `centre` goes into the part by more than the tolerance.
  bool gouges(const Vec3& centre) const;
  // The tool with its ball centred at `centre` along `axis` stands clear of the part: the ball and the flutes above
  // it (a sphere a tolerance thinner than the grown ball swept down the axis to the centre), a wider shank and the
  // holder (swept the same way to their lower ends), as push() leaves them at a cutter location.
  bool body_clear(const Vec3& centre, const Vec3& axis) const;
  // It comes within the tolerance and `slack` of the part.
  bool touches(const Vec3& centre, double slack) const;

  // How far along `axis` from p until a sphere of radius r is wholly outside the grown bounds: the free space the
  // sweeps start from.
  double run_out(const Vec3& p, const Vec3& axis, double r) const;
  const Box3& free_bounds() const { return free_; }
  const MeshRays& rays() const { return rays_; }
  double radius() const { return R_; }
  double tolerance() const { return tol_; }
  const Tool& tool() const { return tool_; }

 private:
  bool shank_and_holder_clear(const Vec3& centre, const Vec3& axis) const;

  const Mesh& mesh_;
  MeshRays rays_;
  std::vector<std::array<Vec3, 3>> normals_;
  const Tool& tool_;
  double R_, ra_, tol_;
  Box3 free_;  // outside it the tool meets nothing
};

// Cutter locations between a and b (b appended, the locations inserted before it), halving the move until the ball
// halfway along each, the tip and the axis interpolated as the controller moves them, neither goes into the part
// nor stands off it by more than the tolerance beyond what its ends leave, and the rest of the tool there stands
// clear of the part (body_clear: the axis turning between two locations swings flutes, shank and holder). `between(s,
// axis)` is the cutter location at parameter s of the pass with a given axis. `broke` is set where the tool cannot
// reach between them (or a halving at the deepest still goes in): the pass must break there.
void refine_between(const BallContact& contact, const BallLocation& a, const BallLocation& b, double sa, double sb,
                    const std::function<BallLocation(double, const Vec3&)>& between, std::vector<BallLocation>& out,
                    bool& broke, int depth = 0);

// A run of cutter locations at parameters `at` refined (refine_between) into the runs it breaks into, each of two
// locations or more, appended to `runs`.
void refine_run(const BallContact& contact, const std::vector<BallLocation>& run, const std::vector<double>& at,
                const std::function<BallLocation(double, const Vec3&)>& between,
                std::vector<std::vector<BallLocation>>& runs);

// A pass sampled at parameters at(0) .. at(n): `locate(s, previous)` gives the cutter location at s (`previous` the
// one before in the same run, or null), the pass breaking where it gives none; each run is handed to `adjust` (when
// given: a smoothing of its axes) and refined (refine_run).
std::vector<std::vector<BallLocation>> sample_runs(
    const BallContact& contact, int n, const std::function<double(int)>& at,
    const std::function<BallLocation(double, const BallLocation*)>& locate,
    const std::function<BallLocation(double, const Vec3&)>& between,
    const std::function<void(std::vector<BallLocation>&, const std::vector<double>&)>& adjust = {});

// What the cutter locations of the multi-axis passes say of their tool axes, for the plan's report.
struct AxisFigures {
  double max_tilt_deg = 0;         // from +Z
  double max_rate_deg_per_mm = 0;  // change of axis along a cutting move
  double max_left_mm = 0;          // the most a kept location stands off
};

// The run's cutting moves after its first location, each to a location's tip with its axis, at `feed`; the figures
// take in the whole run.
void add_cuts(ToolpathPass& pass, const std::vector<BallLocation>& run, double radius, double feed, AxisFigures& f);

// A multi-axis ball strategy's report.
void report_axes(PlanReport* report, const Toolpath& tp, size_t lines, size_t samples, size_t turned,
                 size_t unreachable, const AxisFigures& f);

// Throws Error(strategy, ...) unless the tool is a ball end mill and the mesh has facets of some area.
void check_ball_finishing(const Mesh& mesh, const Tool& tool, const std::string& strategy);

}  // namespace rosmill::core
