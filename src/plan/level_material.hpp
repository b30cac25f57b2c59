// The material one roughing level still has to cut, as a bitmap of square cells in XY: a cell is material while
// its centre lies in the region to clear and no cutter disc that passed at this level covered it. The adaptive
// strategy asks it the cutter's radial engagement (the angle of its leading half-circle in material) and whether a
// disc is free of material; it is the planner's own bookkeeping, not the verifier's independent measurement.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "rosmill/geometry/clip_region.hpp"

namespace rosmill::core {

class LevelMaterial {
 public:
  // Cells of edge `cell` covering [lo, hi]; no material anywhere.
  LevelMaterial(const Vec2& lo, const Vec2& hi, double cell);
  // Cells whose centre lies inside the region (even-odd over its loops) become `value` (1: material).
  void fill(const clip::Paths& region, uint8_t value);
  bool material(const Vec2& p) const {
    const long i = static_cast<long>(std::floor((p.x() - x0_) / cell_));
    const long j = static_cast<long>(std::floor((p.y() - y0_) / cell_));
    return i >= 0 && j >= 0 && i < nx_ && j < ny_ && bits_[size_t(j) * nx_ + i] != 0;
  }
  // Degrees of the leading half-circle (the half ahead of `dir`) of radius r around p that lies in material:
  // 180 for a full slot, acos(1 - ae / r) for a side cut of width ae, 0 in air.
  double engagement(const Vec2& p, const Vec2& dir, double r) const;
  // False only when no material lies within r of p (blocks of cells counted: a quick test before finer ones).
  bool near_material(const Vec2& p, double r) const;
  // No material cell centre within r of p.
  bool disc_clear(const Vec2& p, double r) const;
  // No material cell centre within r of the segment a-b.
  bool capsule_clear(const Vec2& a, const Vec2& b, double r) const;
  // Every cell whose centre lies within r of the segment a-b is cut.
  void cut_along(const Vec2& a, const Vec2& b, double r);
  double material_area() const;
  double cell() const { return cell_; }

 private:
  // Calls f(cell index) for the cells whose centre lies within r of the segment a-b until f returns false.
  template <class F>
  bool each_within(const Vec2& a, const Vec2& b, double r, const F& f) const;
  double x0_, y0_, cell_;
  long nx_, ny_;
  std::vector<uint8_t> bits_;
  // Material cells per block of kBlock x kBlock cells.
  static constexpr long kBlock = 16;
  long bx_ = 0, by_ = 0;
  std::vector<uint32_t> block_count_;
  void set(size_t c, uint8_t value);
};

}  // namespace rosmill::core
