// An 8-bit colour, and a colour with what it stands for (a legend's or a colour bar's entry).
#pragma once
#include <cstdint>
#include <string>

namespace rosmill::core::picture {

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
};

struct ColourBand {
  Rgb colour;
  std::string label;
};

}  // namespace rosmill::core::picture
