// A list of trivially copyable values that a hot loop appends to and clears
// again and again, keeping its storage: std::vector's interface, with an
// append that is always inlined.
#pragma once

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "dewall/detail/common/assert.hpp"

namespace dewall::detail {

/// Why not std::vector: with link-time optimisation GCC kept
/// std::vector::push_back out of line in the 2D cavity search (a call for
/// every cell in conflict and every new cell). Here the append is a compare, a store and an
/// increment; growing is the out-of-line rare case.
template <class T>
class Scratch_list {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  Scratch_list() = default;
  Scratch_list(const Scratch_list&) = default;
  Scratch_list& operator=(const Scratch_list&) = default;
  /// A moved-from list is empty (its size would otherwise outlive its storage).
  Scratch_list(Scratch_list&& other) noexcept
      : storage_(std::move(other.storage_)), size_(std::exchange(other.size_, 0)) {}
  Scratch_list& operator=(Scratch_list&& other) noexcept {
    storage_ = std::move(other.storage_);
    size_ = std::exchange(other.size_, 0);
    return *this;
  }

  /// By value: x may be one of the list's own elements (growing moves them).
  [[gnu::always_inline]] void push_back(T x) {
    if (size_ == storage_.size()) [[unlikely]]
      grow();
    storage_[size_++] = x;
  }
  void clear() { size_ = 0; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T& operator[](std::size_t k) {
    DEWALL_EXPENSIVE_ASSERT(k < size_);
    return storage_[k];
  }
  const T& operator[](std::size_t k) const {
    DEWALL_EXPENSIVE_ASSERT(k < size_);
    return storage_[k];
  }
  const T* begin() const { return storage_.data(); }
  const T* end() const { return storage_.data() + size_; }

 private:
  [[gnu::noinline]] void grow() { storage_.resize(std::max<std::size_t>(64, 2 * storage_.size())); }

  std::vector<T> storage_;
  std::size_t size_ = 0;
};

}  // namespace dewall::detail
