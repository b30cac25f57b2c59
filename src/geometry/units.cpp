#include "rosmill/units.hpp"

#include "rosmill/error.hpp"

namespace rosmill::core {

double mm_per_unit(Units u) {
  switch (u) {
    case Units::Millimetre: return 1.0;
    case Units::Inch: return 25.4;
    case Units::Metre: return 1000.0;
  }
  return 1.0;
}

Units parse_units(const std::string& text, const std::string& where) {
  if (text == "mm") return Units::Millimetre;
  if (text == "inch" || text == "in") return Units::Inch;
  if (text == "m") return Units::Metre;
  throw Error(where, "unknown units '" + text + "' (expected mm, inch or m)");
}

}  // namespace rosmill::core
