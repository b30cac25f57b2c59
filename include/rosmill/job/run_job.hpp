// Runs a job: its setups in order (chosen from the segmentation with `setups: auto`), each with the part turned so
// that its tool axis points up, held in its fixture, its program's zero at its datum; each operation planned in its
// setup on the in-process stock the operations before left (whatever setup they ran in), kept clear of the
// fixture, its moves removed from the stock, and, when asked, every setup written as a G-code program that sets its
// own work offset, through the one program pipeline. Roughing cuts only what is left; a setup's finishing keeps to
// the faces the setup machines and an overlap band. The report gives per operation, per setup and for the job the
// material removed, the share of the feed path that cut only air, and the machining time.
#pragma once
#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/fixture/fixture.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/gcode/trajectory_limits.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/job/job_spec.hpp"
#include "rosmill/job/surface_account.hpp"
#include "rosmill/machine/trunnion.hpp"
#include "rosmill/planner/presets.hpp"
#include "rosmill/setups/setup_choice.hpp"
#include "rosmill/stock/in_process_stock.hpp"
#include "rosmill/plan/plan_report.hpp"
#include "rosmill/verify/engagement.hpp"

namespace rosmill::core::job {

struct OperationView;

struct JobOptions {
  const ToolTable* tools = nullptr;      // for tool ids; null: tools given as ball:D etc. only
  const PresetTable* presets = nullptr;  // for preset names
  std::string out_dir;                   // empty: no programs written
  bool per_operation = false;            // one program per operation instead of one per setup
  std::string dialect = "linuxcnc";
  // Where the part was found on the table (a registration): the program of a job's one setup with the workpiece
  // datum sets G54 there (G10 L2 P1); none: G54 as it stands. A job of several setups is refused with one.
  std::optional<gcode::WorkOffset> work_offset;
  gcode::ProgramChecks checks;           // what every written program is checked against; its machine also places
                                         // each setup's fixture and datum on the table (fixture_position, table_z)
  // Called with the operation's index and the fraction of it done (0 before it starts, 1 when its moves are
  // removed from the stock; in between while it is planned). Returning false cancels the job: the operations
  // finished so far are kept in the report (and their programs written), the rest are not run.
  std::function<bool(size_t operation, double fraction)> progress;
  // Called once the setups are known (chosen, with `setups: auto`), with every operation the job will run.
  std::function<void(const std::vector<OperationSpec>& operations)> operations_known;
  // Called after each operation with what it did, for a live view (rviz): its toolpaths, its setup, the stock it
  // left and the part.
  std::function<void(const OperationView&)> operation_done;
  // Given: the part (mm, workpiece frame), instead of reading the job's `part` (e.g. the mesh a ROS node received).
  const Mesh* part = nullptr;
  // false: every operation plans as `rosmill plan` would, against its own box or stock mesh, not the stock the
  // operations before left (and a rest operation runs whole): the behaviour before jobs knew the stock, for
  // comparisons.
  bool plan_on_stock = true;
  // Links over the material keep this much above it (mm): the machine's clearance over the stock.
  double link_clearance = 2.0;
  // The machine's trajectory planner (the machine file's): every operation's time is its posted program's cycle
  // time (gcode/cycle_time.hpp). Without limits: the time at the feeds alone.
  gcode::TrajectoryLimits trajectory;
  // Measure every operation's radial engagement against the stock before it (verify/engagement.hpp), and set a
  // roughing operation's feeds from it by radial chip thinning (cutter/chip_thinning.hpp), capped by the tool and
  // the machine's max_feed: its program and the time estimate then follow the cut's real engagement.
  bool measure_engagement = true;
  bool feeds_from_engagement = true;
};

struct OperationReport {
  std::string name, strategy, tool, setup;
  Tool tool_used;          // the tool as it ran: its cutter, stick-out and holder (the setup sheet lists them)
  size_t setup_index = 0;  // into JobReport::setups
  bool rest = false;
  size_t rest_cells = 0;  // a rest operation: the cells of the stock's grid it was sent to
  bool nothing_to_cut = false;  // no material stood above the design and the allowance where it works: not planned
  size_t moves = 0;
  double cutting_mm = 0, rapid_mm = 0, air_feed_mm = 0, air_cut_share = 0;
  double removed_mm3 = 0, time_s = 0;
  // Where the job's own time went, per stage (s): planning, the engagement's measurement, the removal from the
  // stock and the verifier's sweep (the last three side by side).
  double plan_seconds = 0, engagement_seconds = 0, remove_seconds = 0, verify_seconds = 0;
  uint32_t collision_line = 0;  // the toolpath move number of the first rapid into material (0: none)
  // Material left on the part after the operation, seen from its setup (mm; negative: cut below the design).
  double min_left_mm = 0, max_left_mm = 0;
  // The deepest cut below the design by the verifier (mm, 0: none; beyond its 0.01 mm tolerance) and the toolpath
  // move that made it.
  double gouge_mm = 0;
  uint32_t gouge_move = 0;
  std::string program;          // the written program (with an output folder)
  bool roughing = false;        // its strategy clears stock in levels (the strategy table's `roughing`)
  // The cutter's radial engagement against the stock before the operation (JobOptions::measure_engagement;
  // move_deg left empty), and the feed moves whose feed was set from it (roughing, feeds_from_engagement).
  bool engagement_measured = false;
  verify::EngagementReport engagement;
  size_t feeds_from_engagement = 0;
  // What the strategy reported of each toolpath it planned: for adaptive clearing, the channels it cut as slots and
  // the material it could not clear, patch by patch with the reason (in the setup's frame).
  std::vector<PlanReport> plan_reports;
};

// A setup as the job ran it: what the operator clamps and where the program's zero is.
struct SetupReport {
  std::string name;
  Vec3 direction = Vec3::UnitZ();   // the tool axis, workpiece frame
  std::string source;               // why it is a setup: "given", or what setup selection saw ("axis", ...)
  SetupFrame frame;                 // the workpiece in the setup's program frame (the datum at its origin)
  Datum datum = Datum::TopCentre;
  Vec3 datum_point = Vec3::Zero();  // the datum in the workpiece frame
  std::string face_down;            // the face the part stands on: "-Z" (the side opposite the tool axis)
  Box3 stock;                       // the stock when the setup began, in its frame
  fixture::Fixture fixture;         // placed, in the setup's frame
  // The work offset the setup's program sets (G10 L2 Pn, G54..G59: the datum on the machine); none: G54 as the
  // controller has it (the workpiece datum without a registration).
  std::optional<gcode::WorkOffset> work_offset;
  // On a trunnion table: the A and C the part is turned to for this setup (3+2); the frame is then the machine's.
  std::optional<machine::Index> index;
  // The indexing before the setup (the G53 retract, A and C turning, the way down to its clearance), included in
  // time_s (s).
  double indexing_s = 0;
  std::vector<size_t> operations;   // indices into JobReport::operations
  double finished_area = 0;         // mm^2 of the part's faces this setup finishes (0: not bound to faces)
  double time_s = 0;
  std::string program;
};

struct JobReport {
  std::vector<OperationReport> operations;
  std::vector<SetupReport> setups;
  bool indexed = false;       // on a trunnion: the setups are A/C indexing in one program
  // On a trunnion: where the part stands on the table at A = C = 0 ("table" <- "workpiece").
  std::optional<Placement> workpiece_on_table;
  // On a trunnion, the written 3+2 program read back from its file and simulated through its rotary moves
  // (verify/indexed.hpp): the same check `rosmill verify --machine` makes, from the G-code, not the toolpaths.
  struct ProgramCheck {
    bool done = false;
    size_t runs = 0;                      // the runs of moves between indexings
    double gouge_mm = 0;                  // the deepest cut below the design (0: none)
    uint32_t gouge_line = 0;
    double min_left_mm = 0, max_left_mm = 0, left_mm3 = 0, seconds = 0;
  } program_check;
  // With `setups: auto`, what setup selection found: the surface no setup machines, and why.
  bool setups_chosen = false;
  double part_area = 0, unreachable_area = 0;
  std::vector<setups::Unreached> unreachable;
  // Per facet of the part: the setup (index into `setups`) that finishes most of it, -1 for none; empty when the
  // job's operations work over the whole part (the older form).
  std::vector<int> facet_setup;
  double stock_mm3 = 0;       // the raw stock
  Box3 stock_box;             // its bounds, workpiece frame (rosmill verify --stock)
  double left_mm3 = 0;        // the stock after the job
  double removed_mm3 = 0, air_cut_share = 0, time_s = 0;
  // After the job, on the whole surface of the part, all setups together (surface_account.hpp): the least and the
  // most material left over the faces the job was to finish (over every face when it was to finish none; negative:
  // a gouge, the depth below the design), in mm.
  double min_left_mm = INFINITY, max_left_mm = 0;
  SurfaceAccount surface;     // per face: within its limit, above it (where, how much, why), or not asked
  bool accept_unfinished = false;  // the job's accept_unfinished
  // Faces the job was to finish and left above their limit, and the job does not accept it.
  bool unfinished() const { return surface.unfinished_faces > 0 && !accept_unfinished; }
  double gouge_mm = 0;        // the deepest of the operations' (the verifier's)
  size_t stock_bytes = 0;
  bool cancelled = false;     // the progress hook said stop: `operations` holds the finished ones
};

struct OperationView {
  size_t index;
  const OperationReport& report;
  const Job& toolpaths;          // in the setup's frame
  const SetupReport& setup;      // its frame, fixture and datum
  const std::vector<int>& facet_setup;  // JobReport::facet_setup
  const stock::InProcessStock& stock;
  const Mesh& part;              // workpiece frame
};

JobReport run_job(const JobSpec& job, const JobOptions& options);

// The job's part as run_job reads it: its STL in the job's units, or a primitive.
Mesh read_part(const JobSpec& job);

// The job's programs as ranges [first, end) of the report's operations: one per setup (the part stays clamped;
// the tools change between its operations), or one per operation.
std::vector<std::pair<size_t, size_t>> program_groups(const JobReport& report, bool per_operation);

nlohmann::json to_json(const JobReport& report);

}  // namespace rosmill::core::job
