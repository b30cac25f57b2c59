// Every strategy, preset and template (plan_names.hpp) on every bundled STL model of test/data (the inch models
// read as inches, so scaled to mm), posted for LinuxCNC with arcs and for GRBL with lines: LinuxCNC's own interpreter
// (rs274 -g)
// accepts each program and its canonical moves are the toolpath's within the output precision, and each program
// keeps the bundled machine's limits (config/machine.yaml). Coarse on purpose to stay quick: a 6 mm ball (flat
// for contour) at 6 mm stepover, 10 mm step-down, 0.1 mm tolerance; the cloud strategies take the model's
// vertices as their cloud. One test per model, so ctest runs them side by side.
#include <gtest/gtest.h>

#include "plan_names.hpp"
#include "rosmill/testing/sanitized.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/rs274_check.hpp"
#include "rosmill/io/stl.hpp"
#include "bundled_models.hpp"

using namespace rosmill::core;
using namespace rosmill::core::gcode;

namespace {

using test_data::BundledModel;

// The models of test/data (the two large ones take minutes through every strategy and dialect).
std::vector<BundledModel> small_models() {
  std::vector<BundledModel> out;
  for (const BundledModel& m : test_data::kBundledModels)
    if (m.small) out.push_back(m);
  return out;
}

class EveryStrategyOnModel : public ::testing::TestWithParam<BundledModel> {};

std::string model_name(const ::testing::TestParamInfo<BundledModel>& info) {
  std::string n;
  for (const char* c = info.param.file; *c && *c != '.'; ++c) n.push_back(std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_');
  return n;
}

}  // namespace

TEST_P(EveryStrategyOnModel, AcceptedByRs274WithTheToolpathsMovesAndWithinTheMachine) {
  const BundledModel& model = GetParam();
  StlReadOptions ro;
  ro.units = model.units;
  const Mesh mesh = read_stl(ROSMILL_TEST_DATA "/" + std::string(model.file), ro);
  PointCloud cloud;
  cloud.points = mesh.vertices;
  cloud.recompute_bbox();
  const MachineLimits machine = load_machine_limits(ROSMILL_SOURCE_DIR "/config/machine.yaml");
  const std::vector<BundledModel> models = small_models();
  size_t index = 0;
  while (index < models.size() && std::string(models[index].file) != model.file) ++index;
  const std::vector<test::PlanName> names = test::plan_names();
  size_t verified = 0, expected = 0;
  for (size_t i = 0; i < names.size(); ++i) {
    const test::PlanName& s = names[i];
    // Under the sanitizers each name runs on one model, in turn: the paths are the same code on all of them.
    if (rosmill::testing::kSanitized && i % models.size() != index) continue;
    expected += 2;
    PlanParams params;
    params.tool.id = 1;
    params.tool.cutter = s.name == "contour" ? Cutter::flat(6) : Cutter::ball(6);
    params.tool.stepover = 6;
    params.tool.stepdown = 10;
    params.tolerance = 0.1;
    params.max_feed = machine.max_feed;  // feeds raised for a thin engagement stop at the machine's, as plan does
    // Four-axis rings start the holder's radius above the part's bottom: a slim collet, for the flat models.
    if (s.multi_axis) params.tool.holder_diameter = 8;
    const std::string what = s.name + " on " + model.file;
    Job job;
    try {
      job = test::plan_named(s, mesh, cloud, params);
    } catch (const Error& e) {
      // Four-axis rings need a part taller than the holder's radius over the table: a flat one is refused so.
      if (s.name == "four-axis" && std::string(e.what()).find("four-axis: the part is lower") == 0) {
        verified += 2;
        continue;
      }
      ADD_FAILURE() << what << ": " << e.what();
      continue;
    }
    for (const char* dialect : {"linuxcnc", "grbl"}) {
      PostOptions o;
      o.dialect = dialect;
      o.arcs = o.dialect == "linuxcnc";
      o.arc_tolerance = 0.01;
      if (s.multi_axis) {
        // For the trunnion with tool-centre-point control; GRBL has no rotary axes, and says so.
        o = test::multi_axis_post(o);
        if (o.dialect == "grbl") {
          EXPECT_THROW(post(job, o), Error) << what;
          ++verified;
          continue;
        }
      }
      const Program p = post(job, o);
      const Rs274Result r = run_rs274(p.lines);
      ASSERT_TRUE(r.ok) << what << " (" << dialect << "): line " << r.error_line << ": " << r.error;
      const VerifyReport rep = compare_with_job(p, job, r, o.arc_tolerance);
      EXPECT_TRUE(rep.ok) << what << " (" << dialect << "): " << rep.problem;
      EXPECT_GT(rep.canon_moves, 0u) << what;
      // A multi-axis program's limits are the small trunnion's, which most of these models do not fit on
      // (test_five_axis checks them on parts that do).
      if (!s.multi_axis)
        for (const LimitViolation& v : check_limits(p.lines, machine))
          ADD_FAILURE() << what << " (" << dialect << "): line " << v.line << ": " << v.message();
      ++verified;
    }
  }
  EXPECT_EQ(verified, expected);
}

INSTANTIATE_TEST_SUITE_P(BundledModels, EveryStrategyOnModel, ::testing::ValuesIn(small_models()), model_name);
