// Independent checks of a planned toolpath against the part, for the test_plan_* tests: every cutter location and
// points along every move, each against the reference drop over all triangles (cutter/reference_drop, which
// shares no code with the drop-cutter the planner uses). The allowance is applied here by growing the cutter
// by hand, not through the planner's offset_cutter.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "rosmill/testing/reference_drop.hpp"
#include "rosmill/testing/sanitized.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::core::test {

// Feed moves and rapids are sampled at most this far apart (mm), besides their end points.
constexpr double kAlongMoveStep = 0.1;
// The gouge tolerance (mm).
constexpr double kGougeTolerance = 0.001;

// The cutter whose surface lies `allowance` outside the given one's: every radius larger by it.
inline Cutter grown_by_hand(const Cutter& c, double allowance) {
  Cutter g = c;
  g.diameter = c.diameter + 2 * allowance;
  if (c.type == CutterType::BallEnd) g.corner_radius = 0.5 * g.diameter;
  if (c.type == CutterType::FlatEnd && allowance > 0) g.type = CutterType::BullNose, g.corner_radius = allowance;
  if (c.type == CutterType::BullNose) g.corner_radius = c.corner_radius + allowance;
  return g;
}

struct GougeReport {
  size_t cl_points = 0;       // move end points checked
  size_t along_points = 0;    // points between them
  size_t rapid_points = 0;
  size_t gouges = 0;          // feed points deeper than the tolerance into part + allowance
  size_t rapid_hits = 0;      // rapid points inside the part
  double worst = 0;           // the largest vertical depth (reference drop - tip) among the gouges, mm
  Vec3 worst_at = Vec3::Zero();
  Vec3 rapid_hit_at = Vec3::Zero();

  std::string str() const {
    std::ostringstream s;
    s << cl_points << " CL + " << along_points << " along moves + " << rapid_points << " on rapids; " << gouges
      << " gouges";
    if (gouges) s << " (worst vertical depth " << worst << " at " << worst_at.transpose() << ")";
    s << ", " << rapid_hits << " rapid points in the part";
    if (rapid_hits) s << " (e.g. " << rapid_hit_at.transpose() << ")";
    return s.str();
  }
};

// Every position the cutter passes (move ends and points at most `step` apart along each move) against the
// reference: a feed position is a gouge when part + allowance lies deeper than the tolerance inside the cutter
// (the cutter grown by the allowance, its tip lowered by it, eroded by the tolerance still meets the mesh); a
// rapid position is a hit when the cutter itself goes into the part at all.
inline GougeReport check_toolpath(const Toolpath& tp, const Mesh& mesh, double allowance,
                                  double step = kAlongMoveStep, double tolerance = kGougeTolerance) {
  struct Sample {
    Vec3 p;
    bool rapid, end;
  };
  std::vector<Sample> samples;
  Vec3 at = tp.start;
  for (const ToolpathPass& pass : tp.passes)
    for (const Move& m : pass.moves) {
      const int n = std::max(1, static_cast<int>(std::ceil((m.to - at).norm() / step)));
      for (int k = 1; k <= n; ++k)
        samples.push_back({at + (m.to - at) * (double(k) / n), m.type == MoveType::Rapid, k == n});
      at = m.to;
    }
  const Cutter grown = grown_by_hand(tp.tool.cutter, allowance);
  const Vec3 down(0, 0, allowance);
  rosmill::testing::thin_reference_samples(samples);  // every 16th under the sanitizers
  std::vector<char> bad(samples.size());
  tbb::parallel_for(size_t(0), samples.size(), [&](size_t i) {
    const Sample& s = samples[i];
    bad[i] = s.rapid ? reference_gouges(tp.tool.cutter, mesh, s.p, 0.0)
                     : reference_gouges(grown, mesh, s.p - down, tolerance);
  });
  GougeReport r;
  for (size_t i = 0; i < samples.size(); ++i) {
    const Sample& s = samples[i];
    if (s.rapid) {
      ++r.rapid_points;
      if (bad[i] && r.rapid_hits++ == 0) r.rapid_hit_at = s.p;
      continue;
    }
    (s.end ? r.cl_points : r.along_points)++;
    if (!bad[i]) continue;
    ++r.gouges;
    const double depth = reference_drop(grown, mesh, s.p.x(), s.p.y()) - (s.p.z() - allowance);
    if (depth > r.worst) r.worst = depth, r.worst_at = s.p;
  }
  return r;
}

// The gouge assertions every strategy test makes (the tolerance is the one the toolpath was planned with).
inline void expect_no_gouge(const Toolpath& tp, const Mesh& mesh, double allowance, const std::string& what,
                            double tolerance = kGougeTolerance, double step = kAlongMoveStep) {
  const GougeReport r = check_toolpath(tp, mesh, allowance, step, tolerance);
  SCOPED_TRACE(what + ": " + r.str());
  EXPECT_GT(r.cl_points, 0u);
  EXPECT_EQ(r.gouges, 0u) << "the cutter goes deeper than the tolerance into the part plus allowance";
  EXPECT_EQ(r.rapid_hits, 0u) << "a rapid passes through the part";
  std::printf("  %s: %s\n", what.c_str(), r.str().c_str());
}

}  // namespace rosmill::core::test
