// orientation_d: the sign of det[p_1 − p_0, …, p_D − p_0].
//
// Sign convention (CGAL's): POSITIVE when p_0 … p_D are positively oriented, e.g.
// counterclockwise in 2D, and in 3D when p_3 lies on the positive side of the
// plane through p_0, p_1, p_2 oriented by (p_1 − p_0) × (p_2 − p_0). ZERO when the
// points are affinely dependent. Orientation is never perturbed.
//
// Where the including file's compile flags are unsafe (floating_point.hpp),
// only the declarations below are seen, and the calls go to the instantiations
// compiled into dewall::kernel (kernel/src/predicates.cpp, D = 2 … 6).
#pragma once

#include <optional>

#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/sign.hpp"

namespace dewall::kernel {

template <int D>
using Orientation_points = Point_refs<D, D + 1>;

/// The static filter alone: a proven sign, or nothing (in any floating-point
/// environment of the caller: error_bounds.hpp).
template <int D>
std::optional<Sign> orientation_d_filter(const Orientation_points<D>& p);
/// The interval stage alone.
template <int D>
std::optional<Sign> orientation_d_interval(const Orientation_points<D>& p);
/// The running-error stage alone (nothing outside the filter's domain).
template <int D>
std::optional<Sign> orientation_d_running_error(const Orientation_points<D>& p);
/// The exact stage alone (128-bit integers or GMP).
template <int D>
Sign orientation_d_exact(const Orientation_points<D>& p);
/// The filtered predicate: exact for every finite input, in any floating-point
/// environment of the caller (the filter needs none; the later stages run
/// under an Fp_environment_guard).
/// \pre every coordinate is finite. Cost: O(D·2^D) flops when the filter decides.
template <int D>
Sign orientation_d(const Orientation_points<D>& p);

/// Convenience form: orientation_d(p0, p1, …, pD).
template <int D, class... Rest>
  requires(sizeof...(Rest) == D)
Sign orientation_d(const Point_d<D>& p0, const Rest&... rest) {
  return orientation_d<D>(Orientation_points<D>{&p0, &rest...});
}

}  // namespace dewall::kernel

#ifndef DEWALL_UNSAFE_FP_FLAGS
#include "dewall/kernel/filtered_predicate.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::kernel {

template <int D>
struct Orientation_recipe {
  static constexpr int arity = D + 1;
  static constexpr int size = D;
  static constexpr int spatial_columns = D;
  static constexpr double epsilon = error_bounds::orientation_epsilon(D);
  static constexpr Sign sign_adjust = POSITIVE;
  static constexpr int origin = 0;  // rows p_{i+1} − p_0

  /// Writes the matrix into m (the exact stage reuses m's integers: no allocation).
  template <class T, class Coord>
  static void fill(Matrix<T, size>& m, const Coord& c) {
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j)
        m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = c(i + 1, j) - c(0, j);
  }
  template <class T, class Coord>
  static Matrix<T, size> matrix(const Coord& c) {
    Matrix<T, size> m;
    fill(m, c);
    return m;
  }
  static Predicate_stats& stats() { return predicate_stats().orientation[D]; }
};

template <int D>
std::optional<Sign> orientation_d_filter(const Orientation_points<D>& p) {
  return stages::filter<Orientation_recipe<D>, D>(p);
}
template <int D>
std::optional<Sign> orientation_d_interval(const Orientation_points<D>& p) {
  const Fp_environment_guard guard;
  return stages::interval<Orientation_recipe<D>, D>(p);
}
template <int D>
std::optional<Sign> orientation_d_running_error(const Orientation_points<D>& p) {
  const Fp_environment_guard guard;
  return stages::running_error_in_domain<Orientation_recipe<D>, D>(p);
}
template <int D>
Sign orientation_d_exact(const Orientation_points<D>& p) {
  const Fp_environment_guard guard;
  return stages::exact<Orientation_recipe<D>, D>(p);
}
template <int D>
Sign orientation_d(const Orientation_points<D>& p) {
  return stages::filtered<Orientation_recipe<D>, D>(p);
}

// The instantiations compiled into dewall::kernel (kernel/src/predicates.cpp
// expands this with an empty PREFIX). Declared `extern` here, so that a file
// including this header never emits its own out-of-line copy (it may still
// inline the fast path): no copy compiled with a user's flags can stand in for
// the library's at link time (floating_point.hpp).
#define DEWALL_ORIENTATION_INSTANTIATION(PREFIX, D)                                           \
  PREFIX template std::optional<Sign> orientation_d_filter<D>(const Orientation_points<D>&);   \
  PREFIX template std::optional<Sign> orientation_d_interval<D>(const Orientation_points<D>&); \
  PREFIX template std::optional<Sign> orientation_d_running_error<D>(const Orientation_points<D>&); \
  PREFIX template Sign orientation_d_exact<D>(const Orientation_points<D>&);                   \
  PREFIX template Sign orientation_d<D>(const Orientation_points<D>&);                         \
  PREFIX template Sign stages::after_filter<Orientation_recipe<D>, D>(const Orientation_points<D>&, double, bool);
#define DEWALL_EXTERN_ORIENTATION(D) DEWALL_ORIENTATION_INSTANTIATION(extern, D)
DEWALL_FOR_EACH_DIMENSION(DEWALL_EXTERN_ORIENTATION)
#undef DEWALL_EXTERN_ORIENTATION

}  // namespace dewall::kernel
DEWALL_FLOATING_POINT_CODE_END
#endif
