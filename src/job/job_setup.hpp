// What a setup's operations share, made once when the setup begins (private to the job area): the part turned into
// the setup's frame, its datum and fixture placed on the stock as it then is, the setup's work offset on the
// machine, the surface its operations plan on (the part, the fixture kept clear of), and the design's heights and
// the faces the setup finishes on the grid of the stock's view from the setup.
#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "rosmill/job/run_job.hpp"
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

struct SetupContext {
  const JobSpec& job;
  const JobOptions& options;
  const Mesh& part;
  const Mesh* stock_mesh;
  // Who finishes what (setup selection's assignment), and which of its setups this one is (-1: none of them, the
  // setup finishes no face); null: the whole part.
  const setups::SetupChoice* faces = nullptr;
  int chosen = 0;
};

// Begins the setup `index` of the job on the stock as the setups before left it. Throws Error naming the setup when
// its fixture cannot hold the stock.
JobSetup begin_setup(const SetupSpec& spec, size_t index, const stock::InProcessStock& stock,
                     const SetupContext& context);

}  // namespace rosmill::core::job
