// Parallel loops over fixed chunks and ranges (TBB), each isolated so that a
// waiting thread takes no unrelated outer task. The chunks are fixed by the
// sizes, never by the threads: the callers' results do not depend on them.
#pragma once

#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace dewall::detail {

/// Calls f(c) for c = 0 … chunks − 1, as parallel tasks when there are
/// several. Isolated, as parallel_ranges.
template <class F>
void for_each_chunk(std::size_t chunks, F&& f) {
  if (chunks == 1) f(std::size_t{0});
  else tbb::this_task_arena::isolate([&] { tbb::parallel_for(std::size_t{0}, chunks, f); });
}

/// Calls f(range) on ranges of [0, count) of about `grain` indices, as
/// parallel tasks. Isolated: while it waits for them, the calling thread takes
/// no unrelated outer task (a hybrid's region builds inside one).
template <class F>
void parallel_ranges(std::size_t count, std::size_t grain, F&& f) {
  tbb::this_task_arena::isolate(
      [&] { tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain), f); });
}

}  // namespace dewall::detail
