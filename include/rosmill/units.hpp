// Length units. The core works in millimetres; inputs say what theirs are and are scaled once on the way in.
#pragma once
#include <string>

namespace rosmill::core {

enum class Units { Millimetre, Inch, Metre };

// Millimetres per one unit.
double mm_per_unit(Units u);
// Parses "mm", "inch"/"in", "m"; throws Error naming `where` otherwise.
Units parse_units(const std::string& text, const std::string& where = "units");

}  // namespace rosmill::core
