// Cutter shapes and the tools of the tool table. Dimensions in millimetres, feeds in mm/min.
#pragma once
#include <cmath>
#include <string>

namespace rosmill::core {

enum class CutterType { FlatEnd, BallEnd, BullNose };

// The cutting shape: a cylinder of `diameter` whose bottom is flat (corner_radius 0), a hemisphere
// (corner_radius = diameter / 2) or a torus corner in between. The tip is the lowest point on the axis.
struct Cutter {
  CutterType type = CutterType::FlatEnd;
  double diameter = 6.0;
  double corner_radius = 0.0;
  double flute_length = 20.0;
  double shank_diameter = 6.0;

  double radius() const { return 0.5 * diameter; }
  static Cutter flat(double d) { return {CutterType::FlatEnd, d, 0.0, 4 * d, d}; }
  static Cutter ball(double d) { return {CutterType::BallEnd, d, 0.5 * d, 4 * d, d}; }
  static Cutter bull(double d, double r) { return {CutterType::BullNose, d, r, 4 * d, d}; }
};

// The same cutting shape (type, diameter, corner radius): what one tool number must always name.
inline bool same_cutter(const Cutter& a, const Cutter& b) {
  return a.type == b.type && a.diameter == b.diameter && a.corner_radius == b.corner_radius;
}

// A tool of the tool table (config/tools.yaml): a cutter plus how to run it.
// Degrees of a cutter's circle in material in a straight side cut `ae` wide: acos(1 - ae / radius), 180 from a
// cut of the whole diameter (a slot).
inline double side_cut_engagement_deg(double ae, double radius) {
  const double c = 1.0 - ae / radius;
  return std::acos(c < -1.0 ? -1.0 : c > 1.0 ? 1.0 : c) * 180.0 / M_PI;
}

struct Tool {
  int id = 1;
  std::string name;
  Cutter cutter;
  double spindle_rpm = 10000.0;
  double feed = 1000.0;         // mm/min
  double plunge_feed = 300.0;   // mm/min
  double stepover = 1.0;        // mm
  double stepdown = 1.0;        // mm
  // The radial engagement (degrees of the cutter's circumference in the material) at which `feed` holds; NaN: the
  // engagement of the tool's own stepover (feed_engagement_deg()). Feeds for other engagements follow by radial
  // chip thinning (chip_thinning.hpp).
  double feed_engagement = NAN;
  // How the tool sits in its holder: the length out of the holder (from the holder's face to the tip: the flutes and
  // the exposed shank) and the holder's largest diameter near the tool (a collet nut). NaN: the rule of thumb below.
  double stick_out = NAN;       // mm, at least the flute length
  double holder_diameter = NAN; // mm, at least the shank's

  // The flute length plus one shank diameter of exposed shank, when the table gives none.
  double stick_out_mm() const { return std::isnan(stick_out) ? cutter.flute_length + cutter.shank_diameter : stick_out; }
  // The engagement `feed` is for: the table's, else that of a side cut one stepover wide, acos(1 - stepover / R)
  // (at most 180 degrees: a stepover of the whole diameter is a slot).
  double feed_engagement_deg() const {
    return std::isnan(feed_engagement) ? side_cut_engagement_deg(stepover, cutter.radius()) : feed_engagement;
  }
  // An ER collet nut's diameter for the shank (ER16: 32 mm for a 10 mm shank), when the table gives none.
  double holder_mm() const { return std::isnan(holder_diameter) ? cutter.shank_diameter + 22.0 : holder_diameter; }
};

const char* cutter_type_name(CutterType t);

// The cutter grown by `allowance` on every side (each radius larger by it; a flat end mill becomes a bull nose
// of corner radius `allowance`): dropped, then lifted by `allowance`, it leaves that much stock on every surface.
// Throws Error for a negative or NaN allowance.
Cutter offset_cutter(const Cutter& cutter, double allowance);
// Throws Error naming `where` and the field when a tool's numbers are out of range: a diameter in (0, 500] mm,
// a corner radius in [0, D/2] (0 for a flat end mill, D/2 for a ball), feeds in (0, 1e5] mm/min, a speed in
// [0, 1e5] rpm, stepover and step-down in (0, 500] mm, a stick-out (when given) in [flute length, 1000] mm and a
// holder diameter in [shank diameter, 1000] mm. A tool from a message or a request passes here.
void check_tool(const Tool& tool, const std::string& where = "tool");

// Parses a cutter spec "ball:D", "flat:D" or "bull:D:r" (D diameter, r corner radius); throws Error naming
// `where` on anything else (unknown type, missing or non-positive numbers, r > D/2).
Cutter parse_cutter_spec(const std::string& spec, const std::string& where = "--tool");

}  // namespace rosmill::core
