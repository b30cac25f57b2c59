// Row kernels of the material removal simulation: the lowest cutter bottom a move passes over each cell of a row,
// and the update of the stock's cells from it. The loops are written without branches (selects and masks) so
// that the compiler vectorises them; CMakeLists.txt builds material_removal.cpp with -fno-math-errno
// -fno-trapping-math, without which a square root or a clamp stays a branch.
#pragma once
#include <cstdint>

#include "rosmill/stock/height_field.hpp"
#include "sweep_geometry.hpp"

namespace rosmill::core::stock::sweep {

// ---- cutter profiles: the bottom's height above the tip from the squared distance to the axis

struct FlatProfile {
  double operator()(double) const { return 0.0; }
};
struct BallProfile {
  double R, R2;
  double operator()(double d2) const { return R - sqrt0(R2 - d2); }
};
struct BullProfile {
  double flat, r, r2;  // flat bottom radius, corner radius
  double operator()(double d2) const {
    const double e = std::max(std::sqrt(d2) - flat, 0.0);
    return r - sqrt0(r2 - e * e);
  }
};

// Along (a) and across (b) coordinates of cell i of a row: linear in i.
struct RowFrame {
  double a0, da, b0, db;
  RowFrame(const LineFrame& f, const GridSpec& g, double y)
      : a0(f.a(g.cx(0), y)), da(g.cell * f.ux), b0(f.b(g.cx(0), y)), db(-g.cell * f.uy) {}
  double a(int i) const { return a0 + i * da; }
  double b(int i) const { return b0 + i * db; }
};

// The squared XY distance to the segment from a = 0 to a = L.
inline double axis_d2(const LineFrame& f, double a, double b) {
  const double s = a - clamp01(a * f.invL) * f.L;
  return s * s + b * b;
}

// ---- kernels: height(i, d2) is the lowest bottom over cell i; d2 the squared distance from the cell to the path

template <class Profile>
struct LevelLineRow {  // z constant: the nearest point of the segment is the lowest (a vertical move: its end)
  const LineFrame& f;
  RowFrame r;
  Profile prof;
  double height(int i, double& d2) const {
    d2 = axis_d2(f, r.a(i), r.b(i));
    return f.az + prof(d2);
  }
};

struct BallRampRow {  // the ball's lowest point over the cell, at the clamped stationary point of its bottom
  const LineFrame& f;
  RowFrame r;
  double R, R2;
  double height(int i, double& d2) const {
    const double a = r.a(i), b = r.b(i);
    const double w2 = R2 - b * b;  // the ball's section in the vertical plane along the move has radius W
    const double t = clamp01((a - f.kz * sqrt0(w2)) * f.invL);
    const double s = a - t * f.L;
    d2 = axis_d2(f, a, b);
    return f.az + R + t * f.uz - sqrt0(w2 - s * s);
  }
};

struct FlatRampRow {  // the flat bottom is lowest at the lower end of the part of the ramp over the cell
  const LineFrame& f;
  RowFrame r;
  double R2;
  double height(int i, double& d2) const {
    const double a = r.a(i), b = r.b(i);
    const double w = sqrt0(R2 - b * b), lead = f.uz > 0 ? -w : w;
    d2 = axis_d2(f, a, b);
    return f.az + clamp01((a + lead) * f.invL) * f.uz;
  }
};

// A bull nose on a ramp, exactly: the lowest bottom over a point along a segment is the drop-cutter contact with
// the segment mirrored in z (the min of z + h is minus the max of -z - h), which the cutter area solves.
struct BullRampRow {
  const LineFrame& f;
  RowFrame r;
  const CutterProfile& cp;
  double mirrored[2][3];
  double x0, cell, y;
  BullRampRow(const LineFrame& fr, const GridSpec& g, double row_y, const CutterProfile& c)
      : f(fr), r(fr, g, row_y), cp(c),
        mirrored{{fr.ax, fr.ay, -fr.az}, {fr.ax + fr.L * fr.ux, fr.ay + fr.L * fr.uy, -(fr.az + fr.uz)}},
        x0(g.cx(0)), cell(g.cell), y(row_y) {}
  double height(int i, double& d2) const {
    d2 = axis_d2(f, r.a(i), r.b(i));
    const double x = x0 + i * cell;
    return -std::max({vertex_contact(cp, x, y, mirrored[0]), vertex_contact(cp, x, y, mirrored[1]),
                      edge_contact(cp, x, y, mirrored[0], mirrored[1])});
  }
};

template <class Profile>
struct LevelArcRow {
  const ArcFrame& a;
  double ex0, dex, ey, R2;
  Profile prof;
  double height(int i, double& d2) const {
    const double ex = ex0 + i * dex;
    const double c0 = a.s0x * ey - a.s0y * ex, c1 = ex * a.s1y - ey * a.s1x;
    const bool inside = a.full | (a.small ? (c0 >= 0) & (c1 >= 0) : (c0 >= 0) | (c1 >= 0));
    const double radial = std::sqrt(ex * ex + ey * ey) - a.rho;
    const double px = ex - a.s0x, py = ey - a.s0y, qx = ex - a.s1x, qy = ey - a.s1y;
    d2 = inside ? radial * radial : std::min(px * px + py * py, qx * qx + qy * qy);
    return d2 <= R2 ? a.z + prof(d2) : kInf;
  }
};

// ---- the update of one row's cells from a kernel

struct Target {
  float* top;
  uint32_t* cut_by;
  float* trace;  // finishing axis distances, or null when this move is not a finishing move
  uint32_t id;
  double reach_d2;  // R^2: cells further from the path than R are not under the cutter
  float trace_d2;   // the trace records distances up to this
};

// Lowers the cells [i0, i1] of the row starting at `base` where the kernel's bottom is below them; returns how
// many it lowered.
template <bool Trace, class Kernel>
uint32_t update_row(const Kernel& k, int i0, int i1, size_t base, const Target& t) {
  float* top = t.top + base;
  uint32_t* cut_by = t.cut_by + base;
  float* trace = Trace ? t.trace + base : nullptr;
  const uint32_t id = t.id;
  const float reach = t.trace_d2;
  const double R2 = t.reach_d2;
  uint32_t lowered = 0;
  for (int i = i0; i <= i1; ++i) {
    double d2;
    const double bottom = k.height(i, d2);
    const float h = static_cast<float>(d2 <= R2 ? bottom : kInf);
    const float old = top[i];
    const uint32_t mask = 0u - static_cast<uint32_t>(h < old);
    top[i] = h < old ? h : old;
    cut_by[i] = (cut_by[i] & ~mask) | (id & mask);
    lowered += mask & 1u;
    if constexpr (Trace) {
      const float d = static_cast<float>(d2);
      trace[i] = d < trace[i] && d <= reach ? d : trace[i];
    }
  }
  return lowered;
}

template <class Kernel>
uint32_t update(const Kernel& k, int i0, int i1, size_t base, const Target& t) {
  return t.trace ? update_row<true>(k, i0, i1, base, t) : update_row<false>(k, i0, i1, base, t);
}

}  // namespace rosmill::core::stock::sweep
