#include "dewall/io/progress.hpp"

#include <algorithm>
#include <chrono>
#include <unistd.h>

namespace dewall::io {
namespace {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

Progress::Progress(bool enabled, std::FILE* out, double delay_seconds)
    : enabled_(enabled), out_(out), delay_(delay_seconds) {
  if (enabled_) thread_ = std::thread([this] { run(); });
}

Progress::~Progress() {
  if (!enabled_) return;
  finish();
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void Progress::phase(const std::string& name, std::uint64_t total) {
  if (!enabled_) return;
  finish();
  std::lock_guard lock(mutex_);
  name_ = name;
  total_ = total;
  done_.store(0, std::memory_order_relaxed);
  start_ = now_seconds();
  active_ = true;
  shown_ = false;
}

void Progress::finish() {
  if (!enabled_) return;
  std::lock_guard lock(mutex_);
  if (active_ && shown_) draw(true);
  active_ = false;
  shown_ = false;
}

void Progress::run() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, std::chrono::milliseconds(100));
    if (!stop_ && active_ && now_seconds() - start_ >= delay_) draw(false);
  }
}

void Progress::draw(bool final_line) {
  const double elapsed = now_seconds() - start_;
  // "\r\033[K": back to the start of the line and clear it, so a shorter line
  // leaves no remains of a longer one.
  if (total_ > 0) {
    const std::uint64_t done = std::min(done_.load(std::memory_order_relaxed), total_);
    const double fraction = final_line ? 1.0 : static_cast<double>(done) / static_cast<double>(total_);
    constexpr int width = 30;
    const int filled = static_cast<int>(fraction * width);
    char bar[width + 1];
    for (int i = 0; i < width; ++i) bar[i] = i < filled ? '#' : '.';
    bar[width] = '\0';
    std::fprintf(out_, "\r\033[K%s [%s] %3d%%  %.1f s", name_.c_str(), bar, static_cast<int>(fraction * 100), elapsed);
  } else {
    std::fprintf(out_, "\r\033[K%s… %.1f s", name_.c_str(), elapsed);
  }
  if (final_line) std::fputc('\n', out_);
  std::fflush(out_);
  shown_ = true;
}

}  // namespace dewall::io
