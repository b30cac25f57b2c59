// The account of a job's work on the part: after the last setup, the material left on every face of the part, all
// setups together, in the workpiece frame — walls and the faces no setup looks at head-on included, not what one
// setup's height field sees.
//
// The faces are the part's surface patches (phase 1 of Lefebvre and Lauwers' segmentation: sharp-edge flooding).
// The surface is sampled (the setup choice's samples, each standing for its piece of a facet); at each sample the
// material left is how far the material of the in-process stock runs along the outward normal before it ends: cut
// away by a move of some setup (the stock's exact point query, its moves read between the cells' centres), outside
// the raw stock, or at the part again across a gap. A sample inside the part that some move cut away is a gouge
// (negative material left, its depth).
//
// A face is to be finished when a finishing operation (any but roughing) runs in the setup that machines it, or, in
// a job whose setups were chosen (`setups: auto`, which asks for the whole part), when no setup machines it at all;
// the face the part is held by never is. Its limit is the least allowance of those operations plus their tolerance
// (at least 0.01 mm, the verifier's resolution: a design's facets leave a cutter a few micrometres at their joints)
// and the scallop their stepover (raster) or step-down (waterline) leaves on a level or a vertical face by the
// cutter's corner: what the operator asked for. Where more is left, the account says why, per sample: no setup
// machines it ("no setup"), the fixture keeps the tool off it ("fixture"), the finishing tool touching the face
// there would meet the part elsewhere ("tool does not fit": a corner or slot narrower than the cutter, or a face
// deeper than the shank and the holder let it reach), or none of these ("strategy left it": the operations could
// have reached it but did not).
#pragma once
#include <string>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/fixture/fixture.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/setups/setup_choice.hpp"
#include "rosmill/stock/in_process_stock.hpp"

namespace rosmill::core::job {

enum class FaceVerdict { Within, Above, NotAsked };
const char* verdict_name(FaceVerdict v);  // "within", "above", "not asked"

// Why material stands above a face's limit.
enum class LeftReason { NoSetup, Fixture, ToolDoesNotFit, StrategyLeftIt };
const char* reason_name(LeftReason r);  // "no setup", "fixture", "tool does not fit", "strategy left it"
constexpr int kLeftReasons = 4;

struct FaceLeft {
  uint32_t face = 0;              // the patch
  double area = 0;                // mm^2
  Vec3 centroid = Vec3::Zero(), normal = Vec3::Zero();  // workpiece frame
  int setup = -1;                 // the job's setup that machines most of it, -1 none
  FaceVerdict verdict = FaceVerdict::NotAsked;
  double allowance = 0, limit = 0;               // mm; limit: allowance + tolerance + scallop
  double min_left_mm = 0, max_left_mm = 0;       // over its samples (negative: a gouge)
  double above_area = 0;                         // mm^2 left above the limit
  Vec3 above_centroid = Vec3::Zero();            // where that is, on average
  Vec3 most_at = Vec3::Zero();                   // where the most is left
  Vec3 least_at = Vec3::Zero();                  // where the least is (a gouge's deepest, when negative)
  double reason_area[kLeftReasons] = {0, 0, 0, 0};  // mm^2 above the limit for each reason
  std::vector<uint32_t> facets;                  // the part's facets of the face
  LeftReason main_reason() const;                // the reason of the largest area above
};

struct SurfaceAccount {
  bool done = false;
  std::vector<FaceLeft> faces;    // every patch of the part, by id
  size_t samples = 0;
  size_t asked_faces = 0;         // faces the job was to finish
  // Over the faces the job was to finish (every face, when it was to finish none): the least and most material left
  // (mm); and what stands above the limits.
  double min_left_mm = 0, max_left_mm = 0;
  double unfinished_area = 0;     // mm^2
  size_t unfinished_faces = 0;
  double seconds = 0;
};

// One of the job's setups as the account sees it.
struct AccountSetup {
  SetupFrame frame;               // workpiece -> the setup's frame (its tool axis along +Z)
  fixture::Fixture fixture;       // in the setup's frame
};

// One of the job's operations as the account sees it.
struct AccountOperation {
  size_t setup = 0;
  bool finishing = false;         // not a roughing strategy: it was to finish the faces of its setup
  Tool tool;
  double allowance = 0, tolerance = 0, scallop = 0;  // mm
};

struct AccountInput {
  const Mesh* part = nullptr;                    // workpiece frame
  const stock::InProcessStock* stock = nullptr;  // after the job
  const setups::SetupChoice* choice = nullptr;   // the samples and who machines each
  std::vector<int> job_setup;                    // per setup of the choice, the job's setup (-1: none ran)
  bool whole_part = false;                       // setups: auto: every face but the held one is to be finished
  std::vector<AccountSetup> setups;
  std::vector<AccountOperation> operations;
  double march_step = 0.25;                      // mm: how the material past the limit is followed out
};

SurfaceAccount account_surface(const AccountInput& input);

// The scallop an operation's passes leave by the cutter's corner on the faces they are meant for: a raster's
// stepover across a level face, a waterline's step-down up a vertical wall (0 for a flat end's bottom or side, for
// every other strategy, and for an unknown step).
double nominal_scallop(const Cutter& cutter, const std::string& strategy, double stepover, double stepdown);

}  // namespace rosmill::core::job
