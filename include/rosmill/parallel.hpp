// How the core spreads work over the cores: TBB's loops, reductions, per-thread scratch and tasks, in one place.
// With ROSMILL_SEQUENTIAL defined, everything runs on the calling thread and no thread library is linked:
// the command-line front builds the few sources `rosmill info` needs that way for small files, whose whole run is
// shorter than loading TBB and the shared C++ library (see src/cli/front/front_main.cpp).
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>

#ifdef ROSMILL_SEQUENTIAL
#include <functional>
#include <optional>
#else
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>
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

// In the next two loops, work that is not split (one chunk, a range no longer than its grain) runs on the calling
// thread without touching the thread pool: its first start (libraries, a worker) costs more than a small loop.

// body(k) for k in [0, chunks), each chunk one task (the caller sizes the chunks, or each is one large item).
template <class Index, class Body>
void for_each_chunk(Index chunks, const Body& body) {
#ifndef ROSMILL_SEQUENTIAL
  if (chunks > 1) {
    tbb::parallel_for(Index(0), chunks, body, tbb::simple_partitioner());
    return;
  }
#endif
  for (Index k = 0; k < chunks; ++k) body(k);
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

// body(i) for i in [first, last), the items taken on demand by the cores (TBB's index loop: its partitioner groups
// them as the cores go idle).
template <class Index, class Body>
void for_each_index(Index first, Index last, const Body& body) {
#ifdef ROSMILL_SEQUENTIAL
  for (Index i = first; i < last; ++i) body(i);
#else
  tbb::parallel_for(first, last, body);
#endif
}

// The reductions: body(begin, end, value) adds the items [begin, end) to `value` and returns it; join(a, b) returns
// a and b combined, a holding the items before b's. An empty range is `identity`.

// Over pieces of at least `grain` items taken on demand: how the range is cut (and so the order of the joins)
// varies from run to run, so the result does when join is not exact (floating point sums).
template <class Index, class Value, class Body, class Join>
Value reduce_pieces(Index first, Index last, Index grain, const Value& identity, const Body& body, const Join& join) {
#ifdef ROSMILL_SEQUENTIAL
  (void)grain;
  (void)join;
  return last > first ? body(first, last, identity) : identity;
#else
  return tbb::parallel_reduce(
      tbb::blocked_range<Index>(first, last, grain), identity,
      [&](const tbb::blocked_range<Index>& r, const Value& v) { return body(r.begin(), r.end(), v); }, join);
#endif
}

// The same sums in the same order whatever the threads: the range is halved down to pieces of at most `grain`
// items, and each half's result joined to its neighbour's (TBB's deterministic reduce, whose cuts the sequential
// build makes too, so that both give the same bits).
template <class Index, class Value, class Body, class Join>
Value reduce_pieces_deterministic(Index first, Index last, Index grain, const Value& identity, const Body& body,
                                  const Join& join) {
#ifdef ROSMILL_SEQUENTIAL
  if (!(last > first)) return identity;
  if (last - first <= grain) return body(first, last, identity);
  const Index middle = first + (last - first) / 2u;  // where blocked_range splits
  return join(reduce_pieces_deterministic(first, middle, grain, identity, body, join),
              reduce_pieces_deterministic(middle, last, grain, identity, body, join));
#else
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Index>(first, last, grain), identity,
      [&](const tbb::blocked_range<Index>& r, const Value& v) { return body(r.begin(), r.end(), v); }, join);
#endif
}

// One T for each thread that asks, made on its first local(): by `make()` when given, else T's default. For
// scratch a loop's items reuse (a thread runs one item at a time) without sharing it between threads.
template <class T>
class PerThread {
 public:
#ifdef ROSMILL_SEQUENTIAL
  PerThread() : make_([] { return T(); }) {}
  template <class Make>
  explicit PerThread(Make make) : make_(std::move(make)) {}
#else
  PerThread() = default;
  template <class Make>
  explicit PerThread(Make make) : values_(std::move(make)) {}
#endif

  T& local() {
#ifdef ROSMILL_SEQUENTIAL
    if (!value_) value_.emplace(make_());
    return *value_;
#else
    return values_.local();
#endif
  }

 private:
#ifdef ROSMILL_SEQUENTIAL
  std::function<T()> make_;
  std::optional<T> value_;
#else
  tbb::enumerable_thread_specific<T> values_;
#endif
};

// Work started now on another core, waited for later (run() may start several); the waiting thread helps with it.
class TaskGroup {
 public:
  template <class F>
  void run(F&& f) {
#ifdef ROSMILL_SEQUENTIAL
    f();
#else
    group_.run(std::forward<F>(f));
#endif
  }
  void wait() {
#ifndef ROSMILL_SEQUENTIAL
    group_.wait();
#endif
  }

 private:
#ifndef ROSMILL_SEQUENTIAL
  tbb::task_group group_;
#endif
};

// f(), whose thread, while it waits for f's own parallel work, takes no other task (one of a TaskGroup still
// running, say): the waiting thread's state stays its own.
template <class F>
auto isolated(const F& f) {
#ifdef ROSMILL_SEQUENTIAL
  return f();
#else
  return tbb::this_task_arena::isolate(f);
#endif
}

// How many threads the loops above may run on.
inline int max_threads() {
#ifdef ROSMILL_SEQUENTIAL
  return 1;
#else
  return tbb::this_task_arena::max_concurrency();
#endif
}

// At most `threads` threads for the loops above while it lives (none taken off for 0 or less).
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads) {
#ifdef ROSMILL_SEQUENTIAL
    (void)threads;
#else
    if (threads > 0)
      limit_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
#endif
  }

 private:
#ifndef ROSMILL_SEQUENTIAL
  std::unique_ptr<tbb::global_control> limit_;
#endif
};

}  // namespace rosmill::core
