#include "rosmill/heap_reuse.hpp"

#include <malloc.h>
#include <sys/mman.h>

#include <climits>
#include <cstdint>

#include "rosmill/parallel.hpp"

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

void fault_in_on_both_cores(void* data, size_t bytes) {
#ifdef MADV_POPULATE_WRITE
  constexpr uintptr_t kPage = 4096, kHuge = uintptr_t(2) << 20;
  if (bytes < 4 * kHuge) return;  // a few milliseconds at most: not worth a second thread
  const uintptr_t first = (reinterpret_cast<uintptr_t>(data) + kPage - 1) & ~(kPage - 1);
  const uintptr_t last = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(kPage - 1);
  // The split on a huge-page boundary, so that no 2 MB page is faulted from both sides.
  const uintptr_t middle = ((first + last) / 2) & ~(kHuge - 1);
  const auto populate = [](uintptr_t from, uintptr_t to) {
    if (to > from) ::madvise(reinterpret_cast<void*>(from), to - from, MADV_POPULATE_WRITE);  // a hint: may fail
  };
  run_both([&] { populate(first, middle); }, [&] { populate(middle, last); });
#else
  (void)data;
  (void)bytes;
#endif
}

}  // namespace rosmill::core
