// The loop of one thread, for the functions that take a loop to run their
// independent parts on (first_occurrences, the certifier's spatial order): a
// caller with threads passes its own, calling f(i, worker) for every i.
#pragma once

#include <cstddef>

namespace dewall::kernel {

/// f(0, 0) … f(count − 1, 0), in order, on the calling thread.
struct Serial_loop {
  template <class F>
  void operator()(std::size_t count, F&& f) const {
    for (std::size_t i = 0; i < count; ++i) f(i, 0u);
  }
};

}  // namespace dewall::kernel
