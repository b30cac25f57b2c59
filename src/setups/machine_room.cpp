#include <cstdio>

#include "rosmill/setups/setup_choice.hpp"

namespace rosmill::core::setups {

std::string machine_misfit(const MachineRoom& room, const Box3& stock, const fixture::Fixture& fixture) {
  char why[320];
  // The stock stands `seat` above the table; the rapids clear it, and the fixture where that stands higher.
  const double top = fixture.empty() ? stock.max.z() : std::max(stock.max.z(), fixture.bounds().max.z());
  const double tip = room.table_z + fixture.seat + (top - stock.min.z()) + room.clearance;
  if (tip > room.travel.max.z() + 1e-9) {
    std::snprintf(why, sizeof why,
                  "the stock stands %.1f mm high in it%s: the tool clearing it by %.1f mm would reach machine z %.1f, "
                  "above %s's Z travel (%.1f)",
                  stock.size().z(), fixture.seat > 0 ? (" on a seat " + std::to_string(int(fixture.seat + 0.5)) +
                                                        " mm over the table").c_str() : "",
                  room.clearance, tip, room.name.empty() ? "the machine" : room.name.c_str(), room.travel.max.z());
    return why;
  }
  static const char axis[] = "xy";
  for (int a = 0; a < 2; ++a) {
    const double half = 0.5 * stock.size()[a] + room.beyond;
    const double lo = room.fixture_position[a] - half, hi = room.fixture_position[a] + half;
    if (lo < room.travel.min[a] - 1e-9 || hi > room.travel.max[a] + 1e-9) {
      std::snprintf(why, sizeof why,
                    "the stock is %.1f mm long along %c in it: with the tools %.1f mm beyond it the tip would run "
                    "from machine %c %.1f to %.1f, beyond %s's travel (%.1f to %.1f)",
                    stock.size()[a], axis[a], room.beyond, axis[a], lo, hi,
                    room.name.empty() ? "the machine" : room.name.c_str(), room.travel.min[a], room.travel.max[a]);
      return why;
    }
  }
  return "";
}

}  // namespace rosmill::core::setups
