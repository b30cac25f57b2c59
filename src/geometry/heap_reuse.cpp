#include "rosmill/heap_reuse.hpp"

#include <malloc.h>

#include <climits>

namespace rosmill::core {

bool keep_freed_memory() {
  // Every block comes from the heap (no mmap per large block, which free() would unmap), the free top of the
  // heap is never trimmed back to the kernel, and worker threads allocate from the same heap (a thread's own
  // arena gives its freed pages back to the kernel, so its next large block would be fresh memory again).
  const bool no_mmap = mallopt(M_MMAP_MAX, 0) == 1;
  const bool no_trim = mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
  const bool one_arena = mallopt(M_ARENA_MAX, 1) == 1;
  return no_mmap && no_trim && one_arena;
}

}  // namespace rosmill::core
