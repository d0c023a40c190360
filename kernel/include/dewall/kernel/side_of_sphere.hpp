// side_of_oriented_sphere_d: where q lies relative to the sphere through p_0 … p_D.
//
// Evaluated as the (D+1)×(D+1) determinant M = det[p_i − q, |p_i − q|²]_{i=0..D},
// the lifted (D+2)×(D+2) determinant translated by q.
// Sign convention (CGAL's): for a positively oriented simplex, ON_POSITIVE_SIDE
// when q is strictly inside the sphere. Derivation of the sign adjustment: M is
// a quadratic in q vanishing on the sphere, M(q) = κ·(r² − |q − c|²); at the
// centre, |p_i − c|² = r² and M(c) = r²·det[p_i, 1] = r²·(−1)^D·orientation(p),
// expanding det[p_i, 1] along its last column after subtracting row 0. So
// inside ⇔ (−1)^D·M > 0 for a positively oriented simplex.
//
// Where the including file's compile flags are unsafe (floating_point.hpp),
// only the declarations below are seen, and the calls go to the instantiations
// compiled into dewall::kernel (kernel/src/predicates.cpp, D = 2 … 6).
#pragma once

#include <optional>

#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/sign.hpp"

namespace dewall::kernel {

template <int D>
using Sphere_points = Point_refs<D, D + 2>;  // simplex, then the query

/// The stages alone: the static filter (valid in any floating-point
/// environment), the interval stage, the running-error stage (nothing outside
/// the filter's domain), the exact stage.
template <int D>
std::optional<Sign> side_of_oriented_sphere_d_filter(const Sphere_points<D>& p);
template <int D>
std::optional<Sign> side_of_oriented_sphere_d_interval(const Sphere_points<D>& p);
template <int D>
std::optional<Sign> side_of_oriented_sphere_d_running_error(const Sphere_points<D>& p);
template <int D>
Sign side_of_oriented_sphere_d_exact(const Sphere_points<D>& p);

/// The filtered, unperturbed predicate: may return ON_ORIENTED_BOUNDARY.
/// Exact in any floating-point environment of the caller (as orientation_d).
/// \pre every coordinate is finite.
template <int D>
Oriented_side side_of_oriented_sphere_d(const Sphere_points<D>& p);

/// The perturbed predicate (CGAL's lexicographic scheme, perturbation.hpp):
/// never ON_ORIENTED_BOUNDARY.
/// \pre p_0 … p_D positively oriented (orientation_d == POSITIVE), q distinct from them.
template <int D>
Oriented_side side_of_oriented_sphere_d_sos(const Sphere_points<D>& p);

/// Convenience forms: side_of_oriented_sphere_d{,_sos}(p0, …, pD, q).
template <int D, class... Rest>
  requires(sizeof...(Rest) == D + 1)
Oriented_side side_of_oriented_sphere_d(const Point_d<D>& p0, const Rest&... rest) {
  return side_of_oriented_sphere_d<D>(Sphere_points<D>{&p0, &rest...});
}
template <int D, class... Rest>
  requires(sizeof...(Rest) == D + 1)
Oriented_side side_of_oriented_sphere_d_sos(const Point_d<D>& p0, const Rest&... rest) {
  return side_of_oriented_sphere_d_sos<D>(Sphere_points<D>{&p0, &rest...});
}

}  // namespace dewall::kernel

#ifndef DEWALL_UNSAFE_FP_FLAGS
#include "dewall/kernel/filtered_predicate.hpp"
#include "dewall/kernel/perturbation.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::kernel {

template <int D>
struct Side_of_sphere_recipe {
  static constexpr int arity = D + 2;  // p_0 … p_D, then q
  static constexpr int size = D + 1;
  static constexpr int spatial_columns = D;
  static constexpr double epsilon = error_bounds::side_of_sphere_epsilon(D);
  static constexpr Sign sign_adjust = D % 2 == 0 ? POSITIVE : NEGATIVE;
  static constexpr int origin = D + 1;  // rows p_i − q

