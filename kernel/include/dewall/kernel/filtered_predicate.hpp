// The one cascade every predicate runs: static filter → permanent filter →
// running error (intervals outside the filter's domain) → exact.
//
// A predicate is described by a *recipe*: the K×K matrix whose determinant's
// sign it is, written once as a template over the number type. The stages below
// instantiate that recipe with double, Interval and Exact_integer; nothing about
// the cascade is repeated per predicate (compare CGAL's Filtered_predicate and
// Geogram's PCK stage templates).
//
// Recipe requirements:
//   static constexpr int arity;            number of input points
//   static constexpr int size;             K, the matrix size
//   static constexpr int spatial_columns;  columns holding coordinate differences
//   static constexpr double epsilon;       error_bounds.hpp, for this K and D
//   static constexpr Sign sign_adjust;     sign(predicate) = sign_adjust · sign(det)
//   static constexpr int origin;           the point every row is a difference from
//   template <class T, class Coord> static Matrix<T, size> matrix(const Coord& c);
//   template <class T, class Coord> static void fill(Matrix<T, size>& m, const Coord& c);  (the same, in place)
//       c(i, j) is coordinate j of input point i, as a T (or as a type whose
//       difference is a T: Exact_coordinate, running_error.hpp).
// The matrix's determinant is, up to a sign fixed by the recipe, an alternating
// function of the input points (det[p_i, 1] for orientation, the lifted
// det[p_i, |p_i|², 1] for the sphere test), so exchanging two points negates it;
// the running-error stage uses that to choose its origin.
//   static Predicate_stats& stats();
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "dewall/kernel/determinant.hpp"
#include "dewall/kernel/error_bounds.hpp"
#include "dewall/kernel/exact_integer.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/interval.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/predicate_stats.hpp"
#include "dewall/kernel/running_error.hpp"
#include "dewall/kernel/sign.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::kernel::stages {

/// max(m, |v|) without a libm call. An infinite v wins and then fails the
/// domain check; v is never NaN (differences of finite doubles).
inline double max_abs(double m, double v) {
  const double a = std::fabs(v);  // andpd
  return m < a ? a : m;           // maxsd: branch-free
}

/// max_i |m[i][j]|: the largest entry of column j in magnitude.
template <int K>
[[gnu::always_inline]] inline double column_max(const Matrix<double, K>& m, int j) {
  double largest = 0;
  for (int i = 0; i < K; ++i) largest = max_abs(largest, m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]);
  return largest;
}

template <int D, int N>
using Point_refs = kernel::Point_refs<D, N>;

/// Whether every point has the same coordinate j (±0 alike), from the bits.
template <int D, int N>
bool same_coordinate(const Point_refs<D, N>& p, int j) {
  for (int i = 1; i < N; ++i)
    if (order_key((*p[static_cast<std::size_t>(i)])[j]) != order_key((*p[0])[j])) return false;
  return true;
}

/// Stage 1: the determinant in double, accepted when it exceeds the proven
/// bound ε·Π_j M̂_j (error_bounds.hpp). Returns nothing when undecided or when
/// the column maxima leave the filter's domain. Its answers hold in any
/// rounding mode and with FTZ/DAZ on (error_bounds.hpp, steps 1 and 4), so it
/// runs without a guard of the environment; the later stages hold one.
/// `computed` (optional) receives the double determinant when the filter got that far.
template <class Recipe, int D>
[[gnu::always_inline]] inline Maybe_sign filter(const Point_refs<D, Recipe::arity>& p,
                                                         double* computed = nullptr);

/// Stage 1's decision from the matrix m that the recipe makes of p and a
/// callable giving determinant<double>(m), asked for only once the column
/// maxima are inside the filter's domain. The static filter
/// (static_filter.hpp), which has computed both already, decides here what
/// its own bound leaves, without computing them again.
template <class Recipe, int D, class Determinant>
[[gnu::always_inline]] inline Maybe_sign filter_decision(const Point_refs<D, Recipe::arity>& p,
                                                                  const Matrix<double, Recipe::size>& m,
                                                                  Determinant&& determinant_of_m, double* computed) {
  constexpr int K = Recipe::size;
  double bound = Recipe::epsilon;
  for (int j = 0; j < K; ++j) {
    const double column_max = stages::column_max<K>(m, j);
    if (j < Recipe::spatial_columns) {
      // A zero column makes the exact determinant 0 when the points share that
      // coordinate. The computed column says so only under gradual underflow
      // (DAZ reads a subnormal as 0), so the bits decide.
      if (column_max == 0) return same_coordinate<D, Recipe::arity>(p, j) ? Maybe_sign(ZERO) : std::nullopt;
      if (!(column_max >= error_bounds::min_column_max && column_max <= error_bounds::max_column_max))
        return std::nullopt;
    }
    bound *= column_max;
  }
  const double det = determinant_of_m();
  if (computed) *computed = det;
  if (det > bound) return Recipe::sign_adjust;
  if (det < -bound) return -Recipe::sign_adjust;
  return std::nullopt;
}

