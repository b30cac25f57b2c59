// An independent account of the material written programs leave on a part, for checking the job's own
// (job/surface_account.hpp) — it shares no code with the stock model, its removal kernels or rosmill's G-code
// reader.
//
// Each program is read by LinuxCNC's own interpreter (`rs274 -g`): its canonical moves, in the program's
// coordinates, with the tool changes; arcs become chords within 0.1 um. Its moves are swept as swept_check.hpp
// sweeps a cutter along a line (the least height of the cutter's bottom over a point, by golden-section search of a
// convex function), mapped back through the program's frame. The design's surface is sampled afresh (uniform random
// points on every facet, a fixed seed). The material left at a sample is how far the stock box runs along the
// outward normal, uncut, before it is cut away, leaves the box, or meets the part again (the part's facets tested
// one by one); a sample the moves cut into is a gouge, its depth.
#pragma once
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core {

struct SweptCutter {
  CutterType type = CutterType::FlatEnd;
  double radius = 3, corner_radius = 0;  // mm
};

// One written program and how its coordinates sit on the part.
struct SweptProgram {
  std::string path;
  Eigen::Isometry3d workpiece_to_program = Eigen::Isometry3d::Identity();
  std::map<int, SweptCutter> tools;  // by T number
};

struct SweepSample {
  Vec3 point = Vec3::Zero(), normal = Vec3::Zero();  // workpiece frame
  uint32_t facet = 0;
  double area = 0;                                  // mm^2 it stands for
  double left = 0;                                  // mm along the normal (negative: cut that deep into the part)
};

struct SweepCheck {
  std::vector<SweepSample> samples;
  size_t moves = 0;
};

// Samples about `spacing` apart over the part; at each, the material left, followed out to at most `reach` mm
// (`step` apart, then halved to 1e-4 mm). Throws std::runtime_error when rs274 refuses a program.
SweepCheck sweep_programs(const Mesh& part, const Box3& stock, const std::vector<SweptProgram>& programs,
                          double spacing, double step = 0.1, double reach = 50);

}  // namespace rosmill::core
