#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::core {

size_t Toolpath::move_count() const {
  size_t n = 0;
  for (const auto& p : passes) n += p.moves.size();
  return n;
}

bool Toolpath::multi_axis() const {
  for (const auto& p : passes)
    if (!p.axes.empty()) return true;
  return false;
}

Box3 Toolpath::bounds() const {
  Box3 b;
  for (const auto& p : passes)
    for (const auto& m : p.moves) b.add(m.to);
  return b;
}

}  // namespace rosmill::core