template <class Recipe, int D>
[[gnu::always_inline]] inline Maybe_sign filter(const Point_refs<D, Recipe::arity>& p, double* computed) {
  const auto m = Recipe::template matrix<double>([&](int i, int j) { return (*p[static_cast<std::size_t>(i)])[j]; });
  return filter_decision<Recipe, D>(p, m, [&] { return determinant<double, Recipe::size>(m); }, computed);
}

/// Stage 1 again, on the points scaled by a power of two 2^s that brings the
/// largest coordinate difference near 1, for inputs whose differences leave
/// the filter's domain (coordinates like 2^600 or 2^-600, where the interval
/// stage overflows or underflows too). Scaling every coordinate by 2^s
/// multiplies each predicate's determinant by a positive power of two (2^sD,
/// or 2^s(D+2) with the lifted column), so the sign is the predicate's — when
/// the scaling is exact: every scaled coordinate zero or a normal double.
/// Otherwise (coordinates of very different magnitudes in one call), nothing.
// Cold (inputs far from 1): kept out of line so the common path stays small.
template <class Recipe, int D>
[[gnu::noinline]] Maybe_sign filter_scaled(const Point_refs<D, Recipe::arity>& p, double* computed) {
  constexpr int N = Recipe::arity;
  double largest_difference = 0, largest_coordinate = 0;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < D; ++j) {
      largest_coordinate = max_abs(largest_coordinate, (*p[static_cast<std::size_t>(i)])[j]);
      largest_difference = max_abs(largest_difference, (*p[static_cast<std::size_t>(i)])[j] - (*p[0])[j]);
    }
  if (largest_difference == 0) return std::nullopt;  // all points equal: the later stages say ZERO
  // An infinite difference (coordinates near ±2^1023): scale by the coordinates.
  const int s = std::isfinite(largest_difference) ? -std::ilogb(largest_difference)
                                                  : -std::ilogb(largest_coordinate) - 2;
  std::array<Point_d<D>, N> scaled;
  Point_refs<D, N> refs;
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < D; ++j) {
      const double x = (*p[static_cast<std::size_t>(i)])[j];
      if (x != 0) {
        const int e = std::ilogb(x) + s;
        if (e < std::numeric_limits<double>::min_exponent - 1 || e > std::numeric_limits<double>::max_exponent - 1)
          return std::nullopt;
      }
      scaled[static_cast<std::size_t>(i)][j] = std::ldexp(x, s);
    }
    refs[static_cast<std::size_t>(i)] = &scaled[static_cast<std::size_t>(i)];
  }
  return filter<Recipe, D>(refs, computed);
}

constexpr int factorial_int(int k) { return k <= 1 ? 1 : k * factorial_int(k - 1); }

/// Stage 2a: the filter's own double determinant `computed`, against a bound
/// from this call's entries instead of their column maxima. Where the
/// filter's bound is too coarse (points near one sphere: every monomial far
/// below K!·Π_j M_j), this decides what the interval stage would, at a tenth
/// of its cost (one more expansion in double, no interval products).
/// Derivation (error_bounds.hpp, steps 1, 2 and 4):
///  * Step 2 before its last inequality: |fl(det) − det| ≤ γ_N·perm(|X|), X
///    the exact entries, for the filter's computation in any rounding mode.
///  * P̂ = perm(|X̂|) computed from the entries in any rounding mode (u = 2^-52
///    bounds each operation's error in all of them): every entry and monomial
///    is a product of nonnegative terms, so P̂ ≥ perm(|X|)·(1 − γ_{c(K) + K(D+2)}) (each
///    computed |x̂| ≥ |x|·(1 − γ_{D+2}), each monomial and sum rounded at most
///    c(K) times), at least perm(|X|)·(1 − 2^-45) for K ≤ 7. The (1 + 2^-30)
///    margin of permanent_epsilon covers that and the two roundings of the
///    bound, so B = ε·P̂ ≥ γ_N·perm(|X|) in the rounding model.
///  * Underflow: the filter only computed `computed` when every spatial column
///    maximum lay in [2^-100, 2^100] (a NaN otherwise: nothing here). Then an
///    entry is at most D·2^200, and each of the at most K!·(c(K) + K(D+2)) <
///    2^19 operations (filter's or ours) that lands below 2^-1022 loses less
///    than 2^-1022 (FTZ, DAZ or gradual), later multiplied by at most the
///    K − 1 other entries of its monomial (≤ D·2^(100K)): in total less than
///    2^(19 − 1022 + 3 + 100K) < 2^(100K − 900), the floor added to B.
///  So |computed| > B proves sign(computed) = sign(det). Tested against GMP
///  on every family of test_predicates_vs_gmp.cpp and on points near spheres.
/// `m`: the entries, computed in any rounding mode (u = 2^-52 bounds every
/// mode's rounding, so the steps above hold for the filter's own entries
/// too, as computed by the caller, and for P̂ computed in the caller's mode;
/// the floor covers FTZ and DAZ): filtered_after_static asks it inline,
/// without a guard.
template <class Recipe, int D>
[[gnu::always_inline]] inline Maybe_sign permanent_decision(const Matrix<double, Recipe::size>& m, double computed) {
  constexpr int K = Recipe::size;
  Matrix<double, K> magnitudes;
  for (int i = 0; i < K; ++i)
    for (int j = 0; j < K; ++j)
      magnitudes[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] =
          std::fabs(m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]);
  constexpr int factors = Recipe::spatial_columns == K ? error_bounds::orientation_factors(D)
                                                       : error_bounds::side_of_sphere_factors(D);
  constexpr double epsilon = error_bounds::permanent_epsilon(factors);
  constexpr double floor = error_bounds::power_of_two(100 * K - 900);
  const double bound = epsilon * permanent<double, K>(magnitudes) + floor;
  if (computed > bound) return Recipe::sign_adjust;
  if (computed < -bound) return -Recipe::sign_adjust;
  return std::nullopt;
}
template <class Recipe, int D>
Maybe_sign permanent_filter(const Point_refs<D, Recipe::arity>& p, double computed) {
  if (std::isnan(computed)) return std::nullopt;
  const auto m = Recipe::template matrix<double>([&](int i, int j) { return (*p[static_cast<std::size_t>(i)])[j]; });
  return permanent_decision<Recipe, D>(m, computed);
}

