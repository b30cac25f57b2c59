// How much work one request may ask for, as one policy for every strategy, the slicer and the drop-cutter grid:
// each estimates its work from its parameters and the part's size and calls check_work before it allocates
// anything of that size. A stepover of a micrometre or a part read in the wrong units (metres as millimetres)
// would otherwise take the machine's memory or run for hours instead of being refused with the reason.
#pragma once
#include <string>

namespace rosmill::core {

// Minutes of work at about a million drop-cutter queries a second on two cores.
constexpr double kMaxDropQueries = 2e8;
// Points held at once (grid nodes, samples, cutter locations; 16 to 48 bytes each): about 2 GB at most.
constexpr double kMaxHeldPoints = 5e7;

struct Work {
  double queries = 0;   // drop-cutter queries, or steps of about their cost
  double points = 0;    // points held in memory at once
  std::string counted;  // how: "1.2e+07 lines x 401 samples"
  const char* steps = "drop-cutter queries";  // what `queries` counts, for the message
};

// Throws Error(where, ...) giving the estimate, the limit, how it was counted and the part's size (mm) when the
// work exceeds either limit (or is not a finite number).
void check_work(const std::string& where, const Work& work, double part_width, double part_depth);

// "1.2e+07 lines": a count and what it counts, for Work::counted.
std::string count_text(double n, const char* what);

// Positions of a step over a length, ends included, as a double (it may be far beyond any integer type).
double step_count(double length, double step);

}  // namespace rosmill::core
