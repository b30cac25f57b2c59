// The part as the whole tool meets it, not the cutter alone: above the cutter the shank from the flute length up and
// the holder from the stick-out up (the tool table's stick_out and holder_diameter), each a flat-ended cylinder of
// its radius and a clearance. A drop is the highest of the drops, each body's lowered by its height above the tip;
// a strategy planning on this surface keeps the shank and the holder out of the part as it keeps the cutter out, and
// leaves a feature deeper than the tool reaches for a longer tool. The bodies keep out of the material a job's stock
// still holds (MaterialTop) too: the cutter cuts it, its holder must not meet it. Where neither stands higher over
// the floor than the stick-out (or the flutes, for a shank wider than the cutter) no such body can meet it, and the
// surface answers as the one inside, at its cost.
#pragma once
#include <memory>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/plan/material_top.hpp"
#include "rosmill/plan/surface.hpp"

namespace rosmill::core {

// mm the shank and the holder keep from the part, beyond their radii and the plan's allowance: the stock the
// plans leave stands the allowance off the part, on cells of the stock's grid (0.5 mm in the bundled jobs).
constexpr double kBodyClearance = 1.0;

class ToolBodySurface : public Surface {
 public:
  // `inner` and `material` (the stock's material in the plan's frame, or null) must outlive this surface.
  ToolBodySurface(const Surface& inner, const Tool& tool, const MaterialTop* material = nullptr,
                  double allowance = 0);

  // Whether any part of the tool above the cutter can meet the surface (else every answer is inner's).
  bool body_matters() const { return shank_ || holder_; }

  Box3 bounds() const override { return inner_.bounds(); }
  Drop drop(const Cutter& cutter, double x, double y) const override;
  void drop_many(const Cutter& cutter, const Vec2* xy, size_t n, Drop* out) const override;
  bool held_above(const Cutter& cutter, double x, double y, double z) const override;
  std::unique_ptr<LevelProbe> level_probe(const Cutter& cutter, double z) const override;
  SweepHit sweep(const Cutter& cutter, const Vec3& a, const Vec3& b, double floor) const override;
  bool skips(double x, double y, double radius) const override { return inner_.skips(x, y, radius); }
  // The inner surface's, and a body's radius beyond whatever holds it (the part, or the material's grid).
  double held_reach() const override;

 private:
  struct Body {
    Cutter cylinder;  // flat-ended, the body's radius and the clearance
    double height;    // its lowest point above the tip
    MaterialTop material;  // the highest material within the body's reach, per cell (no cells without material)
  };
  // The highest material a body with its axis at (x, y) stands over; -infinity without material there.
  double material_under(const Body& b, double x, double y) const;
  // Whether the body, the tip at z, meets the material or the part.
  bool body_holds(const Body& b, double x, double y, double z) const;
  const Surface& inner_;
  const MaterialTop* grid_ = nullptr;
  std::unique_ptr<Body> shank_, holder_;
};

}  // namespace rosmill::core
