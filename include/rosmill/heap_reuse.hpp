// Keeps the memory a job frees inside the process for the next job, instead of handing it back to the kernel.
//
// Why: on the virtual machines rosmill runs on (the CI's 2-core VMs among them), the first write to a page the
// process has not used before costs about 2 ms per MB (a host-side fault per 4 KB page), ten times the cost of
// the work itself for a large mesh. glibc's malloc returns big blocks (mmap) and the heap's free top (trim) to
// the kernel on free, so every load or segmentation of a 2M-triangle mesh would pay that again (and a worker
// thread's own malloc arena gives its pages back too, so all threads share one arena). A node serves
// request after request, and a benchmark repeats a job: both should call this once at start-up. The cost is
// that the process's resident size stays at its high-water mark.
#pragma once
#include <cstddef>

namespace rosmill::core {

// Call once, early in main(), before any large allocation. Returns false when the C library refused a setting
// (the program still works, only slower).
bool keep_freed_memory();

// Makes the fresh pages of [data, data + bytes) the process's own before they are first written, half on each
// core: the host-side faults of a virtual machine (see above) run side by side instead of one after the other
// inside a single thread's zero-fill. For a block about to be filled by one thread (a vector's resize); a hint:
// small blocks, and kernels older than Linux 5.14 (no MADV_POPULATE_WRITE), are left to fault as they are written.
void fault_in_on_both_cores(void* data, size_t bytes);

}  // namespace rosmill::core
