#include "rosmill/verify/verify.hpp"

#include <chrono>
#include <cmath>
#include <type_traits>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "rosmill/error.hpp"
#include "rosmill/stock/design_height.hpp"

namespace rosmill::core::verify {
namespace {

using Clock = std::chrono::steady_clock;

// The stock's bounds: the explicit box, the stock mesh's, or the design's; the design must stand within them in XY.
Box3 stock_bounds(const StockSpec& spec, const Box3& design_bounds) {
  const Box3 b = spec.kind == StockSpec::Kind::Box    ? spec.box
                 : spec.kind == StockSpec::Kind::Mesh ? spec.mesh->bbox
                                                      : design_bounds;
  if (b.empty()) throw Error(spec.kind == StockSpec::Kind::DesignBounds ? "design" : "--stock", "nothing to cover: it is empty");
  // The grid is the stock's: a design reaching beyond it in XY could not be compared there (nor be made).
  const double slack = 1e-6 * (1 + b.size().head<2>().norm());
  if ((design_bounds.min.head<2>().array() < b.min.head<2>().array() - slack).any() ||
      (design_bounds.max.head<2>().array() > b.max.head<2>().array() + slack).any()) {
    char what[240];
    std::snprintf(what, sizeof what, "the stock (x %g..%g, y %g..%g mm) does not hold the design (x %g..%g, y %g..%g mm)",
                  b.min.x(), b.max.x(), b.min.y(), b.max.y(), design_bounds.min.x(), design_bounds.max.x(),
                  design_bounds.min.y(), design_bounds.max.y());
    throw Error("--stock", what);
  }
  return b;
}

// The stock before the program on `grid`: a box, or the stock mesh's top (cells it misses hold no material).
stock::HeightField stock_on(const StockSpec& spec, const Box3& b, const stock::GridSpec& grid) {
  stock::HeightField stock = stock::HeightField::box(grid, b.min.z(), b.max.z());
  if (spec.kind == StockSpec::Kind::Mesh) stock.top = stock::design_heights(*spec.mesh, grid, b.min.z());
  return stock;
}

// The engagement along the program, on a grid of the same stock as fine as the measurement asks.
EngagementReport engagement_on(const StockSpec& spec, const Box3& b, const stock::MachineProgram& program,
                               const EngagementOptions& options) {
  stock::HeightField field = stock_on(spec, b, engagement_grid(program, b, options));
  return measure_engagement(program, field, options);
}

template <class Design>
VerifyResult run(const Design& design, const Box3& bounds, const stock::MachineProgram& program, const StockSpec& spec,
                 const VerifyOptions& options, double floor) {
  const auto start = Clock::now();
  const Box3 b = stock_bounds(spec, bounds);
  stock::HeightField stock =
      stock_on(spec, b, stock::GridSpec::covering(b.min.head<2>(), b.max.head<2>(), options.resolution, options.max_cells));
  std::vector<float> heights;
  if constexpr (std::is_same_v<Design, rosmill::core::Mesh>) heights = stock::design_heights(design, stock.grid, floor);
  else heights = stock::design_heights(design, stock.grid);
  stock::SimulationOptions so = options.simulation;
  if (!(so.trace_radius > 0)) so.trace_radius = scallop_window(program, options.compare, stock.grid.cell);
  const stock::SimulationResult sim = stock::simulate(program, stock, so);
  VerifyResult result;
  result.report = compare(stock, heights, program, sim, options.compare, &result.grid);
  if (options.measure_engagement) result.engagement = engagement_on(spec, b, program, options.engagement);
  result.simulation_seconds = sim.seconds;
  result.cells_visited = sim.cells_visited;
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace

StockSpec StockSpec::parse_box(const std::string& text, const std::string& where) {
  StockSpec s;
  if (text.empty() || text == "box") return s;
  std::vector<double> v;
  std::stringstream ss(text);
  for (std::string part; std::getline(ss, part, ',');) {
    char* end = nullptr;
    const double x = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !std::isfinite(x)) throw Error(where, "'" + part + "' is not a number");
    v.push_back(x);
  }
  if (v.size() != 6) throw Error(where, "expected box or x0,y0,z0,x1,y1,z1 (mm), got '" + text + "'");
  s.kind = Kind::Box;
  s.box.add(Vec3(v[0], v[1], v[2]));
  s.box.add(Vec3(v[3], v[4], v[5]));
  if (!(s.box.size().minCoeff() > 0)) throw Error(where, "the stock box has no volume");
  return s;
}

stock::InProcessStock in_process_stock(const rosmill::core::Mesh& design, const StockSpec& spec,
                                       const VerifyOptions& o) {
  if (spec.kind == StockSpec::Kind::Mesh)
    return stock::InProcessStock::from_mesh(*spec.mesh, o.resolution, o.max_cells);
  return stock::InProcessStock::box(spec.kind == StockSpec::Kind::Box ? spec.box : design.bbox, o.resolution,
                                    o.max_cells);
}

VerifyResult verify_program(const rosmill::core::Mesh& design, const stock::MachineProgram& program,
                            const StockSpec& stock,
                            const VerifyOptions& options) {
  return run(design, design.bbox, program, stock, options, design.bbox.min.z());
}

VerifyResult verify_program(const PointCloud& design, const stock::MachineProgram& program, const StockSpec& stock,
                            const VerifyOptions& options) {
  return run(design, design.bbox, program, stock, options, design.bbox.min.z());
}

}  // namespace rosmill::core::verify
