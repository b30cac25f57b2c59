#include "rosmill/job/surface_account.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "rosmill/geometry/mesh_ray.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/parallel.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/plan/plan_params.hpp"
#include "rosmill/plan/tool_body_surface.hpp"
#include "rosmill/segment/surface_patches.hpp"
#include "rosmill/stock/material_along.hpp"

namespace rosmill::core::job {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// How near to one another the stock's point queries are read from one gathering of the moves (StockProbe): about a
// march step, so that a run followed out gathers once a step and its halving reads from the last.
constexpr double kProbeRadius = 0.25;
// The finest finish the account holds a face to (mm): the verifier's own resolution of a gouge. A plan's chord
// tolerance is often finer (1 um by default), but the design's facets themselves leave a cutter that much at their
// joints: a 6 mm end mill in an 8 mm hole of 48 facets cannot come nearer than 6 um to its corners.
constexpr double kFinestFinish = 0.01;

// What the job asked of one setup's faces: its finishing operations' least allowance, with their largest tolerance
// and scallop, and their tools.
struct SetupAsk {
  bool finishing = false;
  double allowance = kInf, tolerance = 0, scallop = 0;
  std::vector<Tool> tools;
};

std::vector<SetupAsk> asks_of(const AccountInput& in) {
  std::vector<SetupAsk> out(in.setups.size());
  for (const AccountOperation& op : in.operations) {
    if (!op.finishing || op.setup >= out.size()) continue;
    SetupAsk& a = out[op.setup];
    a.finishing = true;
    a.allowance = std::min(a.allowance, op.allowance);
    a.tolerance = std::max({a.tolerance, op.tolerance, kFinestFinish});
    a.scallop = std::max(a.scallop, op.scallop);
    a.tools.push_back(op.tool);
  }
  return out;
}

// The part and the fixture in each setup's frame, as a tool touching a face there would meet them: the part as each
// finishing tool's whole body meets it (its shank and holder too).
struct SetupSolids {
  Mesh part, fixture;
  std::unique_ptr<MeshSurface> part_surface, fixture_surface;
  std::vector<std::unique_ptr<ToolBodySurface>> bodies;  // per tool of the setup's SetupAsk
  double table_z = NAN;   // the machine table's top (no tip goes below it); NaN: not known (a trunnion's turns)
};

Mesh fixture_mesh(const fixture::Fixture& f) {
  std::vector<Vec3> corners;
  for (const fixture::FixtureBox& b : f.boxes) {
    const std::vector<Vec3> c = box_corners(b.box);
    corners.insert(corners.end(), c.begin(), c.end());
  }
  return build_mesh(corners);
}

// The finishing cutter touching the face at p (normal n, both in the setup's frame) from above: the axis and the tip
// of the cutter whose surface meets p with the face's normal (a torus's tube centre at p + r n, its axis R - r
// further out across the face), moved `clear` off the face.
void touching(const Cutter& c, const Vec3& p, const Vec3& n, double clear, Vec2& axis, double& tip) {
  const double R = c.radius();
  const double r = c.type == CutterType::FlatEnd ? 0.0 : c.type == CutterType::BallEnd ? R : c.corner_radius;
  const Vec2 across = n.head<2>().norm() > 1e-9 ? Vec2(n.head<2>().normalized()) : Vec2::Zero();
  const Vec3 tube = p + (r + clear) * n;
  axis = tube.head<2>() + (R - r) * across;
  tip = tube.z() - r;
}

// Why the material at a sample of a setup's face stays: the fixture or the part holds every finishing cutter off
// it, or neither does (the operations could have reached it).
LeftReason why_left(const SetupAsk& ask, const SetupSolids& solids, const Vec3& p, const Vec3& n, double tolerance) {
  if (n.z() < -1e-6) return LeftReason::ToolDoesNotFit;  // faces away from the tool
  bool fixture = false;
  for (size_t t = 0; t < ask.tools.size(); ++t) {
    const Cutter& c = ask.tools[t].cutter;
    Vec2 axis;
    double tip;
    touching(c, p, n, 0.5 * tolerance, axis, tip);
    if (tip < solids.table_z - tolerance) continue;  // the table holds it off: a ball's corner at a wall's foot
    if (solids.bodies[t]->held_above(c, axis.x(), axis.y(), tip + tolerance)) continue;
    if (solids.fixture_surface && solids.fixture_surface->held_above(c, axis.x(), axis.y(), tip + tolerance)) {
      fixture = true;
      continue;
    }
    return LeftReason::StrategyLeftIt;
  }
  return fixture ? LeftReason::Fixture : LeftReason::ToolDoesNotFit;
}

// One sample's account.
struct SampleLeft {
  double left = 0;       // mm (negative: gouged that deep)
  int setup = -1;        // the job's setup that machines it
  FaceVerdict verdict = FaceVerdict::NotAsked;
  double allowance = 0, limit = 0;
  LeftReason reason = LeftReason::StrategyLeftIt;
};

class Sampler {
 public:
  Sampler(const AccountInput& in, const MeshRays& rays) : in_(in), rays_(rays), asks_(asks_of(in)) {}

