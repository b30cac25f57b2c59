// How the core spreads a loop or two pieces of work over the cores: TBB's parallel_for and parallel_invoke, in one
// place. With ROSMILL_SEQUENTIAL defined, everything runs on the calling thread and no thread library is linked:
// the command-line front builds the few sources `rosmill info` needs that way for small files, whose whole run is
// shorter than loading TBB and the shared C++ library (see src/cli/front/front_main.cpp).
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>

#ifndef ROSMILL_SEQUENTIAL
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/partitioner.h>
#endif

namespace rosmill::core {

// f() and g(), one on each core.
template <class F, class G>
void run_both(const F& f, const G& g) {
#ifdef ROSMILL_SEQUENTIAL
  f();
  g();
#else
  tbb::parallel_invoke(f, g);
#endif
}

// In both loops below, work that is not split (one chunk, a range no longer than its grain) runs on the calling
// thread without touching the thread pool: its first start (libraries, a worker) costs more than a small loop.

// body(k) for k in [0, chunks), each chunk one task (the caller sizes the chunks).
template <class Body>
void for_each_chunk(int chunks, const Body& body) {
#ifndef ROSMILL_SEQUENTIAL
  if (chunks > 1) {
    tbb::parallel_for(0, chunks, body, tbb::simple_partitioner());
    return;
  }
#endif
  for (int k = 0; k < chunks; ++k) body(k);
}

// body(begin, end) over pieces of [first, last) of at least `grain` items, taken on demand by the cores.
template <class Index, class Body>
void for_each_piece(Index first, Index last, Index grain, const Body& body) {
#ifdef ROSMILL_SEQUENTIAL
  (void)grain;
  body(first, last);
#else
  if (last - first <= grain) {
    if (last > first) body(first, last);
    return;
  }
  tbb::parallel_for(
      tbb::blocked_range<Index>(first, last, grain),
      [&](const tbb::blocked_range<Index>& r) { body(r.begin(), r.end()); }, tbb::auto_partitioner());
#endif
}

}  // namespace rosmill::core