  /// Writes the matrix into m (the exact stage reuses m's integers: no allocation).
  template <class T, class Coord>
  static void fill(Matrix<T, size>& m, const Coord& c) {
    for (int i = 0; i <= D; ++i) {
      auto& row = m[static_cast<std::size_t>(i)];
      for (int j = 0; j < D; ++j) row[static_cast<std::size_t>(j)] = c(i, j) - c(D + 1, j);
      T& lifted = row[static_cast<std::size_t>(D)];
      lifted = row[0] * row[0];
      for (int j = 1; j < D; ++j) add_product(lifted, row[static_cast<std::size_t>(j)], row[static_cast<std::size_t>(j)]);
    }
  }
  template <class T, class Coord>
  static Matrix<T, size> matrix(const Coord& c) {
    Matrix<T, size> m;
    fill(m, c);
    return m;
  }
  static Predicate_stats& stats() { return predicate_stats().side_of_sphere[D]; }
};

template <int D>
std::optional<Sign> side_of_oriented_sphere_d_filter(const Sphere_points<D>& p) {
  return stages::filter<Side_of_sphere_recipe<D>, D>(p);
}
template <int D>
std::optional<Sign> side_of_oriented_sphere_d_interval(const Sphere_points<D>& p) {
  const Fp_environment_guard guard;
  return stages::interval<Side_of_sphere_recipe<D>, D>(p);
}
template <int D>
std::optional<Sign> side_of_oriented_sphere_d_running_error(const Sphere_points<D>& p) {
  const Fp_environment_guard guard;
  return stages::running_error_in_domain<Side_of_sphere_recipe<D>, D>(p);
}
template <int D>
Sign side_of_oriented_sphere_d_exact(const Sphere_points<D>& p) {
  const Fp_environment_guard guard;
  return stages::exact<Side_of_sphere_recipe<D>, D>(p);
}
template <int D>
Oriented_side side_of_oriented_sphere_d(const Sphere_points<D>& p) {
  return static_cast<Oriented_side>(stages::filtered<Side_of_sphere_recipe<D>, D>(p));
}
template <int D>
Oriented_side side_of_oriented_sphere_d_sos(const Sphere_points<D>& p) {
  const auto side = static_cast<Oriented_side>(stages::filtered<Side_of_sphere_recipe<D>, D>(p));
  if (side != ON_ORIENTED_BOUNDARY) return side;
  count(predicate_stats().side_of_sphere[D].perturbed);
  return perturbed_side_of_sphere<D>(
      p, [](const Orientation_points<D>& o) { return stages::filtered<Orientation_recipe<D>, D>(o); },
      [](const Point_d<D>& a, const Point_d<D>& b) { return compare_lexicographically(a, b) == SMALLER; });
}

// Compiled into dewall::kernel, as DEWALL_ORIENTATION_INSTANTIATION (orientation.hpp).
#define DEWALL_SIDE_OF_SPHERE_INSTANTIATION(PREFIX, D)                                             \
  PREFIX template std::optional<Sign> side_of_oriented_sphere_d_filter<D>(const Sphere_points<D>&);   \
  PREFIX template std::optional<Sign> side_of_oriented_sphere_d_interval<D>(const Sphere_points<D>&); \
  PREFIX template std::optional<Sign> side_of_oriented_sphere_d_running_error<D>(const Sphere_points<D>&); \
  PREFIX template Sign side_of_oriented_sphere_d_exact<D>(const Sphere_points<D>&);                   \
  PREFIX template Oriented_side side_of_oriented_sphere_d<D>(const Sphere_points<D>&);                \
  PREFIX template Oriented_side side_of_oriented_sphere_d_sos<D>(const Sphere_points<D>&);            \
  PREFIX template Sign stages::after_filter<Side_of_sphere_recipe<D>, D>(const Sphere_points<D>&, double, bool);
#define DEWALL_EXTERN_SIDE_OF_SPHERE(D) DEWALL_SIDE_OF_SPHERE_INSTANTIATION(extern, D)
DEWALL_FOR_EACH_DIMENSION(DEWALL_EXTERN_SIDE_OF_SPHERE)
#undef DEWALL_EXTERN_SIDE_OF_SPHERE

}  // namespace dewall::kernel
DEWALL_FLOATING_POINT_CODE_END
#endif
