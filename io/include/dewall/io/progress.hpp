// A progress indicator on standard error for long work: one line, redrawn in
// place, naming the current phase ("reading points.txt", "triangulating", …),
// its elapsed time and, when the amount of work is known, a percentage bar.
//
// It shows nothing for a phase that ends within its delay (one second by
// default): short runs stay silent. It is enabled only when the output stream is
// a terminal (a log file or a pipe gets no carriage returns) and never with
// --quiet; the caller decides through `enabled`.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace dewall::io {

/// True when standard error is a terminal.
bool stderr_is_terminal();

/// The indicator. A background thread redraws the line every tenth of a second,
/// so a phase that blocks in one long call (the triangulation) still shows its
/// elapsed time. `advance_to` is a relaxed atomic store: cheap enough to call
/// every few thousand items from a hot loop.
class Progress {
 public:
  /// `enabled` false makes every call a no-op (no thread is started).
  /// `delay_seconds`: how long a phase runs before it is shown.
  explicit Progress(bool enabled, std::FILE* out = stderr, double delay_seconds = 1.0);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Starts a phase (ending the previous one). `total` > 0: the amount of work,
  /// reported through advance_to, shown as a percentage bar.
  void phase(const std::string& name, std::uint64_t total = 0);
  /// Work done so far in the current phase (0 … total).
  void advance_to(std::uint64_t done) { done_.store(done, std::memory_order_relaxed); }
  /// Ends the current phase: if it was shown, its line is completed with the
  /// total time and a newline.
  void finish();
  bool enabled() const { return enabled_; }

 private:
  void run();
  void draw(bool final_line);  // with mutex_ held

  bool enabled_;
  std::FILE* out_;
  double delay_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
  bool stop_ = false;
  bool active_ = false;  // a phase is running
  bool shown_ = false;   // its line has been drawn at least once
  std::string name_;
  std::uint64_t total_ = 0;
  std::atomic<std::uint64_t> done_{0};
  double start_ = 0;
};

}  // namespace dewall::io
