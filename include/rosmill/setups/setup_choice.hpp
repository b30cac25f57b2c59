// Setup selection: from the candidate tool directions (candidates.hpp) and what the finishing tool reaches along
// each (reach.hpp), the setups that reach the most of the part's area with the fewest setups, as operations
// planning is meant to choose among the coexisting segmentations (Lefebvre and Lauwers, section 3.3).
//
// The rule a machinist works by: a face that one setup reaches whole is finished whole in one setup (no seam
// across it that needs none); a face no single setup reaches whole (a cylinder's side, a blade) is finished in
// pieces from the setups that reach them. So a set of setups covers a whole-reachable face's area only when one
// of them reaches it whole, and any other surface where any of them reaches it. The search is exhaustive over the
// candidates (up to `exhaustive_limit` of them; greedy beyond, and said so): the fewest setups whose cover comes
// within `min_gain_share` of the part's area of what all candidates together cover, the largest cover among them.
// Then every sample is machined by the chosen setup that reaches it (its face whole) most nearly head-on.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rosmill/cutter/cutter.hpp"
#include "rosmill/fixture/fixture.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/segment/surface_patches.hpp"
#include "rosmill/setups/candidates.hpp"
#include "rosmill/setups/reach.hpp"

namespace rosmill::core::setups {

// The room a 3-axis machine has for a setup (machine coordinates, mm): the tool tip's travel, the table's top, where
// the fixture stands on it, how high over the stock the programs' rapids run and how far past the stock's sides the
// tools go. A candidate whose stock, standing in its fixture, would take the tip out of its travel is not a setup.
struct MachineRoom {
  Box3 travel;                       // the tip's soft limits
  double table_z = 0;                // the table's top
  Vec2 fixture_position = Vec2::Zero();  // the stock is centred over it
  double clearance = 5;              // the rapids' height over the stock's top (the plans' safe clearance)
  double beyond = 0;                 // how far the tools reach past the stock's sides (the largest tool's diameter)
  std::string name;                  // the machine's, for messages
};

struct ChoiceOptions {
  Tool tool;                        // the tool whose reach counts (the finishing tool)
  double max_angle_deg = 90.0;
  // The outward normal (workpiece frame) of the face the part is held by in every setup (a fixture plate, the
  // first operation's datum face): that face is never machined, and no setup points the tool at it.
  std::optional<Vec3> held_face;
  // A fixture placed by its rule in every candidate setup around the stock (workpiece frame; empty: the part's box).
  std::optional<fixture::FixtureSpec> fixture;
  Box3 stock;
  double min_gain_share = 0.005;    // a setup must add this share of the part's area to be worth a re-clamping
  double whole_share = 0.995;       // a setup reaching this share of a face reaches it whole
  double spacing = 0.0;             // between samples (mm); 0: about 40,000 samples over the part
  CandidateOptions candidates;
  std::vector<Vec3> directions;     // when given, the candidates instead of the axes, flats and EGI peaks
  std::optional<MachineRoom> machine;  // when given, a candidate must fit it
  // When given: why the machine cannot point the tool along a direction (workpiece frame), empty when it can (a
  // trunnion whose A axis does not reach it). Such a direction is not a setup, as one that does not fit the room.
  std::function<std::string(const Vec3&)> direction_refused;
  // false: every usable candidate is a setup (a job that names its setups): only who machines what is found.
  bool search = true;
  size_t exhaustive_limit = 16;
};

// The part of a phase 1 patch that a setup machines.
struct SegmentShare {
  uint32_t patch = 0;
  double area = 0;   // mm^2
  Vec3 normal = Vec3::Zero();
};

struct ChosenSetup {
  size_t candidate = 0;
  Vec3 direction = Vec3::UnitZ();
  std::string name, source;
  double reachable_area = 0;  // what this setup reaches (mm^2)
  double assigned_area = 0;   // of it, what it machines (the rest another chosen setup finishes)
  std::vector<SegmentShare> segments;
};

// Surface no chosen setup machines, per patch and reason: "held" (the face the part is held by), "fixture" (a
// chosen setup's fixture stands in the way), "not chosen" (a candidate reaches it, but adds too little to be worth
// a setup), "machine" (only candidates that do not fit the machine reach it), "unreachable" (no candidate reaches
// it: an undercut, or deeper than the tool reaches).
struct Unreached {
  uint32_t patch = 0;
  std::string reason;
  double area = 0;
  Vec3 centroid = Vec3::Zero(), normal = Vec3::Zero();
};

// Why a sample is machined by no chosen setup (Unreached's reasons, per sample).
// Machine: only candidates that do not fit the machine reach it.
enum class Unmachined : uint8_t { No, Held, Fixture, NotChosen, Unreachable, Machine };

struct SetupChoice {
  std::vector<Candidate> candidates;
  std::vector<double> candidate_area;       // what each reaches alone (mm^2)
  std::vector<std::string> candidate_refused;  // why a candidate cannot be a setup (empty: it can)
  std::vector<uint8_t> candidate_unfit;         // 1 where it was refused for not fitting the machine
  std::vector<ChosenSetup> setups;
  double total_area = 0, machined_area = 0, unreachable_area = 0;
  double best_cover = 0;      // what every usable candidate together covers under the rule (mm^2)
  std::vector<Unreached> unreachable;
  SurfaceSamples samples;
  std::vector<int> machined_by;  // per sample: the index into `setups` that machines it, -1 none
  std::vector<Unmachined> unmachined;  // per sample: why none does (No where one does)
  std::vector<uint64_t> reached;  // per sample: bit c set when candidate c reaches it
  bool exhaustive = true;
  uint64_t subsets = 0;       // sets of setups compared
  double reach_seconds = 0, search_seconds = 0;
};

SetupChoice choose_setups(const Mesh& part, const segment::SurfacePatches& patches, const ChoiceOptions& options);

// Why the stock, standing in `fixture` as placed for a setup (both in the setup's frame), does not fit the machine:
// its tip would rise above its travel clearing them, or the tools would leave the table's travel beside them; empty
// when it fits.
std::string machine_misfit(const MachineRoom& room, const Box3& stock, const fixture::Fixture& fixture);

// Per facet of the part, the chosen setup that machines most of its area (an index into `setups`), -1 for a facet no
// setup machines: what a view colours the part by.
std::vector<int> facet_setups(const SetupChoice& choice, size_t facets);

}  // namespace rosmill::core::setups