/// Whether a second stage (running error, or intervals outside the filter's
/// domain) is worth trying on this thread for one recipe. After the permanent
/// stage it decides few of the calls that reach it on some inputs (points on
/// a sphere: most calls go on to the exact stage) and nearly all on others;
/// its cost, two to four times the permanent stage's, pays only when it
/// decides often: the intervals cost about 0.4 of the exact stage's
/// fixed-width path (3D, 58 against 140 ns a call). So it is tried in
/// windows of 64 calls; a window in which it decided fewer than one in three
/// makes the next 960 calls skip it (then it is tried again); one in eight
/// left the intervals open on points on a sphere, where they decided about one
/// call in eleven and took 17 % of the run (one in three: the run −10 %).
/// Skipping a stage never changes an answer, only its cost.
/// restart_interval_gates() (predicate_stats.hpp) sends every gate of the
/// thread back to its start.
class Stage_gate {
 public:
  bool open() {
    if (const std::uint32_t epoch = slow_path_counts().gate_epoch; epoch != epoch_) {
      tried_ = decided_ = skip_ = 0;
      epoch_ = epoch;
    }
    if (skip_ == 0) return true;
    --skip_;
    return false;
  }
  void record(bool decided) {
    decided_ += decided ? 1u : 0u;
    if (++tried_ < window) return;
    if (decided_ * 3 < window) skip_ = skipped;
    tried_ = decided_ = 0;
  }

 private:
  static constexpr std::uint32_t window = 64, skipped = 960;
  std::uint32_t tried_ = 0, decided_ = 0, skip_ = 0, epoch_ = 0;
};

struct Running_error_stage;
struct Interval_stage;

/// One gate per thread, recipe and stage.
template <class Recipe, class Stage>
Stage_gate& stage_gate() {
  thread_local Stage_gate gate;
  return gate;
}

/// Which of p's points lies nearest their centroid (L1; ties: the recipe's
/// origin). Translated to it the matrix's rows are shortest, and so are the
/// running error's bounds (degree K in the rows' lengths): on the calls the
/// permanent stage leaves, the query is often at one end of its near-tie
/// (points on a circle: a point inserted beside two or three neighbours),
/// and translating by the central point instead decided 61 % against 41 %
/// (3D, points on a sphere) and 71 % against 57 % (2D, on a circle) of the
/// calls the exact stage had decided before this stage existed. Computed
/// from the differences to the origin point, so that coordinates far larger
/// than the points' spread still choose well; rounding here only changes
/// the choice, never an answer. Not asked in 2D (running_error below).
template <class Recipe, int D>
int central_point(const Point_refs<D, Recipe::arity>& p) {
  constexpr int N = Recipe::arity;
  const auto& o = *p[static_cast<std::size_t>(Recipe::origin)];
  const auto difference = [&](int i, int j) { return (*p[static_cast<std::size_t>(i)])[j] - o[j]; };
  std::array<double, D> sum{};
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < D; ++j) sum[static_cast<std::size_t>(j)] += difference(i, j);
  const auto distance = [&](int i) {
    double d = 0;
    for (int j = 0; j < D; ++j) d += std::fabs(N * difference(i, j) - sum[static_cast<std::size_t>(j)]);
    return d;
  };
  int best = Recipe::origin;
  double best_distance = distance(best);
  for (int i = 0; i < N; ++i)
    if (const double d = distance(i); d < best_distance) {
      best = i;
      best_distance = d;
    }
  return best;
}

