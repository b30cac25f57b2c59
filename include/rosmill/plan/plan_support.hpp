// What the surface strategies (raster, waterline, rough) share: the heights of safe moves, a move writer that
// keeps rapids at the safe height, adaptive drop-cutter sampling along a segment, parallel scan lines, progress
// and cancellation, and the guard against plans of absurd size.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "rosmill/plan/plan_params.hpp"
#include "rosmill/plan/region.hpp"
#include "rosmill/plan/surface.hpp"
#include "rosmill/toolpath/job.hpp"
#include "rosmill/work_bound.hpp"

namespace rosmill::core {

// Heights and parameters of one plan, resolved from PlanParams and the surface's bounds.
struct PlanFrame {
  Box3 part;            // the surface's bounds
  Box3 stock;           // part grown by the stock margin (XY and top; bottom at the part's floor)
  double safe_z = 0;    // above everything: stock top + safe clearance (rapids travel here only)
  double stepover = 0;  // resolved (params, else tool)
  double stepdown = 0;
  double allowance = 0;
  double tolerance = 0.001;
  Cutter cutter;        // the tool's cutter
  Cutter drop_cutter;   // the cutter grown by the allowance (drop it, then add the allowance)
};
PlanFrame make_frame(const Surface& surface, const PlanParams& params);

// CL height at (x, y): drop of the grown cutter plus the allowance, never below the part's floor + allowance.
double cl_height(const Surface& surface, const PlanFrame& f, double x, double y);

// Writes moves into a pass; a cut starts by a rapid at safe_z above its first point and a plunge down.
class MoveWriter {
 public:
  MoveWriter(Toolpath& tp, const PlanFrame& f);
  void begin_pass(const std::string& name);
  // Retract to safe_z (if not there), rapid above p, plunge to p at the plunge feed. With `free_z` between p and
  // safe_z (air a previous level cleared), the descent to it goes at the cutting feed.
  void enter(const Vec3& p, double free_z = NAN);
  // A link that need not climb to safe_z (the caller checked the way against the material): a rapid up to
  // link_z, across to above p, down to clear_z, then the plunge to p. From safe_z, or with link_z at or over it,
  // the rapid across runs at safe_z.
  void link_to(const Vec3& p, double link_z, double clear_z);
  // Plunge vertically down to height z (air above cleared stock) without a retract.
  void plunge_to(const Vec3& p);
  void feed(const Vec3& p);
  // A cutting move that goes in at the plunge feed when it descends vertically, else feed().
  void cut_to(const Vec3& p);
  void retract();
  bool at_safe() const { return at_safe_; }
  const Vec3& position() const { return pos_; }

 private:
  Toolpath& tp_;
  const PlanFrame& f_;
  Vec3 pos_;
  bool at_safe_ = true;
};

// The shortest chord adaptive sampling makes (mm): below it a chord that still misses the tolerance is a jump
// of the CL height (a wall) and is crossed over its highest sampled point (see sample_segment).
constexpr double kMinSampleStep = 0.01;

// CL points from a to b (inclusive) on the surface: first every `step`, then chords halved until the CL points
// at a quarter, half and three quarters of each lie within half the tolerance of it, but never below
// kMinSampleStep; a chord that short still out of tolerance (a vertical wall, the rim of the cutter reaching an
// edge) is replaced by a step that goes up first or comes down last, and consecutive such steps are one plateau.
// So a line costs at most a few drops and moves per kMinSampleStep of its length, whatever the part.
void sample_segment(const Surface& surface, const PlanFrame& f, const Vec2& a, const Vec2& b, double step,
                    std::vector<Vec3>& out);

// Drops points that lie on the straight line of their neighbours (within 1e-9 mm): same path, fewer moves.
void drop_collinear(std::vector<Vec3>& points);

// Parallel lines at `angle_deg` spaced `spacing` apart, clipped to a rectangle and (when not empty) a region;
// each line gives the [start, end] pieces inside, ordered along the direction.
struct ScanLine {
  std::vector<std::pair<Vec2, Vec2>> pieces;
};
std::vector<ScanLine> scan_lines(const Vec2& lo, const Vec2& hi, double angle_deg, double spacing,
                                 const Region& region);

// Runs f over [0, n) in parallel, in blocks, reporting progress between blocks (cancel throws Error).
void parallel_blocks(size_t n, const PlanProgress& progress, double from, double to,
                     const std::function<void(size_t)>& f);
void check_cancel(const PlanProgress& progress, double fraction);

// check_work (rosmill/work_bound.hpp) for a strategy over the plan's part.
void check_plan_work(const std::string& strategy, const Work& work, const PlanFrame& f);

}  // namespace rosmill::core
