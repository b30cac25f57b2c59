// The STL models of ../shared/data/stl and the units each is drawn in (featuretype and ktoolcav are inch
// parts), for the tests and benchmarks that run over all of them. The small ones are also in test/data.
#pragma once
#include "rosmill/units.hpp"

namespace rosmill::core::test_data {

struct BundledModel {
  const char* file;
  Units units;
  bool small;  // copied into test/data (the others are read from ../shared/data/stl)
};

inline constexpr BundledModel kBundledModels[] = {
    {"failedinpycam.stl", Units::Millimetre, true},    {"pycam-textbox.stl", Units::Millimetre, true},
    {"featuretype.STL", Units::Inch, true},             {"ktoolcav.stl", Units::Inch, true},
    {"wheel_in_box.stl", Units::Millimetre, true},      {"mount_rush.stl", Units::Millimetre, true},
    {"counter.unitsmm.STL", Units::Millimetre, false},  {"demo2.stl.gz", Units::Millimetre, false},
};

}  // namespace rosmill::core::test_data