/// The determinant of a K×K matrix (K = 2 or 3) whose first two columns are
/// the plane's coordinate differences: the 2D predicates, orientation (K = 2)
/// and the in-circle test (K = 3, third column lifted), expanded along the
/// third column with each 2×2 spatial minor from exact products
/// (difference_of_products). Why: on neighbouring points of a circle the
/// rows are short and nearly parallel, so each minor is far smaller than its
/// products (spacing h: the products h², the minor about h³); rounded
/// products leave an error u·h² in every minor, about the size of the
/// near tie itself, and the in-circle tests the permanent stage leaves went
/// on to the exact stage one time in three (10^4 points on a circle: 3,188 of
/// 11,192). With exact products the error is u·h³ per minor. Nothing when a
/// nonzero spatial entry is below 2^-484 (difference_of_products' condition; the
/// entries are below 2^101 in the filter's domain, far inside its 2^500).
template <int K, bool Fused>
[[gnu::always_inline]] inline std::optional<Tracked_double> plane_determinant_in(const Matrix<Tracked_double, K>& m) {
  static_assert(K == 2 || K == 3);
  for (int i = 0; i < K; ++i)
    for (int j = 0; j < 2; ++j) {
      const double v = std::fabs(m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)].value());
      if (v != 0 && v < 0x1p-484) return std::nullopt;
    }
  const auto minor = [&](std::size_t a, std::size_t b) {
#ifndef DEWALL_TARGET_HAS_FMA
    if constexpr (!Fused) return difference_of_products_split(m[a][0], m[b][1], m[a][1], m[b][0]);
#endif
    return difference_of_products_fused(m[a][0], m[b][1], m[a][1], m[b][0]);
  };
  if constexpr (K == 2) {
    return minor(0, 1);
  } else {
    return m[0][2] * minor(1, 2) - m[1][2] * minor(0, 2) + m[2][2] * minor(0, 1);
  }
}
#if defined(__x86_64__) && !defined(DEWALL_TARGET_HAS_FMA)
/// Built for FMA (x86-64 before v3 has none: chosen at run time below).
template <int K>
[[gnu::target("fma"), gnu::noinline]] std::optional<Tracked_double> plane_determinant_fma(
    const Matrix<Tracked_double, K>& m) {
  return plane_determinant_in<K, true>(m);
}
#endif
/// The fused form where the processor has an FMA, else the split one.
template <int K>
std::optional<Tracked_double> plane_determinant(const Matrix<Tracked_double, K>& m) {
#ifdef DEWALL_TARGET_HAS_FMA
  return plane_determinant_in<K, true>(m);
#elif defined(__x86_64__)
  static const bool fma = __builtin_cpu_supports("fma");
  return fma ? plane_determinant_fma<K>(m) : plane_determinant_in<K, false>(m);
#else
  return plane_determinant_in<K, false>(m);
#endif
}

