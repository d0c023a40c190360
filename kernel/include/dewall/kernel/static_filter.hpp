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
// call; in 3D a caller may ask for that one first, where the box's bound
// leaves many calls: Semi_static_first) and decides nearly every call on
// well-spread input; what it leaves, the full cascade decides. Tested against GMP on every family of
// test_predicates_vs_gmp.cpp.
//
// Exact evaluation on a lattice. On a lattice every sphere test ties and
// would run the whole cascade to learn that it is zero (on a 10^6-point grid
// half the construction's time). When every coordinate is an integer
// multiple of u = 2^e (`unit_exponent`, e.g. 0 for integers), the filter's
// double determinant is the exact determinant, so it decides every call,
// zeros included, when the bound below holds:
//  * a spatial entry is a difference of two multiples of u, so a multiple of
//    u of magnitude ≤ S_j (computed exactly when representable: the
//    difference of two doubles is); a lifted entry a multiple of u², ≤ the
//    lifted S. (S_j ≥ u for the points' own box; a factor < 1 counts as 1.)
//  * determinant.hpp forms each minor of the last r rows as a sum, over the
//    columns j of its set, of an entry times a smaller minor. By induction
//    every value computed (entry, product, partial sum, minor) is exact: the
//    true value is a signed partial sum of the monomials of one sub-matrix,
//    each monomial a multiple of u^k (k = the degree of the sub-matrix's
//    columns: 1 per spatial, 2 per lifted column) — so the value is m·u^k, m
//    an integer with |m| ≤ the sub-matrix's permanent in units
//    ≤ P = K!·Π_j (S_j / u^deg_j) (every factor ≥ 1, so the full product
//    bounds every sub-matrix's). If P < 2^53, m·u^k is a double, and rounding
//    (in any mode) returns it unchanged. (A factor below 1 — a box thinner
//    than u — is counted as 1.)
//  * Range: with −200 ≤ e ≤ 100 and k ≤ D + 2 ≤ 5, u^k lies in
//    [2^-1000, 2^500]: every non-zero value is a normal double (so FTZ/DAZ
//    change nothing) and none overflows.
// Beyond that bound, each call's own: when the box's lifted extent is below
// 2^52·u², every entry is still computed exactly (a multiple of u, or of u²,
// below 2^53 units), so the column maxima M_j of the call's matrix are
// exact, and the induction above holds with M_j in place of S_j: if
// P = K!·Π_j max(M_j / u^deg_j, 1) < 2^52 (computed in a few roundings of
// relative 2^-52 each, in any mode: the halved limit covers them), the
// call's double determinant is exact, zero included. On a lattice sphere
// too wide for the static bound (every sphere test a tie, R ≈ 1,400) this
// decided what the cascade's exact_in_double did, at a fraction of its cost.
// Points inserted later must lie on the same lattice (Incremental_delaunay
// tells the filter their unit: admit_lattice).
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>

#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/side_of_sphere.hpp"

