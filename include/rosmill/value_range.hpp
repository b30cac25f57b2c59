// The one check of a number against its accepted range, so that every refusal reads the same: the field, the
// range with its unit, and the value given.
#pragma once
#include <string>

namespace rosmill::core {

enum class Bound { Closed, Open };

// Throws Error(where, "must lie in [lo, hi] unit, got v") when v is NaN, infinite or outside the range (an open
// low bound excludes lo itself: (0, hi]).
void check_range(double v, double lo, double hi, const std::string& where, const char* unit,
                 Bound low = Bound::Closed);

}  // namespace rosmill::core
