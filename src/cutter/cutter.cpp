#include "rosmill/cutter/cutter.hpp"

namespace rosmill {

const char* cutter_type_name(CutterType t) {
  switch (t) {
    case CutterType::FlatEnd: return "flat";
    case CutterType::BallEnd: return "ball";
    case CutterType::BullNose: return "bull";
  }
  return "flat";
}

}  // namespace rosmill