#ifndef DEWALL_UNSAFE_FP_FLAGS
DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::kernel {

/// The exponent e of x's lowest set bit (x = odd integer · 2^e), for finite
/// non-zero x; INT_MAX for zero (a multiple of every unit). The smallest over
/// a point set's coordinates is its lattice unit (Static_filter_d's exactness).
inline int lowest_bit_exponent(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const auto biased = static_cast<int>(bits >> 52 & 0x7ff);
  const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
  if (biased == 0)  // zero or subnormal: fraction · 2^-1074
    return fraction == 0 ? INT_MAX : std::countr_zero(fraction) - 1074;
  return std::countr_zero(fraction | std::uint64_t{1} << 52) + biased - 1075;
}

template <int D>
class Static_filter_d {
 public:
  /// Whether the filter exists in dimension D (see the derivation).
  static constexpr bool available = D <= 3;

  /// A filter that never decides.
  Static_filter_d() = default;
  /// The filter for points inside the box [lo, hi] (lo ≤ hi, finite).
  Static_filter_d(const std::array<double, D>& lo, const std::array<double, D>& hi)
      : Static_filter_d(lo, hi, INT_MIN) {}
  /// The filter for points inside [lo, hi] whose coordinates are all integer
  /// multiples of 2^unit_exponent (INT_MIN: not known to be): exact (it
  /// decides every call, zeros included) when the derivation's bound holds.
  Static_filter_d(const std::array<double, D>& lo, const std::array<double, D>& hi, int unit_exponent) {
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
    if (unit_exponent < -200 || unit_exponent > 100) return;
    // P for the sphere's matrix ((D+1)!·Π_j S_j/u · lifted/u²), which bounds
    // the orientation's (D!·Π_j S_j/u, every factor ≥ 1); computed with a
    // relative error far below the margin.
    // A factor below 1 (a box thinner than u: the points share that
    // coordinate) is taken as 1, so that P still bounds every sub-matrix.
    const double unit = std::ldexp(1.0, unit_exponent);
    if (!(lifted / unit / unit < 0x1p52)) return;
    double permanent = std::max(lifted / unit / unit, 1.0);
    for (int j = 0; j < D; ++j) permanent *= std::max(s[j] / unit, 1.0) * (j + 2);
    exact_ = permanent * margin < 0x1p53;
    unit_exponent_ = unit_exponent;
    inverse_unit_ = std::ldexp(1.0, -unit_exponent);
  }

  bool valid() const { return valid_; }
  /// Whether the filter decides every call (points on a small lattice).
  bool exact() const { return exact_; }
  /// Whether the filter knows its points' lattice: it then decides every
  /// call whose own bound holds (exact() or not).
  bool on_lattice() const { return unit_exponent_ != INT_MAX; }
  /// More points are coming whose coordinates are multiples of
  /// 2^unit_exponent: exactness stays only if that lattice is within the
  /// filter's (the static bound stays in any case).
  void admit_lattice(int unit_exponent) {
    if (unit_exponent < unit_exponent_) {
      exact_ = false;
      unit_exponent_ = INT_MAX;
    }
  }

  /// orientation_d's sign when the static bound proves it (always when
  /// exact(); ZERO only then). \pre the points lie in the box (and on the lattice).
  [[gnu::always_inline]] Maybe_sign orientation(const Orientation_points<D>& p) const {
    return decide<Orientation_recipe<D>, D + 1>(p, orientation_bound_);
  }
  /// side_of_oriented_sphere_d's sign (unperturbed) when the static bound
  /// proves it (always when exact(); ZERO only then).
  /// \pre the points lie in the box (and on the lattice).
  [[gnu::always_inline]] Maybe_sign side_of_oriented_sphere(const Sphere_points<D>& p) const {
    return decide<Side_of_sphere_recipe<D>, D + 2>(p, sphere_bound_);
  }
  /// side_of_oriented_sphere_d's sign (unperturbed), always: the static
  /// bound first, in 3D then the semi-static one (semi_static_decision),
  /// then the filter cascade (stages::filtered_after_static) on the same
  /// matrix and determinant. On surface samples, whose cells are
  /// small against the box, the static bound leaves most calls, and the
  /// cascade computing the determinant again took a tenth of a torus's
  /// construction. \pre the points lie in the box (and on the lattice).
  [[gnu::always_inline]] Sign side_of_oriented_sphere_sign(const Sphere_points<D>& p) const {
    return *sphere_through_filters<true>(p);
  }
  /// The same, with the semi-static bound tried before the box's when
  /// Semi_static_first (3D: where the box's bound leaves many calls, its
  /// branch mispredicts; Incremental_delaunay::choose_filter_order). When the
  /// box's bound is tried first, box_bound_left counts the calls it leaves
  /// (and the lattice's own bound after it).
  template <bool Semi_static_first>
  [[gnu::always_inline]] Sign side_of_oriented_sphere_sign(const Sphere_points<D>& p,
                                                           std::uint32_t& box_bound_left) const {
    return *sphere_through_filters<true, Semi_static_first>(p, &box_bound_left);
  }
  /// Whether side_of_oriented_sphere_pair computes its two tests at once
  /// (GCC's and Clang's vector extension, 3D) rather than one after the other.
#if defined(__GNUC__)
  static constexpr bool pairs_sphere_tests = D == 3;
#else
  static constexpr bool pairs_sphere_tests = false;
#endif
  /// Two sphere tests' computed determinants and semi-static bounds.
  struct Sphere_pair {
    std::array<double, 2> det, bound;
  };
  /// The determinants of two sphere tests as side_of_oriented_sphere_sign
  /// computes them and, when Semi_static_first, their semi-static bounds
  /// (only then: the box's bound needs none), for
  /// side_of_oriented_sphere_sign_given; point(k, i) is test k's point i
  /// (i = 0 … D + 1, the query last), by reference (a callable: two arrays of
  /// pointers cost the cavity search's loop registers). Both at once: the
  /// recipe's matrix and determinant over two-double vectors, lane k test k.
  /// Each lane's operations are the scalar code's, each rounded once
  /// (elementwise IEEE arithmetic; no flag that reassociates:
  /// floating_point.hpp), so the derivation's bounds hold for each lane as
  /// for the scalar value; a contracted multiply-add only drops a rounding.
  /// The column maxima are exact however they are computed.
  template <bool Semi_static_first, class Points>
  [[gnu::always_inline]] static Sphere_pair side_of_oriented_sphere_pair(const Points& point) {
    using Recipe = Side_of_sphere_recipe<D>;
#if defined(__GNUC__)
    if constexpr (pairs_sphere_tests) {
      using Lanes = double __attribute__((vector_size(16)));
      using Lane_bits = std::int64_t __attribute__((vector_size(16)));
      const auto m = Recipe::template matrix<Lanes>([&](int i, int j) { return Lanes{point(0, i)[j], point(1, i)[j]}; });
      const Lanes det = determinant<Lanes, Recipe::size>(m);
      Sphere_pair pair{{det[0], det[1]}, {}};
      if constexpr (Semi_static_first) {
        // |x| by clearing the sign bit; the larger kept through the comparison's lane mask.
        const Lane_bits magnitude = Lane_bits{} + std::numeric_limits<std::int64_t>::max();
        std::array<Lanes, Recipe::size> maxima{};
        for (const auto& row : m)
          for (std::size_t j = 0; j < maxima.size(); ++j) {
            const Lane_bits x = std::bit_cast<Lane_bits>(row[j]) & magnitude;
            const Lane_bits larger = maxima[j] < std::bit_cast<Lanes>(x);
            maxima[j] = std::bit_cast<Lanes>((x & larger) | (std::bit_cast<Lane_bits>(maxima[j]) & ~larger));
          }
        const Lanes bound = side_of_oriented_sphere_semi_static_bound(maxima);
        pair.bound = {bound[0], bound[1]};
      }
      return pair;
    }
#endif
    Sphere_pair pair{};
    for (std::size_t k = 0; k < 2; ++k) {
      const auto m = Recipe::template matrix<double>([&](int i, int j) { return point(static_cast<int>(k), i)[j]; });
      pair.det[k] = determinant<double, Recipe::size>(m);
      if constexpr (Semi_static_first) {
        std::array<double, Recipe::size> maxima;
        for (int j = 0; j < Recipe::size; ++j) maxima[static_cast<std::size_t>(j)] = stages::column_max<Recipe::size>(m, j);
        pair.bound[k] = side_of_oriented_sphere_semi_static_bound(maxima);
      }
    }
    return pair;
  }
  /// side_of_oriented_sphere_sign<Semi_static_first>(p, box_bound_left),
  /// given the test's det and bound from side_of_oriented_sphere_pair: the
  /// same sign and count. \pre valid().
  template <bool Semi_static_first>
  [[gnu::always_inline]] Sign side_of_oriented_sphere_sign_given(const Sphere_points<D>& p, double det, double bound,
                                                                 std::uint32_t& box_bound_left) const {
    using Recipe = Side_of_sphere_recipe<D>;
    const Maybe_sign s = Semi_static_first && D == 3 ? bound_decision<Recipe>(det, bound)
                                                     : static_decision<Recipe>(det, sphere_bound_);
    return s ? *s : sign_after_first_bound<Semi_static_first>(p, det, box_bound_left);
  }
  /// The semi-static bound ε·Π_j M̂_j + floor (semi_static_decision) from the
  /// column maxima M̂_j, for T double or a vector of doubles (one test a lane).
  template <class T>
  [[gnu::always_inline]] static T side_of_oriented_sphere_semi_static_bound(const std::array<T, D + 1>& maxima) {
    return semi_static_bound<Side_of_sphere_recipe<D>>(maxima);
  }
  /// The same through the static and the semi-static filter only (on the
  /// same determinant): a sign when one of them proves it, else nothing —
  /// for a caller to whom an undecided test costs less than the exact stages.
  [[gnu::always_inline]] Maybe_sign side_of_oriented_sphere_filtered(const Sphere_points<D>& p) const {
    return sphere_through_filters<false>(p);
  }

 private:
  template <class Recipe, int N>
  [[gnu::always_inline]] Maybe_sign decide(const Point_refs<D, N>& p, double bound) const {
    if (!valid_) return std::nullopt;
    const auto m = Recipe::template matrix<double>([&](int i, int j) { return (*p[static_cast<std::size_t>(i)])[j]; });
    const double det = determinant<double, Recipe::size>(m);
    if (const auto s = static_decision<Recipe>(det, bound)) return s;
    return lattice_decision<Recipe>(m, det);
  }
  /// On the lattice, the call's own bound (the derivation's last part):
  /// every sign, zero included, when it holds.
  template <class Recipe>
  [[gnu::always_inline]] Maybe_sign lattice_decision(const Matrix<double, Recipe::size>& m, double det) const {
    constexpr int K = Recipe::size;
    if (!on_lattice()) return std::nullopt;
    double permanent = stages::factorial_int(K);
    for (int j = 0; j < K; ++j) {
      const double column_max = stages::column_max<K>(m, j);
      const double units = j < Recipe::spatial_columns ? column_max * inverse_unit_
                                                      : column_max * inverse_unit_ * inverse_unit_;
      permanent *= std::max(units, 1.0);
    }
    if (!(permanent < 0x1p52)) return std::nullopt;
    return det == 0 ? ZERO : det > 0 ? Recipe::sign_adjust : -Recipe::sign_adjust;
  }
  /// The static bound's decision on the computed determinant det (the
  /// derivation above), and on a lattice (exact_) every sign, zero included.
  template <class Recipe>
  [[gnu::always_inline]] Maybe_sign static_decision(double det, double bound) const {
    if (det > bound) return Recipe::sign_adjust;
    if (det < -bound) return -Recipe::sign_adjust;
    if (exact_) return det == 0 ? ZERO : det > 0 ? Recipe::sign_adjust : -Recipe::sign_adjust;
    return std::nullopt;
  }

  /// side_of_oriented_sphere_sign_given's stages after the first bound, on
  /// the matrix computed again (the same values). Out of line: on volume data
  /// the first bound decides nearly every test.
  template <bool Semi_static_first>
  [[gnu::noinline]] Sign sign_after_first_bound(const Sphere_points<D>& p, double det,
                                                std::uint32_t& box_bound_left) const {
    using Recipe = Side_of_sphere_recipe<D>;
    const auto m = Recipe::template matrix<double>([&](int i, int j) { return (*p[static_cast<std::size_t>(i)])[j]; });
    return *sphere_after_determinant<true, Semi_static_first>(p, m, det, &box_bound_left);
  }
  template <bool Every_stage, bool Semi_static_first = false>
  [[gnu::always_inline]] Maybe_sign sphere_through_filters(const Sphere_points<D>& p,
                                                           std::uint32_t* box_bound_left = nullptr) const {
    using Recipe = Side_of_sphere_recipe<D>;
    if (!valid_) {
      if constexpr (Every_stage) return stages::filtered<Recipe, D>(p);
      else return stages::filter<Recipe, D>(p);
    }
    const auto m = Recipe::template matrix<double>([&](int i, int j) { return (*p[static_cast<std::size_t>(i)])[j]; });
    const double det = determinant<double, Recipe::size>(m);
    return sphere_after_determinant<Every_stage, Semi_static_first>(p, m, det, box_bound_left);
  }
  /// sphere_through_filters once the matrix and its determinant are known. \pre valid_.
  template <bool Every_stage, bool Semi_static_first>
  [[gnu::always_inline]] Maybe_sign sphere_after_determinant(const Sphere_points<D>& p,
                                                             const Matrix<double, D + 1>& m, double det,
                                                             std::uint32_t* box_bound_left) const {
    using Recipe = Side_of_sphere_recipe<D>;
    if constexpr (Semi_static_first && D == 3) {
      if (const auto s = semi_static_decision<Recipe>(m, det)) return s;
      // The box's bound, never tighter, still decides a lattice's zeros (exact_).
      if (const auto s = static_decision<Recipe>(det, sphere_bound_)) return s;
      if (const auto s = lattice_decision<Recipe>(m, det)) return s;
      if constexpr (Every_stage) return stages::filtered_after_static<Recipe, D>(p, m, det);
      else return std::nullopt;
    }
    if (const auto s = static_decision<Recipe>(det, sphere_bound_)) return s;
    if (const auto s = lattice_decision<Recipe>(m, det)) return s;
    if (box_bound_left) ++*box_bound_left;
    if constexpr (D == 3) {
      if (const auto s = semi_static_decision<Recipe>(m, det)) return s;
      if constexpr (!Every_stage) return std::nullopt;
    }
    if constexpr (Every_stage) return stages::filtered_after_static<Recipe, D>(p, m, det);
    else return stages::filter_decision<Recipe, D>(p, m, [det] { return det; }, nullptr);
  }
  /// The semi-static bound on the computed determinant det: ε·Π_j M̂_j, each
  /// call's own column maxima (error_bounds.hpp, steps 1–3, as
  /// stages::filter_decision), plus a floor, without that stage's checks of
  /// each column against the domain. In the box they are not needed:
  ///  * no overflow: every spatial M̂_j ≤ S_j ≤ 2^100 (the box passed the
  ///    domain check), the lifted one ≤ Σ_j S_j² ≤ 3·2^200;
  ///  * underflow: step 4 asks M̂_j ≥ 2^-100 so that what underflow loses is
  ///    negligible against ε·Π_j M̂_j; in the box it is below 2^-613 whatever
  ///    the columns (the derivation above, "Underflow"), so the floor 2^-600
  ///    covers it instead, and covers ε·Π_j M̂_j when that product underflows.
  ///    The floor's sum is one rounding more, inside ε's (1 + 2^-30) margin.
  ///  * a zero column gives det = 0 exactly, below the floor: undecided, as
  ///    any call this bound leaves, for the stages after it.
  /// So the surface samples' tests (most of which the box's bound leaves: a
  /// surface's cells are small against its box) cost no branch but the
  /// sign's. In 2D, where it did not pay, the cascade's own filter stage stays.
  template <class Recipe>
  [[gnu::always_inline]] Maybe_sign semi_static_decision(const Matrix<double, Recipe::size>& m, double det) const {
    constexpr int K = Recipe::size;
    std::array<double, K> maxima;
    for (int j = 0; j < K; ++j) maxima[static_cast<std::size_t>(j)] = stages::column_max<K>(m, j);
    return bound_decision<Recipe>(det, semi_static_bound<Recipe>(maxima));
  }
  template <class Recipe, class T>
  [[gnu::always_inline]] static T semi_static_bound(const std::array<T, Recipe::size>& maxima) {
    T bound = T{} + Recipe::epsilon;
    for (const T& column_max : maxima) bound = bound * column_max;
    return bound + underflow_floor;
  }
  template <class Recipe>
  [[gnu::always_inline]] static Maybe_sign bound_decision(double det, double bound) {
    if (det > bound) return Recipe::sign_adjust;
    if (det < -bound) return -Recipe::sign_adjust;
    return std::nullopt;
  }
  static constexpr double underflow_floor = 0x1p-600;

  bool valid_ = false, exact_ = false;
  int unit_exponent_ = INT_MAX;  // INT_MAX: no lattice known (or its entries may round)
  double inverse_unit_ = 0;       // 2^-unit_exponent_
  double orientation_bound_ = 0, sphere_bound_ = 0;
};

}  // namespace dewall::kernel
DEWALL_FLOATING_POINT_CODE_END
#endif
