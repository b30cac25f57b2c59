// Why: on a virtual machine each first write to a 4 KB page is a fault costing microseconds (about 2 ms per MB,
// see heap_reuse.hpp); a 2M-triangle load writes some 100 MB of fresh arrays, 24,000 faults, the largest part of
// its time. With madvise(MADV_HUGEPAGE) one fault maps 2 MB (the kernel's transparent huge pages, Linux
// Documentation admin-guide/mm/transhuge), 512 times fewer. glibc's own switch for this (the
// glibc.malloc.hugetlb tunable) is read only from the environment at start-up; this does the same in process.
#include "huge_pages.hpp"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>

namespace rosmill::core::cli {

void reserve_huge_page_heap(size_t bytes) {
  constexpr uintptr_t kHuge = uintptr_t(2) << 20;
  if (bytes < 8 * kHuge) return;  // below 16 MB the faults cost less than a millisecond or two
  void* block = std::malloc(bytes);
  if (!block) return;
  const uintptr_t first = (reinterpret_cast<uintptr_t>(block) + kHuge - 1) & ~(kHuge - 1);
  const uintptr_t last = (reinterpret_cast<uintptr_t>(block) + bytes) & ~(kHuge - 1);
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);  // a hint: may fail
  std::free(block);
}

}  // namespace rosmill::core::cli
