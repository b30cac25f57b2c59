// What a setup's operations share, made once when the setup begins (private to the job area): the part turned into
// the setup's frame, its datum and fixture placed on the stock as it then is, the setup's work offset on the
// machine, the surface its operations plan on (the part, the fixture kept clear of), and the design's heights and
// the faces the setup finishes on the grid of the stock's view from the setup.
#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "rosmill/job/run_job.hpp"
#include "rosmill/machine/machine.hpp"
#include "rosmill/plan/checked_surface.hpp"
#include "rosmill/plan/mesh_surface.hpp"
#include "rosmill/setups/setup_choice.hpp"

namespace rosmill::core::job {

// Planning keeps the cutter this far (mm) from the fixture's boxes, beyond the allowance: a path that touches a jaw
// is a collision on the machine, whatever the model's rounding.
constexpr double kFixtureCheckClearance = 1.0;

struct JobSetup {
  SetupReport report;
  Mesh part;                           // the design in the setup's frame
  std::optional<Mesh> stock_mesh;      // a cast stock, turned
  std::unique_ptr<MeshSurface> part_surface, fixture_surface;
  std::unique_ptr<CheckedSurface> checked;  // the part with the fixture kept clear of (null without a fixture)
  stock::GridSpec grid;                // of the stock's view from the setup
  double floor = 0;                    // the view's lowest height
  std::vector<float> design, design_high;  // the design's centre height and highest per cell (floor where none)
  std::vector<float> fixture_top;      // per cell (-infinity where none; empty without a fixture)
  std::vector<uint8_t> faces;          // per cell: the faces this setup finishes (empty: the whole part)
  std::vector<float> face_low, face_high;  // per cell: the heights those faces stand at there

  const Surface& surface() const { return checked ? static_cast<const Surface&>(*checked) : *part_surface; }
};

// The part on a machine that turns it between setups (a trunnion table, 3+2): clamped once, standing on the table
// centred over the machine's fixture position, turned by the machine's joints from setup to setup.
struct TableSetting {
  const machine::Machine* machine = nullptr;
  Placement workpiece_on_table;        // "table" <- "workpiece"
  fixture::Fixture fixture;            // in the table's frame
  machine::JointValues last;           // where the joints are when the next setup begins

  const machine::Trunnion& trunnion() const { return *machine->trunnion(); }
};

struct SetupContext {
  const JobSpec& job;
  const JobOptions& options;
  const Mesh& part;
  const Mesh* stock_mesh;
  // Who finishes what (setup selection's assignment), and which of its setups this one is (-1: none of them, the
  // setup finishes no face); null: the whole part.
  const setups::SetupChoice* faces = nullptr;
  int chosen = 0;
  TableSetting* table = nullptr;  // a trunnion's (null: each setup clamped on a 3-axis machine)
};

// Per cell of the grid, the top of the fixture over its square (-infinity where none).
std::vector<float> fixture_tops(const fixture::Fixture& f, const stock::GridSpec& g);

// The part clamped on the table of a machine that turns it (its trunnion) by the first setup's fixture, as the raw
// stock stands at A = C = 0.
TableSetting place_on_table(const machine::Machine& machine, const fixture::FixtureSpec& fixture,
                            const stock::InProcessStock& stock, const JobOptions& options, const std::string& where);

// Refuses (Error naming `where` and the indexing block) an indexing of the part from `from` to `to` that would turn
// the stock or the fixture into the tool retracted to the trunnion's safe Z: the material's cells and the fixture's
// boxes swept through A and C as the controller moves them (both at once, linearly), looked at every half degree
// with the way a point can go between two looks added, must stay `clearance` below the longest tool's tip.
void check_indexing(const stock::InProcessStock& stock, const TableSetting& table, const machine::Index& from,
                    const machine::Index& to, double clearance, const std::string& where);

// The time an indexing takes as LinuxCNC runs the post's blocks: the G53 rapid up from machine z `from_z` to the
// safe Z, A and C turning together as one coordinated move (each axis held to its velocity and acceleration), and the
// rapid down to `to_z`. The tool's length offset is not known here: the tip is taken to reach the safe Z, which
// over-counts each way by the length over the rapid feed (s).
double indexing_seconds(const machine::Trunnion& t, const machine::Index& from, const machine::Index& to,
                        double from_z, double to_z, double rapid_feed, const Vec3& max_acceleration);

// Begins the setup `index` of the job on the stock as the setups before left it. Throws Error naming the setup when
// its fixture cannot hold the stock.
JobSetup begin_setup(const SetupSpec& spec, size_t index, const stock::InProcessStock& stock,
                     const SetupContext& context);

}  // namespace rosmill::core::job
