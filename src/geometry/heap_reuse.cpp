#include "rosmill/heap_reuse.hpp"

#include <malloc.h>

#include <climits>

namespace rosmill {

bool keep_freed_memory() {
  // Every block comes from the heap (no mmap per large block, which free() would unmap), and the free top of
  // the heap is never trimmed back to the kernel.
  const bool no_mmap = mallopt(M_MMAP_MAX, 0) == 1;
  const bool no_trim = mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
  return no_mmap && no_trim;
}

}  // namespace rosmill
