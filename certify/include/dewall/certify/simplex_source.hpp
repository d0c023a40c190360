// Where the certifier reads simplices from: rows of D + 1 input indices, handed
// over a block at a time, so that a file is never held twice (its rows as read
// and the certifier's own copy) and a list larger than memory can stream.
// Topology only: nothing here knows the kernel.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "dewall/certify/report.hpp"

namespace dewall::certify {

/// A simplex as D + 1 input indices, in any order.
template <int D>
using Simplex_indices = std::array<std::uint32_t, D + 1>;

/// Rows read in order, a block at a time: a file reader, an MPI rank's share,
/// a CGAL triangulation's cells. The certifier reads each row exactly once,
/// from the first to the last.
template <int D>
class Simplex_source {
 public:
  virtual ~Simplex_source() = default;
  /// Fills the front of `rows` with the next rows and returns how many (at most
  /// rows.size(); 0 only at the end). \throws whatever the source throws for
  /// unreadable input; the certifier lets it through.
  virtual std::size_t read(std::span<Simplex_indices<D>> rows) = 0;
  /// The number of rows still to come when known (to reserve memory), else npos.
  virtual std::size_t remaining() const { return npos; }
};

/// The rows of a span (read, never copied whole).
template <int D>
class Span_source final : public Simplex_source<D> {
 public:
  explicit Span_source(std::span<const Simplex_indices<D>> rows) : rows_(rows) {}
  std::size_t read(std::span<Simplex_indices<D>> out) override {
    const std::size_t k = std::min(out.size(), rows_.size() - next_);
    std::copy(rows_.begin() + static_cast<std::ptrdiff_t>(next_), rows_.begin() + static_cast<std::ptrdiff_t>(next_ + k),
              out.begin());
    next_ += k;
    return k;
  }
  std::size_t remaining() const override { return rows_.size() - next_; }

 private:
  std::span<const Simplex_indices<D>> rows_;
  std::size_t next_ = 0;
};

}  // namespace dewall::certify
