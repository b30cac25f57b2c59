#include "rosmill/verify/indexed.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "rosmill/error.hpp"
#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/stock/design_height.hpp"
#include "rosmill/stock/in_process_stock.hpp"

namespace rosmill::core::verify {
namespace {

std::string line_of(const stock::MachineProgram& p, const CanonMove& m) {
  return (p.from_gcode ? "line " : "move ") + std::to_string(m.source);
}

// The runs of moves at one turn of the table, in program order.
std::vector<stock::MachineProgram> split_runs(const stock::MachineProgram& program, std::vector<IndexedRun>& runs) {
  std::vector<stock::MachineProgram> parts;
  for (const CanonMove& m : program.moves) {
    if (m.known_rotary != 3)
      throw Error(line_of(program, m), "the table's A and C are not known here: a 3+2 program indexes the part "
                                       "(G0 A.. C..) before its first move");
    if (m.indexes() && (m.to - m.from).squaredNorm() > 0)
      throw Error(line_of(program, m), "A or C turns while the tool moves (a simultaneous five-axis move): a 3+2 "
                                       "program indexes with A and C alone");
    if (runs.empty() || runs.back().a != m.a_to || runs.back().c != m.c_to) {
      runs.push_back({m.a_to, m.c_to, 0, m.source, {}});
      parts.emplace_back();
      parts.back().tools = program.tools;
      parts.back().from_gcode = program.from_gcode;
      parts.back().finishing_stepover = program.finishing_stepover;
    }
    parts.back().moves.push_back(m);
    ++runs.back().moves;
  }
  return parts;
}

// The workpiece seen from the spindle with the table at (a, c): the setup frame is the machine's.
SetupFrame frame_at(const machine::Trunnion& t, const Placement& workpiece_on_table, double a, double c) {
  SetupFrame f;
  f.name = "A " + std::to_string(a) + " C " + std::to_string(c);
  f.placement = compose(t.table_in_machine(a, c), workpiece_on_table, "verify");
  f.tool_axis = f.placement.direction_back(Vec3::UnitZ()).normalized();
  return f;
}

}  // namespace

IndexedVerifyResult verify_indexed(const Mesh& design, const stock::MachineProgram& program,
                                   const machine::Trunnion& trunnion, const Placement& workpiece_on_table,
                                   const StockSpec& stock_spec, const VerifyOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  IndexedVerifyResult r;
  const std::vector<stock::MachineProgram> parts = split_runs(program, r.runs);
  stock::InProcessStock stock = in_process_stock(design, stock_spec, options);
  std::vector<SetupFrame> frames;
  for (size_t k = 0; k < parts.size(); ++k) {
    IndexedRun& run = r.runs[k];
    const SetupFrame frame = frame_at(trunnion, workpiece_on_table, run.a, run.c);
    // The gouge, from a fresh height field of the design as the table holds it.
    run.report = verify_program(placed(design, frame.placement), parts[k], StockSpec{}, options).report;
    if (run.report.gouged && run.report.max_gouge_mm > r.max_gouge_mm) {
      r.max_gouge_mm = run.report.max_gouge_mm;
      r.gouge_source = run.report.gouge_source;
    }
    stock.remove(parts[k], frame, options.simulation);
    if (std::none_of(frames.begin(), frames.end(), [&](const SetupFrame& f) { return f.same_as(frame); }))
      frames.push_back(frame);
  }
  r.stock_mm3 = stock.volume();
  r.design_mm3 = report(design).volume;
  r.left_mm3 = r.stock_mm3 - r.design_mm3;
  // Over the design only: where it does not stand (beside it, in the fixture's grip) the stock is not "left on the
  // part".
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const SetupFrame& f : frames) {
    const stock::HeightField view = stock.view(f);
    const std::vector<float> h = stock::design_heights(placed(design, f.placement), view.grid, view.bottom);
    for (size_t c = 0; c < h.size(); ++c) {
      if (view.top[c] == stock::kNoMaterial || !(h[c] > view.bottom + 1e-6)) continue;
      const double left = double(view.top[c]) - h[c];
      lo = std::min(lo, left), hi = std::max(hi, left);
    }
  }
  r.min_left_mm = std::isfinite(lo) ? lo : 0.0;
  r.max_left_mm = hi;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace rosmill::core::verify
