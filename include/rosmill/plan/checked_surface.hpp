// A part to machine with things to keep clear of: the drive surface (the part, what the strategy machines and whose
// bounds set its levels and area) and a check surface (a fixture's boxes grown by a clearance) that the cutter must
// not enter but is not machined. The cutter comes down onto whichever it meets first: a drop is the higher of the
// two, and it is held above a height when either holds it. Every strategy written against Surface so keeps off the
// fixture; what it cannot see (the shank and the holder) the fixture check of the stock catches
// (stock/fixture_collision.hpp).
#pragma once
#include "rosmill/plan/surface.hpp"

namespace rosmill::core {

class CheckedSurface : public Surface {
 public:
  // Neither is owned; both outlive this.
  CheckedSurface(const Surface& drive, const Surface& check) : drive_(drive), check_(check) {}

  Box3 bounds() const override { return drive_.bounds(); }
  Drop drop(const Cutter& cutter, double x, double y) const override;
  bool held_above(const Cutter& cutter, double x, double y, double z) const override;
  SweepHit sweep(const Cutter& cutter, const Vec3& a, const Vec3& b, double floor) const override;
  bool skips(double x, double y, double radius) const override { return drive_.skips(x, y, radius); }
  double held_reach() const override;

 private:
  const Surface& drive_;
  const Surface& check_;
};

}  // namespace rosmill::core
