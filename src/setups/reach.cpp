#include "rosmill/setups/reach.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "height_bound.hpp"
#include "rosmill/cutter/contact.hpp"
#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/plan/mesh_surface.hpp"

namespace rosmill::core::setups {
namespace {

// A sample stands this far off the surface (mm) when asked whether anything stands above it: a slope rising within
// the probe's radius (kProbe) of it cannot hold the probe above the sample then.
constexpr double kLift = 0.01;
constexpr double kProbe = 0.001;  // the radius of the flat probe that asks "anything above?"
// The cutter's axis stands this much farther from the surface than the cutter's radius, so that the shank's
// cylinder of the cutter's own radius grazes, not touches, a wall it runs along.
constexpr double kAxisClearance = 0.01;

// The height bound's cell: half the samples' spacing (a finer one answers few more questions), but between 1/1024
// and 1/128 of the part's longer side.
double bound_cell(const Mesh& turned, double spacing) {
  const double extent = std::max({turned.bbox.size().x(), turned.bbox.size().y(), 1e-3});
  return std::clamp(0.5 * spacing, extent / 1024, extent / 128);
}

// A probe: a flat cylinder of a radius asked whether anything stands above a height near a point, with the height
// bound grown to its radius (height_bound.hpp), which answers "nothing" for most questions before the exact drop.
struct Probe {
  CutterProfile cutter;
  std::vector<float> bound;
};

// The surface turned into the setup with the three probes it is asked with: a thin line over a sample, the shank
// and the holder. `bounded`: with the height bound (the part's many triangles), or the exact drop alone (a
// fixture's few boxes).
class ReachProbe {
 public:
  ReachProbe(const Mesh& turned, const ReachTool& tool, double spacing, bool bounded)
      : surface_(turned),
        bound_(bounded ? std::make_unique<HeightBound>(turned, bound_cell(turned, spacing),
                                                       std::max({kProbe, tool.shank_radius, tool.holder_radius}))
                       : nullptr),
        line_{CutterProfile(Cutter::flat(2 * kProbe)), grown(kProbe)},
        shank_{CutterProfile(Cutter::flat(2 * tool.shank_radius)), grown(tool.shank_radius)},
        holder_{CutterProfile(Cutter::flat(2 * tool.holder_radius)), grown(tool.holder_radius)} {}

  // Whether anything stands above z within the probe's radius of (x, y): the bound first, the exact drop when the
  // bound cannot tell.
  bool above(const Probe& probe, double x, double y, double z, uint32_t& hint) const {
    return (!bound_ || bound_->at(probe.bound, x, y) > z) && surface_.held_above_hinted(probe.cutter, x, y, z, hint);
  }
  const Probe& line() const { return line_; }
  const Probe& shank() const { return shank_; }
  const Probe& holder() const { return holder_; }

 private:
  std::vector<float> grown(double radius) const { return bound_ ? bound_->grown(radius) : std::vector<float>{}; }

  MeshSurface surface_;
  std::unique_ptr<HeightBound> bound_;
  Probe line_, shank_, holder_;
};

// Where the tool stands to touch a sample with normal n (setup frame): its axis and its tip's height.
struct ToolAt {
  Vec2 axis;
  double tip;
};

ToolAt tool_at(const ReachTool& t, const Vec3& p, const Vec3& n) {
  ToolAt at{p.head<2>(), p.z() + t.corner_radius * (n.z() - 1.0)};
  const double s = n.head<2>().norm();
  if (s > 1e-9) {
    const Vec2 out = n.head<2>() / s;
    // The corner's centre is the corner radius out along the normal; the axis the flat bottom's radius further.
    at.axis += t.corner_radius * n.head<2>() + (t.radius - t.corner_radius + kAxisClearance) * out;
  }
  return at;
}

}  // namespace

ReachTool reach_tool(const Tool& tool) {
  const Cutter& c = tool.cutter;
  ReachTool t;
  t.radius = c.radius();
  t.corner_radius = c.type == CutterType::FlatEnd ? 0.0 : c.type == CutterType::BallEnd ? c.radius() : c.corner_radius;
  t.flute_length = c.flute_length;
  t.shank_radius = 0.5 * c.shank_diameter;
  t.stick_out = tool.stick_out_mm();
  t.holder_radius = 0.5 * tool.holder_mm();
  return t;
}

std::vector<Reach> reach_along(const Mesh& part, const SurfaceSamples& samples, const SetupFrame& setup,
                               const ReachTool& tool, const std::vector<Vec3>& fixture_corners,
                               double max_angle_deg) {
  if (!(max_angle_deg > 0 && max_angle_deg <= 180)) throw Error("reach", "the largest angle must lie in (0, 180]");
  // The samples' spacing: the side of the square a sample's weight would be.
  double area = 0;
  for (double w : samples.weights) area += w;
  const double spacing = std::sqrt(area / std::max<size_t>(samples.size(), 1));
  const ReachProbe on_part(placed(part, setup.placement), tool, spacing, true);
  std::unique_ptr<ReachProbe> on_fixture;
  if (!fixture_corners.empty())
    on_fixture = std::make_unique<ReachProbe>(build_mesh(fixture_corners), tool, spacing, false);
  const double facing = std::cos(max_angle_deg * M_PI / 180.0) - 1e-9;
  std::vector<Reach> out(samples.size(), Reach::FacesAway);
  for_each_piece<size_t>(0, samples.size(), 1024, [&](size_t begin, size_t end) {
    uint32_t hints[6] = {0, 0, 0, 0, 0, 0};
    // Clear of the probe's surface: nothing over the sample, the shank's and the holder's way free.
    const auto clear = [&](const ReachProbe& s, const Vec3& p, const Vec3& n, const ToolAt& at, uint32_t* hint) {
      const Vec3 q = p + kLift * n;
      if (s.above(s.line(), q.x(), q.y(), q.z(), hint[0])) return false;
      if (tool.stick_out > tool.flute_length &&
          s.above(s.shank(), at.axis.x(), at.axis.y(), at.tip + tool.flute_length, hint[1]))
        return false;
      return !s.above(s.holder(), at.axis.x(), at.axis.y(), at.tip + tool.stick_out, hint[2]);
    };
    for (size_t k = begin; k < end; ++k) {
      const Vec3 n = setup.direction_to_setup(samples.normals[k]);
      if (n.z() < facing) continue;
      const Vec3 p = setup.to_setup_frame(samples.points[k]);
      const ToolAt at = tool_at(tool, p, n);
      if (!clear(on_part, p, n, at, hints))
        out[k] = Reach::Hidden;
      else if (on_fixture && !clear(*on_fixture, p, n, at, hints + 3))
        out[k] = Reach::Fixture;
      else
        out[k] = Reach::Reached;
    }
  });
  return out;
}

}  // namespace rosmill::core::setups
