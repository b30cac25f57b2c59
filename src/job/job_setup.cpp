#include "job_setup.hpp"

#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "rosmill/error.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/stock/design_height.hpp"
#include "rosmill/toolpath/toolpath_stats.hpp"

namespace rosmill::core::job {
namespace {

// The datum in the turned frame: the stock's top centre or its corner at the lowest x and y on top (the machinist
// sees the stock from the tool), or the part's own origin.
Vec3 datum_at(Datum datum, const Box3& stock) {
  switch (datum) {
    case Datum::Workpiece: return Vec3::Zero();
    case Datum::TopCentre: return Vec3(0.5 * (stock.min.x() + stock.max.x()), 0.5 * (stock.min.y() + stock.max.y()),
                                       stock.max.z());
    case Datum::Corner: return Vec3(stock.min.x(), stock.min.y(), stock.max.z());
  }
  return Vec3::Zero();
}

std::string face_down(const Vec3& direction) {
  const std::string n = setup_name_of(-direction);
  if (n != "custom") return n;
  char s[96];
  std::snprintf(s, sizeof s, "the side facing [%.3f, %.3f, %.3f]", -direction.x() + 0.0, -direction.y() + 0.0,
                -direction.z() + 0.0);
  return s;
}

// The setup's work offset: its datum on the machine, the stock centred over the machine's fixture position and
// standing on the fixture's seat above the table. The workpiece datum keeps G54 where it is (a registration's, or
// the controller's own).
std::optional<gcode::WorkOffset> work_offset_of(const SetupReport& s, size_t index, const JobOptions& o) {
  if (s.datum == Datum::Workpiece) return o.work_offset;
  gcode::WorkOffset w;
  w.index = static_cast<int>(index) + 1;
  const Vec2 at = o.checks.machine ? o.checks.machine->fixture_position : Vec2::Zero();
  const double table = o.checks.machine ? o.checks.machine->table_z : 0.0;
  const Vec2 centre = 0.5 * (s.stock.min.head<2>() + s.stock.max.head<2>());
  w.origin = Vec3(at.x() - centre.x(), at.y() - centre.y(), table - s.fixture.table_z);
  return w;
}


// The fixture's boxes grown by the check clearance, as the surface planning keeps clear of.
Mesh fixture_check_mesh(const fixture::Fixture& f) {
  std::vector<Vec3> corners;
  for (const fixture::FixtureBox& b : f.boxes) {
    Box3 grown = b.box;
    grown.min -= Vec3::Constant(kFixtureCheckClearance);
    grown.max += Vec3::Constant(kFixtureCheckClearance);
    const std::vector<Vec3> c = box_corners(grown);
    corners.insert(corners.end(), c.begin(), c.end());
  }
  return build_mesh(corners);
}

// The cells under the faces this setup finishes, and the heights they stand at in each: the samples setup
// selection gave the setup, and those it reaches within `overlap` of them (the band where the setups' finishes
// meet), projected into the setup's frame.
void finished_faces(const setups::SetupChoice& c, int chosen, const SetupFrame& frame, const stock::GridSpec& g,
                    double overlap, JobSetup& s_out) {
  s_out.faces.assign(g.cells(), 0);
  s_out.face_low.assign(g.cells(), INFINITY);
  s_out.face_high.assign(g.cells(), -INFINITY);
  if (chosen < 0) return;
  const setups::SurfaceSamples& s = c.samples;
  const uint64_t bit = uint64_t(1) << c.setups[size_t(chosen)].candidate;
  const double cell = std::max(overlap, 0.1);
  const auto key = [cell](const Vec3& p) {
    const auto q = [cell](double v) { return static_cast<int64_t>(std::floor(v / cell)) & 0x1fffff; };
    return q(p.x()) << 42 | q(p.y()) << 21 | q(p.z());
  };
  std::unordered_map<int64_t, std::vector<uint32_t>> own;
  for (size_t k = 0; k < s.size(); ++k)
    if (c.machined_by[k] == chosen) own[key(s.points[k])].push_back(static_cast<uint32_t>(k));
  const auto near_own = [&](const Vec3& p) {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = own.find(key(p + cell * Vec3(dx, dy, dz)));
          if (it == own.end()) continue;
          for (const uint32_t k : it->second)
            if ((s.points[k] - p).norm() <= overlap) return true;
        }
    return false;
  };
  double& area = s_out.report.finished_area;
  area = 0;
  for (size_t k = 0; k < s.size(); ++k) {
    const bool mine = c.machined_by[k] == chosen;
    if (!mine && !((c.reached[k] & bit) && overlap > 0 && near_own(s.points[k]))) continue;
    if (mine) area += s.weights[k];
    const Vec3 p = frame.to_setup_frame(s.points[k]);
    const double i = std::floor((p.x() - g.x0) / g.cell), j = std::floor((p.y() - g.y0) / g.cell);
    if (!(i >= 0 && j >= 0 && i < g.nx && j < g.ny)) continue;
    const size_t cell = g.index(int(i), int(j));
    s_out.faces[cell] = 1;
    s_out.face_low[cell] = std::min(s_out.face_low[cell], static_cast<float>(p.z()));
    s_out.face_high[cell] = std::max(s_out.face_high[cell], static_cast<float>(p.z()));
  }
}


// A setup on a 3-axis machine: the part turned over and clamped by the setup's fixture, the program's zero at the
// datum on the stock as it now is.
void clamp(SetupReport& r, const SetupSpec& spec, size_t index, const stock::InProcessStock& stock,
           const SetupContext& c, const std::string& where) {
  SetupFrame turned = direction_setup(spec.direction, where);
  turned.name = spec.name;
  turned.placement.parent = "setup " + spec.name;
  const Box3 held = stock.bounds_in(turned);
  if (held.empty()) throw Error(where, "no stock is left to hold");
  const Vec3 datum = datum_at(spec.datum, held);
  r.frame = turned.with_origin(datum);
  r.datum_point = turned.to_workpiece_frame(datum);
  r.stock = placed(held, Placement{r.frame.placement.parent, turned.placement.parent,
                                   Eigen::Isometry3d(Eigen::Translation3d(-datum))});
  r.fixture = fixture::place_fixture(spec.fixture, r.stock, where + " fixture");
  r.work_offset = work_offset_of(r, index, c.options);
}

// A setup on a trunnion: the part stays clamped as it stands on the table; A and C bring the setup's tool axis under
// the spindle, and the setup's frame is the machine's (identity kinematics: the program's coordinates).
void index_on_table(SetupReport& r, const SetupSpec& spec, const stock::InProcessStock& stock, TableSetting& table,
                    const std::string& where) {
  std::string why;
  const std::optional<machine::JointValues> q = table.machine->setup_joints(spec.direction, table.last, &why);
  if (!q) throw Error(where, "this machine cannot index the part for it: " + why);
  const machine::Index i = machine::index_of(*q);
  r.index = i;
  const Placement table_in_machine = table.trunnion().table_in_machine(i.a, i.c);
  r.frame.name = spec.name;
  r.frame.tool_axis = spec.direction.normalized();
  r.frame.placement = compose(table_in_machine, table.workpiece_on_table, where);
  check_setup(r.frame, where);
  r.datum = Datum::Workpiece;
  r.datum_point = r.frame.placement.point_back(Vec3::Zero());  // the program's zero: machine zero at this turn
  r.stock = stock.bounds_in(r.frame);
  r.fixture = table.fixture;
  // Each box's turned bounds (larger than the box where the turn is not by quarter turns: the check errs safe).
  for (fixture::FixtureBox& b : r.fixture.boxes) b.box = placed(b.box, table_in_machine);
  r.fixture.table_z = NAN;
  // The program's coordinates are the machine's: G54 at machine zero, set by the program itself.
  r.work_offset = gcode::WorkOffset{};
  r.face_down = face_down(Vec3::UnitZ());  // the part stands on the table as the workpiece frame has it
  table.last = *q;
}

}  // namespace