  // How far the material runs from the face along n (stock/material_along.hpp).
  double thickness(const Vec3& p, const Vec3& n, double probe, stock::StockProbe& stock) const {
    return stock::material_thickness(stock, *in_.stock, rays_, p, n, probe, in_.march_step);
  }

  // How deep a cut went into the part under p (0: none beyond `tolerance`).
  double gouge(const Vec3& p, const Vec3& n, double tolerance, stock::StockProbe& s) const {
    return stock::gouge_under(s, p, n, tolerance, in_.march_step);
  }

  SampleLeft sample(size_t k, const std::vector<SetupSolids>& solids, stock::StockProbe& stock) const {
    const setups::SetupChoice& c = *in_.choice;
    const Vec3& p = c.samples.points[k];
    const Vec3 n = c.samples.normals[k].normalized();
    SampleLeft out;
    const int by = c.machined_by[k];
    out.setup = by >= 0 && size_t(by) < in_.job_setup.size() ? in_.job_setup[size_t(by)] : -1;
    const setups::Unmachined why = c.unmachined.empty() ? setups::Unmachined::No : c.unmachined[k];
    const SetupAsk* ask = out.setup >= 0 ? &asks_[size_t(out.setup)] : nullptr;
    // What this sample is to be finished to: its setup's finishing, else (a whole part asked for) the least any
    // finishing of the job asks.
    const SetupAsk* rule = ask && ask->finishing ? ask : nullptr;
    if (!rule && in_.whole_part && why != setups::Unmachined::Held)
      for (const SetupAsk& a : asks_)
        if (a.finishing && (!rule || a.allowance < rule->allowance)) rule = &a;
    const double tolerance = rule ? rule->tolerance : kDefaultTolerance;
    out.allowance = rule ? rule->allowance : 0.0;
    out.limit = rule ? rule->allowance + rule->tolerance + rule->scallop : 0.0;
    const double g = gouge(p, n, tolerance, stock);
    out.left = g > 0 ? -g : thickness(p, n, out.limit + 1e-9, stock);
    if (!rule) return out;
    const bool asked = (ask && ask->finishing) || (in_.whole_part && out.setup < 0);
    if (!asked) return out;
    out.verdict = out.left <= out.limit + 1e-9 ? FaceVerdict::Within : FaceVerdict::Above;
    if (out.verdict == FaceVerdict::Within) return out;
    if (out.setup < 0) {
      out.reason = why == setups::Unmachined::Fixture ? LeftReason::Fixture : LeftReason::NoSetup;
    } else if (!ask->finishing) {
      out.reason = LeftReason::NoSetup;
    } else {
      const SetupFrame& f = in_.setups[size_t(out.setup)].frame;
      out.reason = why_left(*ask, solids[size_t(out.setup)], f.to_setup_frame(p), f.direction_to_setup(n),
                            tolerance);
    }
    return out;
  }

 private:
  const AccountInput& in_;
  const MeshRays& rays_;
  std::vector<SetupAsk> asks_;
};

}  // namespace

const char* verdict_name(FaceVerdict v) {
  switch (v) {
    case FaceVerdict::Within: return "within";
    case FaceVerdict::Above: return "above";
    case FaceVerdict::NotAsked: return "not asked";
  }
  return "";
}

const char* reason_name(LeftReason r) {
  switch (r) {
    case LeftReason::NoSetup: return "no setup";
    case LeftReason::Fixture: return "fixture";
    case LeftReason::ToolDoesNotFit: return "tool does not fit";
    case LeftReason::StrategyLeftIt: return "strategy left it";
  }
  return "";
}

LeftReason FaceLeft::main_reason() const {
  return static_cast<LeftReason>(std::max_element(reason_area, reason_area + kLeftReasons) - reason_area);
}

double nominal_scallop(const Cutter& cutter, const std::string& strategy, double stepover, double stepdown) {
  const double step = strategy == "raster" ? stepover : strategy == "waterline" ? stepdown : NAN;
  if (!(step > 0) || cutter.type == CutterType::FlatEnd) return 0.0;
  const double R = cutter.radius();
  const double r = cutter.type == CutterType::BallEnd ? R : cutter.corner_radius;
  // A raster's bull nose rides its flat bottom across a level face: only a stepover beyond it leaves a cusp.
  const double flat = strategy == "raster" && cutter.type == CutterType::BullNose ? 2 * (R - r) : 0.0;
  const double half = 0.5 * std::max(0.0, step - flat);
  return half >= r ? r : r - std::sqrt(r * r - half * half);
}

