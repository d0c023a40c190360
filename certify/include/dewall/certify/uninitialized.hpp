// Vectors whose new elements are left uninitialised: for the large arrays
// that threads fill element by element (every element written before it is
// read), so that growing them does not first clear their memory on one core.
#pragma once

#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace dewall::certify::detail {

/// std::allocator, but construct() with no arguments default-initialises
/// (for trivial types: leaves the memory as it is).
template <class T>
struct Uninitialized_allocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = Uninitialized_allocator<U>;
  };
  Uninitialized_allocator() = default;
  template <class U>
  Uninitialized_allocator(const Uninitialized_allocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// A vector whose resize(n) leaves the new elements unwritten.
template <class T>
using Uninitialized_vector = std::vector<T, Uninitialized_allocator<T>>;

}  // namespace dewall::certify::detail