std::vector<float> fixture_tops(const fixture::Fixture& f, const stock::GridSpec& g) {
  std::vector<float> top(g.cells(), -INFINITY);
  const double half = 0.5 * g.cell;  // a cell whose square the box overlaps, not only its centre
  for (const fixture::FixtureBox& b : f.boxes)
    for (int j = g.first_y(b.box.min.y() - half); j <= g.last_y(b.box.max.y() + half); ++j)
      for (int i = g.first_x(b.box.min.x() - half); i <= g.last_x(b.box.max.x() + half); ++i) {
        float& t = top[g.index(i, j)];
        t = std::max(t, static_cast<float>(b.box.max.z()));
      }
  return top;
}

double indexing_seconds(const machine::Trunnion& t, const machine::Index& from, const machine::Index& to,
                        double from_z, double to_z, double rapid_feed, const Vec3& max_acceleration) {
  const auto vertical = [&](double dz) {
    return move_seconds(std::abs(dz), Vec3::UnitZ(), rapid_feed, max_acceleration);
  };
  const Vec3 turn(to.a - from.a, to.c - from.c, 0);
  const double angle = turn.norm();
  double seconds = vertical(t.safe_z - from_z) + vertical(t.safe_z - to_z);
  if (angle > 0) {
    // A rotary-only move: its "length" is in degrees, its feed the fastest both axes allow along it (degrees/min).
    const Vec3 dir = turn / angle;
    double feed = INFINITY;
    if (std::abs(dir.x()) > 0) feed = std::min(feed, 60.0 * t.a.velocity / std::abs(dir.x()));
    if (std::abs(dir.y()) > 0) feed = std::min(feed, 60.0 * t.c.velocity / std::abs(dir.y()));
    seconds += move_seconds(angle, dir, feed, Vec3(t.a.acceleration, t.c.acceleration, 0));
  }
  return seconds;
}

