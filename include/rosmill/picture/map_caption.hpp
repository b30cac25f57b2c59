// The title line of a map picture: which map, of which part, from which program or scan, and when, so a printed
// map still says what it shows.
#pragma once
#include <string>

namespace rosmill::core::picture {

struct MapCaption {
  std::string map;     // "deviation map", "inspection map"
  std::string part;    // the design's file name
  std::string source;  // what was compared with it: "program part.ngc", "scan part.pcd"
  std::string date;    // ISO 8601 (yyyy-mm-dd); empty: today's local date

  // "deviation map of part.stl, program part.ngc, 2024-05-17" (empty parts left out).
  std::string title() const;
};

// Today's date in the local time zone, yyyy-mm-dd.
std::string local_iso_date();

}  // namespace rosmill::core::picture
