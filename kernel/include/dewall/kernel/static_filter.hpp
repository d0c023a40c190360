// Static_filter_d<D>: the filter stage of orientation_d and
// side_of_oriented_sphere_d with its error bound computed once, from a box
// that holds every point the predicates will see (the incremental engine's
// input), instead of from each call's column maxima.
//
// Derivation (error_bounds.hpp, steps 1–4, with the same recipes and the same
// `determinant`, so the computed determinant is the filter stage's, bit for bit):
//  * Step 2 bounds |fl(det) − det| by γ_N·K!·Π_j M_j, M_j the largest exact
//    |entry| of column j. For points in the box [lo, hi], a spatial entry is a
//    difference of two coordinates in [lo_j, hi_j], so M_j ≤ hi_j − lo_j; a
//    lifted entry is a sum of D squared differences, at most Σ_j (hi_j − lo_j)².
//    S_j below are those extents, computed and then enlarged by (1 + 2^-40),
//    which more than covers the few roundings of computing them (any rounding
//    mode: a relative error of at most 2^-52 each). So S_j ≥ M_j.
//  * Hence B = ε_K·Π_j S_j ≥ the step-3 bound for every call (computed B is
//    rounded K times, covered by ε's (1 + 2^-30) margin as in step 3), and
//    |fl(det)| > B proves sign(fl(det)) = sign(det).
//  * Step 4, the domain: valid when every S_j lies in [2^-100, 2^100]. No value
//    overflows (as in step 4). Underflow: every lost product or entry (< 2^-1022,
//    also under FTZ/DAZ) is multiplied afterwards by at most the other factors
//    of its monomial, spatial entries ≤ 2^100 and lifted ones ≤ 3·2^200, in at
//    most K!·K places: for D ≤ 3 (K ≤ 4) the total is below
//    2^7·2^-1022·3·2^400 < 2^-613. B's margin share, 2^-30·ε·Π_j S_j, is at
//    least 2^-79·(2^-100)^3·2^-200 = 2^-579 (ε ≥ 2^-49, lifted S ≥ 2^-200),
//    larger. An entry smaller than the box allows only shrinks the other
//    terms. So the filter is offered in 2D and 3D, where this was checked;
//    above, the semi-static filter of each call does the work. Outside the
//    domain the filter never decides.
// It runs before the semi-static filter (which computes the column maxima per
// call) and decides nearly every call on well-spread input; what it leaves,
// the full cascade decides. Tested against GMP on every family of
// test_predicates_vs_gmp.cpp.
#pragma once

#include <array>
#include <optional>

#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/side_of_sphere.hpp"

#ifndef DEWALL_UNSAFE_FP_FLAGS
DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::kernel {

template <int D>
class Static_filter_d {
 public:
  /// Whether the filter exists in dimension D (see the derivation).
  static constexpr bool available = D <= 3;

  /// A filter that never decides.
  Static_filter_d() = default;
  /// The filter for points inside the box [lo, hi] (lo ≤ hi, finite).
  Static_filter_d(const std::array<double, D>& lo, const std::array<double, D>& hi) {
    if constexpr (!available) return;
    constexpr double margin = 1 + 0x1p-40;
    std::array<double, D> s;
    double lifted = 0;
    for (int j = 0; j < D; ++j) {
      s[j] = (hi[j] - lo[j]) * margin;
      if (!(s[j] >= error_bounds::min_column_max && s[j] <= error_bounds::max_column_max)) return;
      lifted += s[j] * s[j];
    }
    lifted *= margin * margin;
    double orientation = Orientation_recipe<D>::epsilon, sphere = Side_of_sphere_recipe<D>::epsilon;
    for (int j = 0; j < D; ++j) {
      orientation *= s[j];
      sphere *= s[j];
    }
    orientation_bound_ = orientation * margin;
    sphere_bound_ = sphere * lifted * margin;
    valid_ = true;
  }

  bool valid() const { return valid_; }

  /// orientation_d's sign when the static bound proves it. \pre the points lie in the box.
  [[gnu::always_inline]] std::optional<Sign> orientation(const Orientation_points<D>& p) const {
    return decide<Orientation_recipe<D>, D + 1>(p, orientation_bound_);
  }
  /// side_of_oriented_sphere_d's sign (unperturbed) when the static bound proves it.
  /// \pre the points lie in the box.
  [[gnu::always_inline]] std::optional<Sign> side_of_oriented_sphere(const Sphere_points<D>& p) const {
    return decide<Side_of_sphere_recipe<D>, D + 2>(p, sphere_bound_);
  }

 private:
  template <class Recipe, int N>
  [[gnu::always_inline]] std::optional<Sign> decide(const Point_refs<D, N>& p, double bound) const {
    if (!valid_) return std::nullopt;
    const auto m = Recipe::template matrix<double>([&](int i, int j) { return (*p[static_cast<std::size_t>(i)])[j]; });
    const double det = determinant<double, Recipe::size>(m);
    if (det > bound) return Recipe::sign_adjust;
    if (det < -bound) return -Recipe::sign_adjust;
    return std::nullopt;
  }

  bool valid_ = false;
  double orientation_bound_ = 0, sphere_bound_ = 0;
};

}  // namespace dewall::kernel
DEWALL_FLOATING_POINT_CODE_END
#endif