TableSetting place_on_table(const machine::Machine& machine, const fixture::FixtureSpec& fixture,
                            const stock::InProcessStock& stock, const JobOptions& o, const std::string& where) {
  TableSetting t;
  t.machine = &machine;
  t.last = machine.home();
  const Box3 raw = stock.bounds_in(SetupFrame{});
  const fixture::Fixture held = fixture::place_fixture(fixture, raw, where + " fixture");
  // The stock centred over the fixture position, on the fixture's seat over the table's top.
  const Vec2 at = o.checks.machine->fixture_position;
  const Vec3 shift(at.x() - 0.5 * (raw.min.x() + raw.max.x()), at.y() - 0.5 * (raw.min.y() + raw.max.y()),
                   o.checks.machine->table_z - held.table_z);
  t.workpiece_on_table = Placement{"table", kWorkpieceFrame, Eigen::Isometry3d(Eigen::Translation3d(shift))};
  t.fixture = held;
  for (fixture::FixtureBox& b : t.fixture.boxes) b.box = placed(b.box, t.workpiece_on_table);
  return t;
}

JobSetup begin_setup(const SetupSpec& spec, size_t index, const stock::InProcessStock& stock,
                     const SetupContext& c) {
  const std::string where = c.job.source + (spec.line ? ":" + std::to_string(spec.line) : "") + " setups[" +
                            std::to_string(index) + "] (" + spec.name + ")";
  JobSetup s;
  SetupReport& r = s.report;
  r.name = spec.name;
  r.direction = spec.direction;
  r.datum = spec.datum;
  r.face_down = face_down(spec.direction);
  if (c.table) index_on_table(r, spec, stock, *c.table, where);
  else clamp(r, spec, index, stock, c, where);

  s.part = placed(c.part, r.frame.placement);
  if (c.stock_mesh) s.stock_mesh = placed(*c.stock_mesh, r.frame.placement);
  s.part_surface = std::make_unique<MeshSurface>(s.part);
  if (!r.fixture.empty()) {
    s.fixture_surface = std::make_unique<MeshSurface>(fixture_check_mesh(r.fixture));
    s.checked = std::make_unique<CheckedSurface>(*s.part_surface, *s.fixture_surface);
  }
  s.grid = stock.setup_grid(r.frame);
  const stock::HeightField view = stock.view(r.frame);
  s.floor = view.bottom;
  s.design = stock::design_heights(s.part, s.grid, s.floor);
  s.design_high = stock::design_highest_in_cells(s.part, s.grid, s.floor, s.design);
  if (!r.fixture.empty()) s.fixture_top = fixture_tops(r.fixture, s.grid);
  if (c.faces) finished_faces(*c.faces, c.chosen, r.frame, s.grid, spec.overlap, s);
  return s;
}

}  // namespace rosmill::core::job