/// Stage 2b, in the filter's domain: the determinant in double with its
/// rounding error bounded as it is computed (running_error.hpp), the rows
/// translated by point `centre` (exchanging it with the origin negates the
/// determinant: the recipe's determinant is alternating in the points).
/// Derivation of the decision |det̂| > B:
///  * running_error.hpp: |det̂ − det| ≤ ê, ê the exact value of the bound's
///    expression over the computed values, when no operation underflows.
///  * The computed bound is at least ê·(1 − u)^m, m the rounded operations
///    of the whole bound computation (a term e_x·e_y joins the roundings of
///    both operands, so not those of one path alone): about 11 per product of
///    the expansion and its sum, K·2^(K−1) ≤ 448 products, and the entries,
///    fewer than 2^13 for K ≤ 7 (in 2D, plane_determinant: fewer, its
///    products' parts exact by its own check); so ê ≤ computed·(1 + 2^-39), and the margin
///    (1 + 2^-30) covers that and the two roundings of B.
///  * Underflow: only called when the filter computed its determinant, so
///    every spatial column maximum of the given translation lay in
///    [2^-100, 2^100]; translated by another of the points, the spatial
///    entries are below 2^101 and the lifted ones below D·2^202. Each of the
///    fewer than 2^13 operations (values and bounds) that lands below
///    2^-1022 loses less than 2^-1022; a loss inside a minor of size r
///    reaches the determinant multiplied by its cofactor, at most (K − r)!
///    monomials of the other rows' entries (each monomial ≤ D·2^(101K)):
///    less than 2^13 · 7! · D · 2^-1022 · 2^(101K) < 2^(101K − 994) in all,
///    below the floor 2^(100K − 900) added to B.
/// So |det̂| > B proves sign(det̂) = sign(det). Tested against GMP on points
/// near circles and spheres with every point as the centre, and on every
/// family of test_predicates_vs_gmp.cpp with the chosen one.
template <class Recipe, int D>
Maybe_sign running_error(const Point_refs<D, Recipe::arity>& p, int centre) {
  constexpr int K = Recipe::size;
  static_assert(K <= 7, "the derivation above counts the operations of K ≤ 7");
  Point_refs<D, Recipe::arity> q = p;
  std::swap(q[static_cast<std::size_t>(centre)], q[static_cast<std::size_t>(Recipe::origin)]);
  const auto m = Recipe::template matrix<Tracked_double>(
      [&](int i, int j) { return Exact_coordinate{(*q[static_cast<std::size_t>(i)])[j]}; });
  const Tracked_double det = [&] {
    if constexpr (Recipe::spatial_columns == 2)
      if (const auto plane = plane_determinant<K>(m)) return *plane;
    return determinant<Tracked_double, K>(m);
  }();
  constexpr double margin = 1 + 0x1p-30;
  constexpr double floor = error_bounds::power_of_two(100 * K - 900);
  const double bound = det.error() * margin + floor;
  const Sign sign = centre == Recipe::origin ? Recipe::sign_adjust : -Recipe::sign_adjust;
  if (det.value() > bound) return sign;
  if (det.value() < -bound) return -sign;
  return std::nullopt;
}
/// In 2D the query stays the origin: with the minors from exact products
/// (plane_determinant) the central point decides few more calls (points on a
/// circle, 10^4: 201 of 10,933 go on to the exact stage with the query, 1,090
/// against 1,291) than the choice costs (the construction −6 % without it).
template <class Recipe, int D>
Maybe_sign running_error(const Point_refs<D, Recipe::arity>& p) {
  if constexpr (Recipe::spatial_columns == 2) return running_error<Recipe, D>(p, Recipe::origin);
  else return running_error<Recipe, D>(p, central_point<Recipe, D>(p));
}

/// The running-error stage on its own, where the cascade runs it: nothing
/// outside the filter's domain (the filter computed no determinant). Under the
/// caller's guard of the environment.
template <class Recipe, int D>
Maybe_sign running_error_in_domain(const Point_refs<D, Recipe::arity>& p) {
  double computed = std::numeric_limits<double>::quiet_NaN();
  (void)filter<Recipe, D>(p, &computed);
  if (std::isnan(computed)) return std::nullopt;
  return running_error<Recipe, D>(p);
}

/// Stage 2b outside the filter's domain: the same determinant in interval
/// arithmetic (no domain limits).
template <class Recipe, int D>
Maybe_sign interval(const Point_refs<D, Recipe::arity>& p) {
  const auto m = Recipe::template matrix<Interval>(
      [&](int i, int j) { return Interval((*p[static_cast<std::size_t>(i)])[j]); });
  if (auto s = determinant<Interval, Recipe::size>(m).sign()) return Recipe::sign_adjust * *s;
  return std::nullopt;
}

/// Bits needed for |v| (v ≠ INT128_MIN).
inline int bit_width_128(Int128 v) {
  const Uint128 a = v < 0 ? -static_cast<Uint128>(v) : static_cast<Uint128>(v);
  const auto high = static_cast<std::uint64_t>(a >> 64);
  return static_cast<int>(high ? 64 + std::bit_width(high) : std::bit_width(static_cast<std::uint64_t>(a)));
}

/// The points' coordinates as integers on one binary scale (exact_integer.hpp).
template <class Recipe, int D>
Common_scale<Recipe::arity * D> common_scale_of(const Point_refs<D, Recipe::arity>& p) {
  double coordinates[Recipe::arity * D];
  for (int i = 0; i < Recipe::arity; ++i)
    for (int j = 0; j < D; ++j) coordinates[i * D + j] = (*p[static_cast<std::size_t>(i)])[j];
  return Common_scale<Recipe::arity * D>(coordinates);
}

/// The exact stage's fixed-width path (wide_integer.hpp): coordinates of at
/// most 125 bits on the common scale, whose differences (< 2^126: exact modulo
/// 2^128) all fit 62 bits; the lifted column (sums of squares, computed modulo
/// 2^128) is then exact too (< 8·2^124). Nothing otherwise.
/// Out of line: inlined into exact(), GCC copied the 128-bit entries through
/// the stack in halves and reloaded them whole (store-forwarding stalls: points
/// on a sphere, 3 % of the run).
template <class Recipe, int D, int N>
[[gnu::noinline]] Maybe_sign exact_small_entries(const Common_scale<N>& scale, int coordinate_bits) {
  if (coordinate_bits > 125) return std::nullopt;
  Uint128 integers[N];
  for (int k = 0; k < N; ++k) integers[k] = static_cast<Uint128>(scale.small_integer(k));
  const auto m = Recipe::template matrix<Uint128>([&](int i, int j) { return integers[i * D + j]; });
  if (const auto s = small_entry_determinant_sign<Recipe::size, Recipe::spatial_columns>(m))
    return Recipe::sign_adjust * static_cast<Sign>(*s);
  return std::nullopt;
}

