// orientation_d: the sign of det[p_1 − p_0, …, p_D − p_0].
//
// Sign convention (CGAL's): POSITIVE when p_0 … p_D are positively oriented, e.g.
// counterclockwise in 2D, and in 3D when p_3 lies on the positive side of the
// plane through p_0, p_1, p_2 oriented by (p_1 − p_0) × (p_2 − p_0). ZERO when the
// points are affinely dependent. Orientation is never perturbed.
#pragma once

#include "dewall/kernel/filtered_predicate.hpp"

namespace dewall::kernel {

template <int D>
struct Orientation_recipe {
  static constexpr int arity = D + 1;
  static constexpr int size = D;
  static constexpr int spatial_columns = D;
  static constexpr double epsilon = error_bounds::orientation_epsilon(D);
  static constexpr Sign sign_adjust = POSITIVE;

  template <class T, class Coord>
  static Matrix<T, size> matrix(const Coord& c) {
    Matrix<T, size> m;
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j)
        m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = c(i + 1, j) - c(0, j);
    return m;
  }
  static Predicate_stats& stats() { return predicate_stats().orientation[D]; }
};

template <int D>
using Orientation_points = stages::Point_refs<D, D + 1>;

/// The static filter alone: a proven sign, or nothing.
template <int D>
std::optional<Sign> orientation_d_filter(const Orientation_points<D>& p) {
  return stages::filter<Orientation_recipe<D>, D>(p);
}
/// The interval stage alone.
template <int D>
std::optional<Sign> orientation_d_interval(const Orientation_points<D>& p) {
  return stages::interval<Orientation_recipe<D>, D>(p);
}
/// The exact stage alone (GMP).
template <int D>
Sign orientation_d_exact(const Orientation_points<D>& p) {
  return stages::exact<Orientation_recipe<D>, D>(p);
}
/// The filtered predicate: exact for every finite input.
/// \pre every coordinate is finite. Cost: O(D·2^D) flops when the filter decides.
template <int D>
Sign orientation_d(const Orientation_points<D>& p) {
  return stages::filtered<Orientation_recipe<D>, D>(p);
}
/// Convenience form: orientation_d(p0, p1, …, pD).
template <int D, class... Rest>
  requires(sizeof...(Rest) == D)
Sign orientation_d(const Point_d<D>& p0, const Rest&... rest) {
  return orientation_d<D>(Orientation_points<D>{&p0, &rest...});
}

}  // namespace dewall::kernel
