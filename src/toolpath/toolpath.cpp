#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::core {

size_t Toolpath::move_count() const {
  size_t n = 0;
  for (const auto& p : passes) n += p.moves.size();
  return n;
}

Box3 Toolpath::bounds() const {
  Box3 b;
  for (const auto& p : passes)
    for (const auto& m : p.moves) b.add(m.to);
  return b;
}

}  // namespace rosmill::core
