// The radial engagement along a program, measured move by move on a height-field stock the program is swept
// through: the independent check of any planner's engagement, and what feeds from engagement read.
//
// The angle. At a point of a feed move, with u the XY direction of travel and R the cutter's radius, the radial
// engagement is the measure of the directions v of the cutter's leading half (v . u >= 0) for which the stock at
// axis + R v stands higher than the tip by more than `floor_tolerance`, in the stock as it is before the cutter gets
// there: the immersion angle of milling mechanics (Altintas, "Manufacturing Automation", ch. 2: a slot is 180
// degrees, a side cut of radial width ae is acos(1 - ae / R), air 0). For a ball or bull nose it is the engagement
// of the cylinder of its diameter at the tip's height, an upper bound of the edge's own. A move straight along the
// tool axis (a plunge) has no direction of travel: it is counted apart and has none.
//
// How. The program is swept through the stock's cells a few millimetres behind the cutter; the path since then is
// held exactly (a line, an arc, z along them), so the material at a point of the cutter's circle is what the cells
// hold there lowered to where the recent path passed within the radius. Just behind the cutter its own cut's edge
// runs close to its circle's sides, where a cell's rounding would misread a wide range of it; and an arc may curl
// into its own cut (a hole milled on a circle smaller than the cutter), which the exact path sees. Samples fall
// every `sample_step` along a move; the leading half is read at `angle_step_deg` steps.
//
// Tolerance. The stock is known at cell centres: a point reads the cell it falls in, within cell / sqrt(2) of it, so
// a material edge seen from the cutter's circle moves by that much at most, and the angle where the circle crosses
// a straight edge at 30 degrees or more by at most deg(cell / (sqrt(2) R sin 30)), plus half an angle step at each of
// its two ends (engagement_tolerance_deg). For a straight cut of 30 to 180 degrees of engagement at the default cell
// (R / 40 or finer) and angle step (0.5 degrees) the measured angle lies within kEngagementToleranceDeg = 2.6
// degrees of the true one; the tests hold it to that. A cut thinner than the rounding (a pass along a wall it cut
// before, ae = 0) may read up to engagement_grazing_deg = acos(1 - cell / (sqrt(2) R)) instead of 0: 9.6 degrees
// at a cell of R / 50 (0.1 mm, R 5), 10.8 at R / 40.
#pragma once
#include <array>
#include <vector>

#include "rosmill/geometry/types.hpp"
#include "rosmill/stock/height_field.hpp"
#include "rosmill/stock/program.hpp"

namespace rosmill::core::verify {

constexpr double kEngagementToleranceDeg = 2.6;  // see above: straight cuts of 30 to 180 degrees, default cell
constexpr int kEngagementBins = 18;              // the histogram's bins, 10 degrees each (180 falls in the last)
constexpr double kEngagementBinDeg = 10.0;

struct EngagementOptions {
  double cell = 0;               // mm: the stock's cell; 0: engagement_cell(program)
  double sample_step = 0;        // mm along a move; 0: two cells, within [0.1, 0.25] mm
  double angle_step_deg = 0.5;   // between the directions read on the cutter's leading half
  double floor_tolerance = 0.01; // mm the stock must stand above the tip to count as material
  size_t max_cells = 16'000'000; // a finer grid over the stock is coarsened to this many cells (and says so)
};

struct EngagementReport {
  double max_deg = 0;
  double p95_deg = 0;            // 95 % of the radial feed length (plunges apart) is engaged this much or less
  std::array<double, kEngagementBins> histogram_mm{};  // radial feed length per 10-degree bin of engagement
  double radial_mm = 0;          // feed length with a direction of travel in XY (lines, arcs, ramps, helices)
  size_t plunges = 0;            // feed moves straight down the tool axis
  double plunge_mm = 0;
  double feed_minutes = 0;       // every feed move's length over its feed
  double removed_mm3 = 0;        // what the program removed from the stock
  double mrr_mm3_per_min = 0;    // removed_mm3 / feed_minutes: the mean material removal rate while feeding
  std::vector<float> move_deg;   // per program move: the largest engagement along it (0: rapid, plunge, air)
  double cell_mm = 0;            // the stock's cell
  double tolerance_deg = 0;      // engagement_tolerance_deg at that cell for the smallest cutter that fed
  double seconds = 0;
};

// The default cell for a program: 0.1 mm, or R / 40 of its smallest cutter that feeds when that is finer.
double engagement_cell(const stock::MachineProgram& program);

// The bound on the measured angle's error for a straight cut of 30 to 180 degrees (see above), degrees.
double engagement_tolerance_deg(double radius, double cell, double angle_step_deg = 0.5);

// The most a grazing pass (ae = 0: along a wall already cut) may read from the cells' rounding, degrees.
double engagement_grazing_deg(double radius, double cell);

// A grid over `stock_bounds` (XY) at the options' cell (0: engagement_cell), limited to where the program's feed
// moves reach (their axis paths grown by the largest radius and a cell) and coarsened to options.max_cells.
stock::GridSpec engagement_grid(const stock::MachineProgram& program, const Box3& stock_bounds,
                                const EngagementOptions& options = {});

// A grid over [lo, hi] (XY, mm) at `cell`, coarsened until its cells fit `max_cells`.
stock::GridSpec engagement_grid_over(const Vec2& lo, const Vec2& hi, double cell, size_t max_cells);

// Sweeps `program` through `stock` (left as the program leaves it) and measures the engagement of every feed move
// before it cuts. Throws Error naming the move for a move with a tool the program lacks, a position that is not
// finite, an arc outside the XY plane, or a feed move without a positive feed; and for options out of range.
EngagementReport measure_engagement(const stock::MachineProgram& program, stock::HeightField& stock,
                                    const EngagementOptions& options = {});

// Recomputes feed_minutes and mrr_mm3_per_min from the program's feeds (after they were set from the engagement).
void retime_engagement(EngagementReport& report, const stock::MachineProgram& program);

}  // namespace rosmill::core::verify
