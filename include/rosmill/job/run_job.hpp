// Runs a job: each operation planned on the part in its setup, its moves removed from the in-process stock left
// by the operations before it, and, when asked, written as a G-code program through the one program pipeline.
// The report gives per operation and for the job the material removed, the share of the feed path that cut only
// air, and the machining time estimated from the feeds and the rapid feed.
#pragma once
#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/gcode/prepare_program.hpp"
#include "rosmill/job/job_spec.hpp"
#include "rosmill/planner/presets.hpp"
#include "rosmill/stock/in_process_stock.hpp"

namespace rosmill::core::job {

struct OperationView;

struct JobOptions {
  const ToolTable* tools = nullptr;      // for tool ids; null: tools given as ball:D etc. only
  const PresetTable* presets = nullptr;  // for preset names
  std::string out_dir;                   // empty: no programs written
  bool per_operation = false;            // one program per operation instead of one per setup
  std::string dialect = "linuxcnc";
  std::optional<gcode::WorkOffset> work_offset;  // set by every written program (G10 L2 P1); none: G54 as it stands
  gcode::ProgramChecks checks;           // what every written program is checked against
  // Called with the operation's index and the fraction of it done (0 before it starts, 1 when its moves are
  // removed from the stock; in between while it is planned). Returning false cancels the job: the operations
  // finished so far are kept in the report (and their programs written), the rest are not run.
  std::function<bool(size_t operation, double fraction)> progress;
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
  // The machine's axes' accelerations for the time estimate (mm/s^2, toolpath_stats.hpp; zero: feeds alone).
  Vec3 max_acceleration = Vec3::Zero();
};

struct OperationReport {
  std::string name, strategy, tool, setup;
  bool rest = false;
  size_t rest_cells = 0;  // a rest operation: the cells of the stock's grid it was sent to
  size_t moves = 0;
  double cutting_mm = 0, rapid_mm = 0, air_feed_mm = 0, air_cut_share = 0;
  double removed_mm3 = 0, time_s = 0, plan_seconds = 0, remove_seconds = 0;
  uint32_t collision_line = 0;  // the toolpath move number of the first rapid into material (0: none)
  // Material left on the part after the operation, seen from its setup (mm; negative: cut below the design).
  double min_left_mm = 0, max_left_mm = 0;
  // The deepest cut below the design by the verifier (mm, 0: none; beyond its 0.01 mm tolerance) and the toolpath
  // move that made it.
  double gouge_mm = 0;
  uint32_t gouge_move = 0;
  std::string program;          // the written program (with an output folder)
};

struct JobReport {
  std::vector<OperationReport> operations;
  double stock_mm3 = 0;       // the raw stock
  double left_mm3 = 0;        // the stock after the job
  double removed_mm3 = 0, air_cut_share = 0, time_s = 0;
  // After the job: the least material left on the part over every operation's view (negative: a gouge, the
  // depth below the design), and the most left as the last operation sees it (mm).
  double min_left_mm = INFINITY, max_left_mm = 0;
  double gouge_mm = 0;        // the deepest of the operations' (the verifier's)
  size_t stock_bytes = 0;
  bool cancelled = false;     // the progress hook said stop: `operations` holds the finished ones
};

struct OperationView {
  size_t index;
  const OperationReport& report;
  const Job& toolpaths;  // in the setup's frame
  const SetupFrame& setup;
  const stock::InProcessStock& stock;
  const Mesh& part;
};

JobReport run_job(const JobSpec& job, const JobOptions& options);

// The job's programs as ranges [first, end) of its first `operations` operations: one per run of operations in the
// same setup (the part stays clamped; the tools change between them), or one per operation.
std::vector<std::pair<size_t, size_t>> program_groups(const JobSpec& job, size_t operations, bool per_operation);

nlohmann::json to_json(const JobReport& report);

}  // namespace rosmill::core::job