SurfaceAccount account_surface(const AccountInput& in) {
  const auto t0 = std::chrono::steady_clock::now();
  SurfaceAccount a;
  const Mesh& part = *in.part;
  const setups::SetupChoice& c = *in.choice;
  const segment::SurfacePatches patches = segment::segment_surface(part);
  std::vector<SetupSolids> solids(in.setups.size());
  const std::vector<SetupAsk> asks = asks_of(in);
  for (size_t s = 0; s < in.setups.size(); ++s) {
    solids[s].part = placed(part, in.setups[s].frame.placement);
    solids[s].part_surface = std::make_unique<MeshSurface>(solids[s].part);
    for (const Tool& t : asks[s].tools)
      solids[s].bodies.push_back(std::make_unique<ToolBodySurface>(*solids[s].part_surface, t));
    solids[s].table_z = in.setups[s].fixture.table_z;
    if (!in.setups[s].fixture.empty()) {
      solids[s].fixture = fixture_mesh(in.setups[s].fixture);
      solids[s].fixture_surface = std::make_unique<MeshSurface>(solids[s].fixture);
    }
  }
  const MeshRays rays(part);
  const Sampler sampler(in, rays);
  std::vector<SampleLeft> left(c.samples.size());
  for_each_piece<size_t>(0, left.size(), 64, [&](size_t b, size_t e) {
    stock::StockProbe probe(*in.stock, kProbeRadius);
    for (size_t k = b; k < e; ++k) left[k] = sampler.sample(k, solids, probe);
  });

  a.faces.resize(patches.count());
  std::vector<std::vector<double>> setup_area(patches.count(), std::vector<double>(in.setups.size() + 1, 0.0));
  for (size_t f = 0; f < patches.count(); ++f) {
    const segment::Patch& patch = patches.patch(f);
    FaceLeft& face = a.faces[f];
    face.face = static_cast<uint32_t>(f);
    face.normal = patch.normal;
    face.facets.assign(patches.facets_begin(patch), patches.facets_begin(patch) + patch.facet_count);
    face.min_left_mm = kInf;
    face.max_left_mm = -kInf;
  }
  std::vector<uint8_t> asked(patches.count(), 0);
  for (size_t k = 0; k < left.size(); ++k) {
    const SampleLeft& s = left[k];
    const double w = c.samples.weights[k];
    const Vec3& p = c.samples.points[k];
    FaceLeft& face = a.faces[patches.label(c.samples.facets[k])];
    face.area += w;
    face.centroid += w * p;
    setup_area[face.face][s.setup < 0 ? in.setups.size() : size_t(s.setup)] += w;
    if (s.left < face.min_left_mm) face.min_left_mm = s.left, face.least_at = p;
    if (s.left > face.max_left_mm) face.max_left_mm = s.left, face.most_at = p;
    if (s.verdict == FaceVerdict::NotAsked) continue;
    if (!asked[face.face]) face.allowance = s.allowance, face.limit = s.limit;
    face.allowance = std::min(face.allowance, s.allowance);
    face.limit = std::max(face.limit, s.limit);
    asked[face.face] = 1;
    if (s.verdict == FaceVerdict::Above) {
      face.above_area += w;
      face.above_centroid += w * p;
      face.reason_area[static_cast<int>(s.reason)] += w;
    }
  }
  a.samples = left.size();
  a.min_left_mm = kInf;
  a.max_left_mm = -kInf;
  double any_min = kInf, any_max = -kInf;  // over every face, for a job that was to finish none
  for (FaceLeft& face : a.faces) {
    if (face.area > 0) face.centroid /= face.area;
    const std::vector<double>& by = setup_area[face.face];
    const size_t best = std::max_element(by.begin(), by.end()) - by.begin();
    face.setup = best == in.setups.size() || by[best] == 0 ? -1 : static_cast<int>(best);
    if (face.area == 0) face.min_left_mm = face.max_left_mm = 0;
    if (face.area > 0) any_min = std::min(any_min, face.min_left_mm), any_max = std::max(any_max, face.max_left_mm);
    if (!asked[face.face]) continue;
    ++a.asked_faces;
    face.verdict = face.above_area > 0 ? FaceVerdict::Above : FaceVerdict::Within;
    if (face.above_area > 0) {
      face.above_centroid /= face.above_area;
      a.unfinished_area += face.above_area;
      ++a.unfinished_faces;
    }
    a.min_left_mm = std::min(a.min_left_mm, face.min_left_mm);
    a.max_left_mm = std::max(a.max_left_mm, face.max_left_mm);
  }
  if (a.min_left_mm > a.max_left_mm) a.min_left_mm = any_min, a.max_left_mm = any_max;  // none was to be finished
  if (a.min_left_mm > a.max_left_mm) a.min_left_mm = a.max_left_mm = 0;
  a.done = true;
  a.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return a;
}

}  // namespace rosmill::core::job
