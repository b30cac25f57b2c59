// The seam between geometry and planning: "where does this cutter touch down at (x, y)?". A mesh answers from its
// triangles, a point cloud from its points; every strategy is written against this. Two optional queries let a
// surface answer better than sampling its drops: how deep it reaches into a cutter moving in a straight line (the
// check of the paths between cutter locations in Muslimin et al., "Direct NC Toolpath Generation from 3D Point
// Cloud Datasets"), and where the input asks for no cut at all (missing data a cloud's hole policy skips).
#pragma once
#include <cstddef>
#include <memory>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/types.hpp"

namespace rosmill::core {

struct Drop {
  double z = 0.0;       // tip height of the cutter at its lowest position that touches the surface
  bool touched = false; // false: nothing lies under the cutter's footprint (z is then the surface's floor)
};

// How deep the surface reaches into a cutter that moves with its tip from a to b.
struct SweepHit {
  double depth = 0.0;  // mm the deepest part goes into the cutter (<= 0: clear)
  double at = 0.0;     // where along the move that is (0 at a, 1 at b)
};

// Many "held above z?" questions at one height, asked in bursts near one place each (a waterline bisects along a
// grid edge, then refines a chord): a surface may gather once per place what can answer them there.
class LevelProbe {
 public:
  virtual ~LevelProbe() = default;
  // The questions until the next focus lie within `radius` of `centre`.
  virtual void focus(const Vec2& centre, double radius) = 0;
  // Surface::held_above(cutter, x, y, z) for the probe's cutter and height, (x, y) within the focus.
  virtual bool held_above(double x, double y) = 0;
};

class Surface {
 public:
  virtual ~Surface() = default;
  virtual Box3 bounds() const = 0;
  // Lowest tip height for the cutter with its axis at (x, y) that does not go into the surface. Thread-safe,
  // no allocation: strategies call it from both cores.
  virtual Drop drop(const Cutter& cutter, double x, double y) const = 0;
  // Batch form: z for n points; the default loops over drop(). Implementations parallelise.
  virtual void drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const;
  // True when the surface touches the cutter at (x, y) and holds its tip above z: drop(...) touched at a height
  // above z, to the last bit. A question a surface can answer without finding the exact contact (a waterline
  // asks it many times per loop point); the default drops the cutter.
  virtual bool held_above(const Cutter& cutter, double x, double y, double z) const;
  // A probe for held_above at one height, used by one thread at a time; the default asks held_above.
  virtual std::unique_ptr<LevelProbe> level_probe(const Cutter& cutter, double z) const;
  // The deepest the surface goes into the cutter along the straight move from tip a to tip b when deeper than
  // `floor`, else {floor, 0}. The default compares the drop with the tip's height every R/16 (0.01 to 0.05 mm)
  // along the move, which is what a mesh answers; a cloud answers exactly from its points.
  virtual SweepHit sweep(const Cutter& cutter, const Vec3& a, const Vec3& b, double floor) const;
  // True when a cutter footprint of `radius` at (x, y) reaches where the input says not to cut (a cloud's holes
  // under the Skip policy); strategies leave such positions out. The default: nowhere.
  virtual bool skips(double x, double y, double radius) const;
  // How far beyond bounds() in XY, past the cutter's own radius, the surface may hold a cutter: 0 for a part alone;
  // a fixture beside it, or a tool's holder wider than its cutter, reaches further. A strategy that contours
  // where the cutter is held (a waterline) covers that much more, so that no contour runs off its grid.
  virtual double held_reach() const { return 0.0; }
};

}  // namespace rosmill::core
