// Where an engine's simplices go. Either collected in output order and handed
// over once the triangulation is complete (the same order for every number of
// threads), or streamed as they are built (Options::stream): then only a block
// per task is in memory (and, with Engine::automatic, what is held until the
// first region is kept), and with several threads the order depends on their
// timing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <mutex>
#include <span>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "dewall/detail/common/index.hpp"

namespace dewall::detail {

/// A simplex (input indices) with the recursion level of the wall that built
/// it (0: the first wall, and every simplex the incremental engine built).
template <int D>
struct Built_simplex {
  Simplex<D> vertices;
  std::uint8_t wall_level;
};

template <int D>
class Cell_graph_output;

class Progress_meter;

/// The receiver of an engine's simplices, block by block: in output order when
/// collected or on one thread. Never called concurrently.
template <int D>
class Simplex_output {
 public:
  /// A receiver of the whole triangulation with its adjacency
  /// (cell_graph_output.hpp), or null. An engine that holds the adjacency
  /// (the project's incremental construction, also when it takes over from
  /// the walls) gives it there instead of calling expect() and put(); the
  /// others call put() as ever.
  virtual Cell_graph_output<D>* cell_graph() { return nullptr; }
  /// The number of simplices about to be put, when it is known before the
  /// first put (collected output): a receiver may reserve room.
  virtual void expect(std::size_t /*count*/) {}
  virtual void put(std::span<const Built_simplex<D>> block) = 0;
  /// Called at most once, when the engine will not read the input points again (the
  /// project's incremental construction, once it has copied them in its
  /// insertion order, before it inserts any; the walls over the project's
  /// kernel, once their point set has copied them: Point_set::reads_input):
  /// a receiver whose caller owns the points may free them. Before any put().
  /// (An engine taking over from the walls reads the copy they restored and
  /// tells that copy's owner instead: automatic_engine.hpp.)
  virtual void input_no_longer_read() {}
  /// Whether input_no_longer_read() lets the caller free the points. If not,
  /// the walls keep the caller's points for a hand-over instead of making a
  /// copy of their own to give back (dewall_engine.hpp).
  virtual bool frees_input() const { return false; }
  /// Where the engines report their progress and learn that the caller
  /// stopped them (progress_meter.hpp, Options::progress), or null.
  virtual Progress_meter* progress() { return nullptr; }

 protected:
  ~Simplex_output() = default;
};

/// The simplices of parallel tasks, passed on to one Simplex_output under a
/// lock. A held stream keeps them until release(): Engine::automatic may still
/// hand over to the incremental engine, and what was passed on could not be
/// taken back (handover_rule.hpp, Handover_decision). Held simplices are kept
/// in the blocks they came in (no growing array whose reallocation doubles
/// the peak).
template <int D>
class Simplex_stream {
 public:
  Simplex_stream(Simplex_output<D>& out, bool held) : out_(out), holding_(held) {}

  /// \throws what the output throws; once it has thrown, the same exception
  /// again for every later block, so that the other tasks stop at their next
  /// block instead of triangulating on for an output that is gone (and
  /// whichever task's exception TBB passes on, the caller sees the output's).
  void put(std::span<const Built_simplex<D>> block) {
    const std::lock_guard lock(mutex_);
    if (failure_) std::rethrow_exception(failure_);
    if (holding_) held_.emplace_back(block.begin(), block.end());
    else pass_on(block);
  }
  /// Passes on what was held, and from now on every block at once.
  void release() {
    const std::lock_guard lock(mutex_);
    if (!holding_ || failure_) return;
    holding_ = false;
    for (auto& b : held_) {
      pass_on(b);
      std::vector<Built_simplex<D>>().swap(b);
    }
    held_.clear();
  }

 private:
  void pass_on(std::span<const Built_simplex<D>> block) {
    try {
      // The caller's output may itself run TBB work; isolated, a thread
      // waiting in it cannot pick up one of our tasks, which would call
      // put() again on this thread and lock the mutex it holds.
      tbb::this_task_arena::isolate([&] { out_.put(block); });
    } catch (...) {
      failure_ = std::current_exception();
      throw;
    }
  }

  Simplex_output<D>& out_;
  std::mutex mutex_;
  bool holding_;
  std::exception_ptr failure_;
  std::vector<std::vector<Built_simplex<D>>> held_;
};

/// A task's built simplices. Collecting: in output order, in blocks of fixed
/// capacity, so that a push never moves earlier simplices and the parallel
/// recursion joins its subproblems' output by moving blocks, not simplices
/// (copying between growing buffers and the page faults of their new memory
/// showed in profiles: docs/engines.md). Streaming: one
/// block, passed to the stream whenever it is full and by flush().
template <int D>
class Built_simplices {
 public:
  explicit Built_simplices(Simplex_stream<D>* stream = nullptr) : stream_(stream) {}

  Simplex_stream<D>* stream() const { return stream_; }

  void push_back(const Built_simplex<D>& s) {
    if (blocks_.empty() || blocks_.back().size() == block_capacity) {
      if (stream_ && !blocks_.empty()) {
        stream_->put(blocks_.back());  // and the block is filled again
        blocks_.back().clear();
      } else {
        blocks_.emplace_back();
        blocks_.back().reserve(block_capacity);
      }
    }
    blocks_.back().push_back(s);
    ++size_;
  }
  /// Streaming: passes on the simplices not passed on yet, and frees the
  /// block: a task flushes before its subproblems run and when it ends, and
  /// kept, its block would be held meanwhile (streaming 10^6 points on two
  /// threads: 9 MB of such blocks at the peak).
  void flush() {
    if (!stream_ || blocks_.empty()) return;
    if (!blocks_.back().empty()) stream_->put(blocks_.back());
    blocks_.clear();
  }
  /// Appends `other`'s simplices after this one's (streaming: passes them on).
  void append(Built_simplices&& other) {
    if (stream_) {
      other.flush();
    } else {
      for (auto& b : other.blocks_) blocks_.push_back(std::move(b));
      other.blocks_.clear();
    }
    size_ += std::exchange(other.size_, 0);
  }
  /// The number of simplices pushed, streamed ones included.
  std::size_t size() const { return size_; }
  /// Collecting: hands the simplices to `out` in order, releasing each block
  /// once handed (the collected list and a copy of it are never both whole).
  /// Streaming: flush().
  void hand_to(Simplex_output<D>& out) {
    if (stream_) return flush();
    out.expect(size_);
    for (auto& b : blocks_) {
      out.put(b);
      std::vector<Built_simplex<D>>().swap(b);
    }
    blocks_.clear();
  }

 private:
  static constexpr std::size_t block_capacity = 8192;
  Simplex_stream<D>* stream_;
  std::vector<std::vector<Built_simplex<D>>> blocks_;
  std::size_t size_ = 0;
};

}  // namespace dewall::detail
