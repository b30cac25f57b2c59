// The reference for setup selection's search (setups/setup_choice.hpp), written apart from it: every set of the
// candidates compared from the per-sample reach, without the search's compression of samples into units. The rule
// it applies: a face (a phase 1 patch) some candidate reaches 99.5 % of counts only for a set holding such a
// candidate; any other surface where any member of the set reaches it. For tests and benchmarks.
#pragma once
#include <cstddef>
#include <cstdint>

#include "rosmill/segment/surface_patches.hpp"
#include "rosmill/setups/setup_choice.hpp"

namespace rosmill::core::testing {

struct ExhaustiveCover {
  size_t fewest = 0;        // the fewest candidates whose cover is within the slack of all candidates'
  double best = 0;          // the largest cover of a set of that many
  double all = 0;           // all candidates' cover
  double of_chosen = 0;     // the cover of `chosen`
};

// Over the choice's candidates and samples (choice.reached), `chosen` a set of candidates (bit c: candidate c).
ExhaustiveCover exhaustive_cover(const setups::SetupChoice& choice, const segment::SurfacePatches& patches,
                                 double slack, uint64_t chosen);

}  // namespace rosmill::core::testing
