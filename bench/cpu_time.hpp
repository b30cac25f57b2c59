// CPU seconds the process has used, all threads together: benchmarks report it beside wall time because it
// moves much less than wall time when other jobs share the machine's cores.
#pragma once
#include <sys/resource.h>

inline double cpu_seconds_used() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