/// Whether x is a normal double with a set bit among the lowest 32 of its
/// significand, 2^52 + fraction (true also for a NaN with such payload
/// bits, which both callers reject anyway). Then x has fewer than 32 trailing zero bits
/// (exact_in_double's test) and is no integer of magnitude at most 2^20
/// (whose significand, times 2^(e − 52) with e ≤ 20, must be a multiple of
/// 2^32): both questions answered from the bits, without the frexp and
/// nearbyint calls they cost otherwise (points on a circle: 6 % of the run,
/// every near-tie asking both of a coordinate of full precision).
inline bool low_bits_set(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  return (bits & 0x7ff0000000000000) != 0 && (bits & 0xffffffff) != 0;
}

/// Whether every coordinate is an integer of magnitude at most 2^20.
template <class Recipe, int D>
bool small_integer_coordinates(const Point_refs<D, Recipe::arity>& p) {
  for (int i = 0; i < Recipe::arity; ++i)
    for (int j = 0; j < D; ++j) {
      const double x = (*p[static_cast<std::size_t>(i)])[j];
      if (low_bits_set(x) || !(std::fabs(x) <= 0x1p20) || x != std::nearbyint(x)) return false;
    }
  return true;
}

/// Whether 128-bit integers hold every value the expansion forms for any
/// input of integers of magnitude at most 2^20: spatial entries below 2^21,
/// lifted ones below D·2^42, so (as in exact's bound) K!·Π_j M_j < 2^125.
template <class Recipe, int D>
constexpr bool small_integers_fit_128() {
  constexpr int K = Recipe::size;
  constexpr int lifted_bits = 42 + static_cast<int>(std::bit_width(static_cast<unsigned>(D)));
  return static_cast<int>(std::bit_width(static_cast<unsigned>(factorial_int(K)))) + 21 * Recipe::spatial_columns +
             lifted_bits * (K - Recipe::spatial_columns) <=
         125;
}

/// Stage 3: the same determinant over exact integers: 128-bit integers when a
/// bound proves they cannot overflow (exactly degenerate inputs are mostly small
/// integers: lattices, cospherical integer points), then integers as wide as
/// each minor needs when the differences fit 62 bits (doubles on one scale:
/// points on spheres and surfaces, near ties the filters cannot decide), GMP
/// otherwise. Exact for every finite input.
/// 128-bit overflow bound: every value the expansion forms (entries, partial sums,
/// minors) is at most K!·Π_j M_j in magnitude, M_j the largest entry of column j
/// (a minor of size r is a sum of r! products of entries from distinct columns).
/// Inputs of at most 40 bits keep the entries themselves (differences, sums of
/// D squares) below 2^90; the determinant path is taken when
/// log2(K!) + Σ_j bits(M_j) ≤ 125.
/// `integers`: small_integer_coordinates(p), when the caller knows it.
template <class Recipe, int D>
Sign exact(const Point_refs<D, Recipe::arity>& p, bool integers) {
  constexpr int N = Recipe::arity * D;
  constexpr int K = Recipe::size;
  // Integer inputs (lattices, cospherical integer points: every sphere test
  // an exact zero) skip the common scale and the bit count: the bound holds
  // for all of them. (Converted through 64 bits: a double to __int128 is a
  // library call.)
  if constexpr (small_integers_fit_128<Recipe, D>()) {
    if (integers) {
      const auto m = Recipe::template matrix<Int128>([&](int i, int j) {
        return static_cast<Int128>(static_cast<std::int64_t>((*p[static_cast<std::size_t>(i)])[j]));
      });
      return Recipe::sign_adjust * sign_of(determinant<Int128, K>(m));
    }
  }
  const auto scale = common_scale_of<Recipe, D>(p);
  const int coordinate_bits = scale.max_bits();
  if (coordinate_bits <= 40) {
    Int128 small[N];
    for (int k = 0; k < N; ++k) small[k] = scale.small_integer(k);
    const auto m = Recipe::template matrix<Int128>([&](int i, int j) { return small[i * D + j]; });
    int bits = static_cast<int>(std::bit_width(static_cast<unsigned>(factorial_int(K))));
    for (int j = 0; j < K; ++j) {
      int column = 0;
      for (int i = 0; i < K; ++i) column = std::max(column, bit_width_128(m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]));
      bits += column;
    }
    if (bits <= 125) {
      const Int128 det = determinant<Int128, K>(m);
      return Recipe::sign_adjust * sign_of(det);
    }
  }
  if (const auto s = exact_small_entries<Recipe, D>(scale, coordinate_bits)) return *s;
  // One workspace per thread and recipe: its integers keep their limbs from
  // call to call, so the exact stage allocates only while they grow.
  struct Workspace {
    Exact_integer integers[N];
    Matrix<Exact_integer, K> m;
    std::array<Exact_integer, (1 << K)> minor;
  };
  thread_local Workspace w;
  for (int k = 0; k < N; ++k) scale.assign_integer(k, w.integers[k]);
  Recipe::fill(w.m, [&](int i, int j) -> const Exact_integer& { return w.integers[i * D + j]; });
  return Recipe::sign_adjust * static_cast<Sign>(determinant_sign_in_place<K>(w.m, w.minor));
}
template <class Recipe, int D>
Sign exact(const Point_refs<D, Recipe::arity>& p) {
  return exact<Recipe, D>(p, small_integer_coordinates<Recipe, D>(p));
}

