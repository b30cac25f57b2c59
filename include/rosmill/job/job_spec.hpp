// A job as a YAML file describes it: the part, the raw stock, and its setups in machining order, each with how the
// part is held (its fixture), its datum (the program's zero, where the setup's work offset G54..G59 lies) and its
// operations. Every field is checked when the file is read; a bad one is an Error naming the file, its line and
// the field.
//
//   part: data/pocket.stl     # STL (relative to the job file's folder) or primitive:NAME
//   units: mm                 # what the part's (and a stock mesh's) numbers are: mm, inch or m
//   resolution: 0.5           # the stock's cell in mm
//   rapid_feed: 5000          # mm/min, for the time estimate
//   stock: {mesh: data/pocket_casting.stl}   # or {box: {margin: 5}} or {cloud: scan.pcd, table_z: 0, units: m}
//   fixture: {vise: {jaw_width: 100, jaw_height: 25, grip: 5, clamp: y}}   # every setup's, unless it gives its own
//   datum: top-centre         # or corner (of the stock, seen from the tool) or workpiece (the part's own origin)
//   overlap: 1                # mm a setup's finishing reaches beyond its own faces, so that the seams blend
//   setups:
//     - name: top
//       direction: +Z         # or [x, y, z]: the tool axis in the part's frame
//       operations:
//         - {name: rough, strategy: rough, tool: 1, stepover: 4, stepdown: 2, allowance: 0.5}
//         - {name: finish, strategy: raster, tool: 5, stepover: 1}
//     - direction: -Y
//       fixture: {vise: {clamp: x, grip: 4}}
//       operations: [{strategy: waterline, tool: 5, stepdown: 1}]
//
// `accept_unfinished: true` lets a job that leaves a face it was to finish above its limit pass (its report still
// lists the face, the material left and why).
// `held_face: -Z` names the face the part is held by in every setup (never machined). `setups: auto` chooses the
// setups (setups/setup_choice.hpp) with `auto: {tool, min_gain}`, and runs the top-level `operations` in each. A job in the older form has `operations`
// only, each with an optional `setup` (+Z, -X, ...): consecutive operations of one setup are that setup, and every
// operation works over the whole part.
#pragma once
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "rosmill/fixture/fixture.hpp"
#include "rosmill/geometry/types.hpp"
#include "rosmill/units.hpp"

namespace rosmill::core::job {

struct StockSpec {
  enum class Kind { Box, Mesh, Cloud } kind = Kind::Box;
  double margin = 5.0;   // box: the part's bounding box grown by this in x, y and up (mm)
  std::string file;      // mesh or cloud, absolute
  Units units = Units::Millimetre;  // cloud: what its numbers are
  double table_z = 0.0;  // cloud: the table the scanned stock stands on (mm, workpiece frame)
};

struct OperationSpec {
  std::string name;
  std::string strategy;  // a strategy or preset of the planner
  std::string tool;      // a tool id of the tool table, or ball:D, flat:D, bull:D:r
  double stepover = NAN, stepdown = NAN, allowance = 0.0, tolerance = NAN;
  // The direction of the raster's and the roughing's lines in the setup's frame (degrees from its X; NaN: the
  // strategy's own). Lines across a slot reach its walls' feet exactly; lines along it leave up to a stepover there.
  double angle = NAN;
  double engagement = NAN;  // adaptive: largest radial engagement, degrees (NaN: from the stepover)
  std::string setup = "+Z";  // the name of its setup
  size_t setup_index = 0;    // into JobSpec::setups
  // Rest machining: only where the stock the operations before left stands above the design by more than the
  // allowance plus rest_threshold (mm).
  bool rest = false;
  double rest_threshold = 0.1;
  int line = 0;          // where it starts in the job file
};

// Where a setup's program has its zero: the stock's top centre or its corner at the lowest x and y on top (as the
// tool sees the stock in that setup), or the part's own origin turned into the setup.
enum class Datum { Workpiece, TopCentre, Corner };
const char* datum_name(Datum datum);

struct SetupSpec {
  std::string name;                 // the job's name for it, else the direction's ("+Z", "custom")
  Vec3 direction = Vec3::UnitZ();   // unit tool axis, workpiece frame
  fixture::FixtureSpec fixture;
  Datum datum = Datum::TopCentre;
  double overlap = 1.0;             // mm
  int line = 0;
};

struct AutoSetups {
  std::string tool;                 // whose reach counts; empty: the last operation's
  std::optional<Vec3> held_face;    // outward normal of the face the part is held by (never machined), workpiece frame
  double min_gain = 0.005;
};

struct JobSpec {
  std::string source;  // the job file
  std::string part;    // absolute path or primitive:NAME
  Units units = Units::Millimetre;
  double resolution = 0.5;
  double rapid_feed = 5000.0;
  StockSpec stock;
  std::vector<SetupSpec> setups;         // in machining order (chosen by run_job with auto_setups)
  bool auto_setups = false;
  AutoSetups auto_options;
  SetupSpec setup_defaults;              // the fixture, datum and overlap of setups that give none
  // Each setup's finishing keeps to the faces the setup machines (plus the overlap): false in the older form,
  // where every operation works over the whole part.
  bool finish_by_setup = true;
  std::vector<OperationSpec> operations;  // in machining order; with auto_setups, each chosen setup's
  // A face the job was to finish that it leaves above its limit (job/surface_account.hpp) fails the job (its report
  // says so, `rosmill job` exits with status 4, the PlanJob action does not succeed) unless this is true.
  bool accept_unfinished = false;
};

JobSpec read_job(const std::string& path);
// The same from text; `name` stands for the file in errors and `folder` is where relative paths start.
JobSpec parse_job(const std::string& text, const std::string& name, const std::string& folder);

// A setup for `direction` with the job's defaults (a chosen one, with auto_setups).
SetupSpec default_setup(const JobSpec& job, const Vec3& direction);

}  // namespace rosmill::core::job
