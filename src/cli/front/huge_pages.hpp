// Transparent huge pages for the heap a large load is about to fill.
#pragma once
#include <cstddef>

namespace rosmill::core::cli {

// Grows the heap by `bytes` and asks the kernel to back that stretch with 2 MB pages when first written. The
// stretch is freed at once and stays in the heap (keep_freed_memory() must have been called), so the load's big
// arrays are carved from it. Does nothing for small sizes or when the kernel refuses.
void reserve_huge_page_heap(size_t bytes);

}  // namespace rosmill::core::cli