/// Stage 1b, for small integer inputs (lattices, grids: every tie exact),
/// also after a common power-of-two scale (a lattice of spacing 2^-6 is one
/// of spacing 1 scaled: the walls' point set scales every input to the unit
/// box, and both signs are of homogeneous polynomials, unchanged by a
/// positive factor). The points are first multiplied by 2^-q, q the lowest
/// set bit of any of their coordinates, which is exact (the products are
/// integers, checked below 2^20, so neither rounding nor underflow). Then,
/// when every coordinate is an integer of magnitude at most 2^20, the entries
/// (differences, and sums of squared differences below 2^53) are computed
/// exactly; if then K!·Π_j M_j < 2^52 (M_j the largest |entry| of column j),
/// every value the expansion forms — a minor of size r is a sum of r!
/// products of entries from distinct columns — is an integer below 2^52, so
/// the double determinant is exact, zero included. (A column of zeros makes
/// the bound 0 and lets through minors of the other columns that may round,
/// but every term of the expansion then holds a zero factor from that column,
/// so the result is exactly ±0, the right answer.) The product is formed in
/// double: each rounding is relative 2^-52 at most, far inside the margin
/// (the test asks 2^52 where 2^53 would do).
/// `integers`: small_integer_coordinates(p) (integers already, a lattice as
/// given: no scale to take out; tested first, because frexp and ldexp on
/// every coordinate cost more than the rest of the stage: grid 10^5, a
/// fifth of the run).
template <class Recipe, int D>
Maybe_sign exact_in_double(const Point_refs<D, Recipe::arity>& p, bool integers) {
  constexpr int K = Recipe::size;
  // q: the exponent of the lowest set bit over all coordinates (x = odd · 2^e).
  int q = integers ? 0 : std::numeric_limits<int>::max();
  for (int i = 0; i < Recipe::arity && !integers; ++i)
    for (int j = 0; j < D; ++j) {
      const double x = (*p[static_cast<std::size_t>(i)])[j];
      if (!std::isfinite(x) || low_bits_set(x)) return std::nullopt;
      if (x == 0) continue;
      int e = 0;
      const double mantissa = std::frexp(x, &e);  // x = mantissa · 2^e, 2^52 · mantissa an integer
      const auto bits = static_cast<std::uint64_t>(std::fabs(std::ldexp(mantissa, 53)));
      const int zeros = std::countr_zero(bits);
      // x's odd part, bits >> zeros, is at least 2^(52 − zeros): above 2^20
      // unless zeros ≥ 32 (returns at once on coordinates of full precision).
      if (zeros < 32) return std::nullopt;
      q = std::min(q, e - 53 + zeros);
    }
  if (q == std::numeric_limits<int>::max()) q = 0;  // all zero
  std::array<std::array<double, D>, Recipe::arity> scaled;
  for (int i = 0; i < Recipe::arity; ++i)
    for (int j = 0; j < D; ++j) {
      const double given = (*p[static_cast<std::size_t>(i)])[j];
      const double x = q == 0 ? given : std::ldexp(given, -q);
      if (!(std::fabs(x) <= 0x1p20)) return std::nullopt;
      scaled[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = x;
    }
  const auto m = Recipe::template matrix<double>(
      [&](int i, int j) { return scaled[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]; });
  double bound = factorial_int(K);
  for (int j = 0; j < K; ++j) bound *= stages::column_max<K>(m, j);
  if (!(bound < 0x1p52)) return std::nullopt;
  const double det = determinant<double, K>(m);
  return Recipe::sign_adjust * sign_of(det);
}
template <class Recipe, int D>
Maybe_sign exact_in_double(const Point_refs<D, Recipe::arity>& p) {
  return exact_in_double<Recipe, D>(p, small_integer_coordinates<Recipe, D>(p));
}

/// A second stage behind its gate: its answer, counted, or nothing when the
/// gate is closed or the stage cannot tell.
template <class Recipe, class Stage, class Evaluate>
Maybe_sign gated_second_stage(Evaluate&& evaluate, std::atomic<std::uint64_t>& counter,
                                       Slow_path_counts& slow) {
  Stage_gate& gate = stage_gate<Recipe, Stage>();
  if (!gate.open()) return std::nullopt;
  const Maybe_sign s = evaluate();
  gate.record(s.has_value());
  if (s) {
    count(counter);
    ++slow.second_stage;
  }
  return s;
}

/// The stages after an undecided filter, under a guard of the floating-point
/// environment (they assume round-to-nearest and gradual underflow). Out of
/// line: the filter decides nearly every call.
/// `permanent_tried`: the caller ran stage 2a already (permanent_decision on
/// the filter's matrix), undecided.
template <class Recipe, int D>
[[gnu::noinline]] Sign after_filter(const Point_refs<D, Recipe::arity>& p, double computed,
                                    bool permanent_tried = false) {
  const Fp_environment_guard guard;
  auto& stats = Recipe::stats();
  const double unscaled = computed;  // the permanent stage's, on the points as given
  if (std::isnan(computed)) {
    if (auto s = filter_scaled<Recipe, D>(p, &computed)) {
      count(stats.filter);
      return *s;
    }
  }
  // A double determinant of exactly 0 almost always means an exactly degenerate
  // input (lattices: small integers compute without rounding), which intervals
  // cannot decide: go straight to the exact stage. Skipping a stage never
  // changes an answer, only its cost.
  Slow_path_counts& slow = slow_path_counts();
  const bool integers = small_integer_coordinates<Recipe, D>(p);
  if (auto s = exact_in_double<Recipe, D>(p, integers)) {
    count(stats.exact);  // an exact answer, if a cheap one
    ++slow.exact;
    return *s;
  }
  if (computed != 0) {
    if (!std::isnan(unscaled)) {
      if (auto s = permanent_tried ? std::nullopt : permanent_filter<Recipe, D>(p, unscaled)) {
        count(stats.permanent);
        return *s;
      }
      if (auto s = gated_second_stage<Recipe, Running_error_stage>([&] { return running_error<Recipe, D>(p); },
                                                                   stats.running_error, slow))
        return *s;
    } else if (auto s = gated_second_stage<Recipe, Interval_stage>([&] { return interval<Recipe, D>(p); },
                                                                   stats.interval, slow)) {
      return *s;
    }
  }
  count(stats.exact);
  ++slow.exact;
  return exact<Recipe, D>(p, integers);
}

/// The cascade from stage 1's decision on, for a caller that has computed
/// the matrix m the recipe makes of p and det = determinant<double>(m) (the
/// same operations as stage 1's, so stage 1's error bound holds for det):
/// what filtered(p)
/// answers, without computing them again. Stage 1 inline, the rest
/// (after_filter) out of line: on surface samples the static filter leaves
/// about half of the sphere tests to stage 1, which decides them, and a call
/// out of line cost measurably there (docs/engines.md). In 3D the static
/// filter's own semi-static bound now decides those before (static_filter.hpp):
/// here stage 1 adds only a zero column's ZERO, and `computed` for the rest.
template <class Recipe, int D>
[[gnu::always_inline]] inline Sign filtered_after_static(const Point_refs<D, Recipe::arity>& p,
                                                         const Matrix<double, Recipe::size>& m, double det) {
  double computed = std::numeric_limits<double>::quiet_NaN();  // NaN: the filter left its domain
  if (auto s = filter_decision<Recipe, D>(p, m, [det] { return det; }, &computed)) {
    count(Recipe::stats().filter);
    return *s;
  }
  // Stage 2a inline too, for 3×3 matrices (the 2D sphere test: only the
  // sphere test's static filter calls this function): on points
  // on a circle every sphere test of a finite cell is a near tie that it
  // decides more often than not (10^4 points: 15,169 of 26,361), and asked
  // here, on the matrix in registers, it costs no call, no guard and no
  // second matrix (that construction −6 %; uniform 2D unchanged). Larger
  // matrices keep it out of line: the 3D cavity search grew and got slower
  // (a torus with noise, 10^6 points, where it never runs: +1.7 %).
  if constexpr (Recipe::size <= 3) {
    if (!std::isnan(computed)) {
      if (auto s = permanent_decision<Recipe, D>(m, computed)) {
        count(Recipe::stats().permanent);
        return *s;
      }
      return after_filter<Recipe, D>(p, computed, true);
    }
  }
  return after_filter<Recipe, D>(p, computed);
}

/// The cascade, counting which stage decided. Exact in any floating-point
/// environment of the caller.
template <class Recipe, int D>
Sign filtered(const Point_refs<D, Recipe::arity>& p) {
  double computed = std::numeric_limits<double>::quiet_NaN();  // NaN: the filter left its domain
  if (auto s = filter<Recipe, D>(p, &computed)) {
    count(Recipe::stats().filter);
    return *s;
  }
  return after_filter<Recipe, D>(p, computed);
}

}  // namespace dewall::kernel::stages
DEWALL_FLOATING_POINT_CODE_END
