#include "rosmill/gcode/block.hpp"

namespace rosmill::core::gcode {

std::string Place::str() const {
  if (line == 0) return std::string(file);
  return file.empty() ? "line " + std::to_string(line) : std::string(file) + ":" + std::to_string(line);
}

bool Block::has_g(int g10) const {
  for (int k = 0; k < g_count; ++k)
    if (g[k] == g10) return true;
  return false;
}

bool Block::has_m(int number) const {
  for (int k = 0; k < m_count; ++k)
    if (m[k] == number) return true;
  return false;
}

std::string g_name(int g10) {
  std::string s = "G" + std::to_string(g10 / 10);
  if (g10 % 10) s += "." + std::to_string(g10 % 10);
  return s;
}

}  // namespace rosmill::core::gcode
