// Long calls that Ctrl-C stops and that report their progress.
//
// Python runs signal handlers only in the main thread, and only when that
// thread holds the GIL and evaluates bytecode or calls PyErr_CheckSignals. A
// call that computes in the calling thread with the GIL released therefore
// cannot see Ctrl-C until it returns. So a large call computes on a thread of
// its own while the calling thread waits, takes the GIL every few
// hundredths of a second, runs the handlers (PyErr_CheckSignals) and the
// caller's progress callback, and, when either raises (KeyboardInterrupt
// from the default SIGINT handler, or whatever a handler of the user's or the
// callback raises), sets the flag the work polls: the library's engines
// through Options::progress, the module's own loops through Watch::poll. The
// work then throws dewall::Cancelled at its next poll, unwinding what it
// built; the thread is joined and the Python exception raised.
//
// Why not a signal handler of the module's own: it would replace the user's
// (or Python's) SIGINT handler for the duration of the call, process-wide,
// while other Python threads may be running; and a handler that does not
// raise (a user's that only logs) must let the work go on. Here Python's own
// machinery decides, and no Python code runs off the calling thread.
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <type_traits>
#include <utility>

#include "dewall/error.hpp"

namespace dewall_python {

namespace py = pybind11;

/// What a watched call's work reports and learns: the fraction done, and
/// whether the caller stopped it. Polled from any thread of the work.
class Watch {
 public:
  /// Throws dewall::Cancelled once the caller has stopped the work.
  void poll() const {
    if (cancelled_.load(std::memory_order_relaxed)) throw dewall::Cancelled();
  }
  /// The fraction of the work done (0 … 1), then poll().
  void report(double fraction) {
    fraction_.store(fraction, std::memory_order_relaxed);
    poll();
  }
  /// For dewall::Options::progress: records the fraction; false once stopped.
  std::function<bool(double)> library_hook() {
    return [this](double fraction) {
      fraction_.store(fraction, std::memory_order_relaxed);
      return !cancelled_.load(std::memory_order_relaxed);
    };
  }
  /// Loops over `count` items in blocks of `block`: body(first, last) for
  /// each block, reporting and polling between blocks.
  template <class Body>
  void blocks(std::size_t count, std::size_t block, Body&& body) {
    for (std::size_t first = 0; first < count; first += block) {
      body(first, std::min(count, first + block));
      report(static_cast<double>(std::min(count, first + block)) / static_cast<double>(count));
    }
  }

  double fraction() const { return fraction_.load(std::memory_order_relaxed); }
  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }

 private:
  std::atomic<double> fraction_{0};
  std::atomic<bool> cancelled_{false};
};

/// Below this many items (points, queries, simplices) a call computes in
/// the calling thread, unwatched: it ends within milliseconds, and a thread
/// would cost more than the work.
inline constexpr std::size_t watched_size = std::size_t{1} << 15;

/// How often the waiting thread runs the signal handlers and the callback.
inline constexpr std::chrono::milliseconds watch_interval{25};

/// Runs work(watch) with the GIL released and returns its result: for at
/// least watched_size items (`size`), on a thread of its own while this one
/// watches (file comment); `progress`, when not None, is called with the
/// fraction done (a float in [0, 1]) as it changes, at most every
/// watch_interval, and with 1.0 at the end. The GIL must be held.
/// \throws the Python exception a signal handler or `progress` raised (the
/// work stopped); what the work threw.
template <class Work>
auto watched(std::size_t size, const py::object& progress, Work&& work) {
  using Result = std::invoke_result_t<Work&, Watch&>;
  Watch watch;
  const bool reports = !progress.is_none();
  double shown = -1;  // the fraction progress was told last
  const auto finished = [&] {
    if (reports && shown != 1.0) progress(1.0);
  };
  if (size < watched_size) {
    if constexpr (std::is_void_v<Result>) {
      {
        py::gil_scoped_release release;
        work(watch);
      }
      finished();
      return;
    } else {
      std::optional<Result> result;
      {
        py::gil_scoped_release release;
        result.emplace(work(watch));
      }
      finished();
      return std::move(*result);
    }
  }

  struct Shared {
    std::mutex mutex;
    std::condition_variable done_changed;
    bool done = false;
  } shared;
  [[maybe_unused]] std::conditional_t<std::is_void_v<Result>, bool, std::optional<Result>> result{};
  std::exception_ptr failure;
  std::thread worker([&] {
    try {
      if constexpr (std::is_void_v<Result>) work(watch);
      else result.emplace(work(watch));
    } catch (...) {
      failure = std::current_exception();
    }
    const std::lock_guard lock(shared.mutex);
    shared.done = true;
    shared.done_changed.notify_one();
  });

  std::optional<py::error_already_set> stopped_by;  // the Python exception that stopped the work
  std::exception_ptr watch_failure;                  // anything else the watching threw
  for (bool done = false; !done;) {
    {
      py::gil_scoped_release release;
      std::unique_lock lock(shared.mutex);
      done = shared.done_changed.wait_for(lock, watch_interval, [&] { return shared.done; });
    }
    if (done) break;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      const double fraction = watch.fraction();
      if (reports && fraction != shown) {
        shown = fraction;
        progress(fraction);
      }
    } catch (py::error_already_set& e) {
      stopped_by.emplace(std::move(e));
      watch.cancel();
      break;
    } catch (...) {
      watch_failure = std::current_exception();
      watch.cancel();
      break;
    }
  }
  {
    py::gil_scoped_release release;  // the work stops at its next poll
    worker.join();
  }
  if (stopped_by) throw std::move(*stopped_by);
  if (watch_failure) std::rethrow_exception(watch_failure);
  if (failure) std::rethrow_exception(failure);
  finished();
  if constexpr (!std::is_void_v<Result>) return std::move(*result);
}

}  // namespace dewall_python
