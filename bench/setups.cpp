// Setup selection on every bundled model (setups/setup_choice.hpp) beside the segmentation's own time and an
// exhaustive search apart from the product's (test support's exhaustive_cover).
//   segment:  phase 1 and phase 2 for the six axis setups, as `rosmill segment FILE` runs them (median of 3).
//   choose:   the setups chosen for the tool table's 6 mm ball (30 mm out of a 28 mm holder): what it reaches
//             from each candidate (reach) and the search over the candidates (search), median of 3.
//   process:  `rosmill segment FILE --setups auto --json` as a user meets it, a fresh process (best of 3).
//   exhaust:  every set of candidates compared from the per-sample reach, without the search's compression into
//             units: the fewest setups within the least gain of all candidates' cover, and the best cover of those.
//             "=" when the choice has as few setups and as much cover.
// Models: the STLs of ../shared/data/stl (test/data's small ones when that folder is missing), the primitives and
// the example pocket. Usage: bench_setups [threads]
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "bundled_models.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/segment/setup_segmentation.hpp"
#include "rosmill/setups/setup_choice.hpp"
#include "rosmill/testing/exhaustive_cover.hpp"

using namespace rosmill::core;

namespace {

using Clock = std::chrono::steady_clock;

double median_seconds(int runs, const std::function<void()>& work) {
  std::vector<double> t;
  for (int i = 0; i < runs; ++i) {
    const auto start = Clock::now();
    work();
    t.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// The best of three runs of the command line, a fresh process each (the model's file read, segmented, chosen).
double process_seconds(const std::string& file, Units units) {
  const std::string units_flag = units == Units::Inch ? " --units inch" : "";
  const std::string command =
      std::string(ROSMILL_CLI) + " segment '" + file + "'" + units_flag + " --setups auto --json > /dev/null 2>&1";
  double best = 1e9;
  for (int i = 0; i < 3; ++i) {
    const auto start = Clock::now();
    if (std::system(command.c_str()) != 0) return -1;
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  return best;
}

void run(const std::string& name, const Mesh& mesh, const Tool& tool, const std::string& file, Units units) {
  segment::SurfacePatches sp = segment::segment_surface(mesh);
  const double t_segment = median_seconds(3, [&] {
    const segment::SurfacePatches p = segment::segment_surface(mesh);
    const segment::EgiSet egis(p);
    for (const segment::SetupFilter& f : segment::axis_setups()) segment::segment_setup(egis, f);
  });
  setups::ChoiceOptions o;
  o.tool = tool;
  setups::SetupChoice c;
  const double t_choose = median_seconds(3, [&] { c = setups::choose_setups(mesh, sp, o); });
  uint64_t chosen = 0;
  for (const setups::ChosenSetup& s : c.setups) chosen |= uint64_t(1) << s.candidate;
  const testing::ExhaustiveCover e = testing::exhaustive_cover(c, sp, o.min_gain_share * c.total_area, chosen);
  std::string names;
  for (const setups::ChosenSetup& s : c.setups) names += (names.empty() ? "" : ",") + s.name;
  const bool same = e.fewest == c.setups.size() && e.of_chosen >= e.best - 1e-6 * c.total_area;
  const double process = file.empty() ? -1 : process_seconds(file, units);
  char proc[16] = "-";
  if (process >= 0) std::snprintf(proc, sizeof proc, "%.3f", process);
  std::printf("%-20s %9zu %3zu %8.4f %8.4f %7.4f %6.1fx %7s %2zu %6.1f%% %6.1f%% %2zu/%-2zu %s  %s\n", name.c_str(),
              mesh.face_count(), c.candidates.size(), t_segment, t_choose, c.search_seconds, t_choose / t_segment,
              proc, c.setups.size(), 100 * c.machined_area / c.total_area, 100 * c.unreachable_area / c.total_area,
              e.fewest, c.setups.size(), same ? "=" : "DIFFERS", names.c_str());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const size_t threads = argc > 1 ? size_t(std::max(1, std::atoi(argv[1]))) : 2;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const ToolTable tools = read_tool_table(std::string(ROSMILL_SOURCE_DIR) + "/config/tools.yaml");
  const Tool& ball = tools.get(2);
  std::printf("setup selection for the %s (%zu threads); seconds, shares of the part's area\n", ball.name.c_str(),
              threads);
  std::printf("%-20s %9s %3s %8s %8s %7s %7s %7s %2s %7s %7s %5s %s  %s\n", "model", "facets", "cnd", "segment",
              "choose", "search", "ratio", "process", "n", "machnd", "unreach", "exh", "", "setups");
  const std::string shared = std::string(ROSMILL_SHARED_DATA) + "/stl/";
  for (const test_data::BundledModel& m : test_data::kBundledModels) {
    std::string file = shared + m.file;
    if (!std::filesystem::exists(file)) {
      if (!m.small) continue;
      file = std::string(ROSMILL_TEST_DATA) + "/" + m.file;
    }
    StlReadOptions read;
    read.units = m.units;
    run(m.file, read_stl(file, read), ball, file, m.units);
  }
  for (const char* p : {"cube", "cylinder", "dome", "cone", "cavity"})
    run(std::string("primitive ") + p, make_primitive(p), ball, "", Units::Millimetre);
  const std::string pocket = std::string(ROSMILL_SOURCE_DIR) + "/config/jobs/data/pocket.stl";
  run("pocket.stl", read_stl(pocket), ball, pocket, Units::Millimetre);
  return 0;
}
