// Error bounds of the static filter, derived here rather than tabulated.
//
// Setting. Both predicates are the sign of det(X) for a K×K matrix X whose
// entries are computed from the input doubles:
//   orientation_d:            K = D,   X[i][j] = p_{i+1}[j] − p_0[j]
//   side_of_oriented_sphere_d: K = D+1, X[i][j] = p_i[j] − q[j] (j < D),
//                                        X[i][D] = Σ_j (p_i[j] − q[j])²
// and det is evaluated by `determinant` (determinant.hpp).
//
// Model. Without underflow or overflow, fl(a ∘ b) = (a ∘ b)(1 + δ) with |δ| ≤ u.
// We take u = 2^-52, which bounds the error of one operation in every rounding
// mode (round-to-nearest alone would allow 2^-53): the static filters then
// hold whatever rounding mode the caller runs in, and need no guard of the
// floating-point environment on their fast path (floating_point.hpp). The cost
// is a bound twice as large, which the filter almost never meets.
// Write θ_n for a product of n factors (1 + δ_i); |θ_n − 1| ≤ γ_n = n·u / (1 − n·u)
// (Higham, "Accuracy and Stability of Numerical Algorithms", Lemma 3.1).
//
// Step 1, the expansion. A computed r×r minor equals Σ_σ sgn(σ) Π_i x_{iσ(i)} · θ_{c(r)}
// with its own θ per monomial, where c(1) = 0 and c(r) = c(r−1) + 1 + (r − 1):
// one rounding for the product a·minor and at most r − 1 for the left-to-right
// sum of r terms. So c(r) = r(r+1)/2 − 1.
//
// Step 2, the entries. A difference p − q carries one factor; a lifted entry
// Σ_j x_j² carries 2 (x_j rounded, squared) + 1 (the product) + (D − 1) (the sum)
// = D + 2 factors. A monomial takes one entry from each column, so
//   orientation_d:             N = c(D)   + D
//   side_of_oriented_sphere_d: N = c(D+1) + D + (D + 2)
// and |fl(det) − det| ≤ γ_N · perm(|X|) ≤ γ_N · K! · Π_j M_j, where M_j is the
// largest |entry| of column j (K! monomials, each at most Π_j M_j).
//
// Step 3, computable bound. We only know the computed maxima M̂_j; they exceed
// the exact ones by at most the factors above (|x| ≤ |x̂|/(1−u), lifted entries
// by 1/(1−γ_{D+2})), and B = ε·Π M̂_j is itself rounded K times. All of these together
// stay below (1 + 64u) = (1 + 2^-46) for K ≤ 8, well inside the (1 + 2^-30)
// margin that `filter_epsilon` multiplies in.
// Hence: if |fl(det)| > ε_K · Π_j M̂_j then sign(fl(det)) = sign(det).
//
// Step 4, the domain. The model ignores underflow and overflow. A product
// below 2^-1022 loses less than 2^-1022 absolutely — 2^-1075 with gradual
// underflow, 2^-1022 when the caller's environment flushes results to zero
// (FTZ) — and a subnormal input read as zero (DAZ) changes an entry by less
// than 2^-1022 too. The filter therefore runs only when every spatial column
// maximum lies in [2^-100, 2^100] (a zero column is handled before, see
// filtered_predicate.hpp). Then: no value exceeds K!·D·2^(100(K+1)) < 2^900
// (no overflow), and the total absolute error from underflows, at most K!·K
// products or entries each losing 2^-1022 and later multiplied by the maxima of
// the remaining columns (≤ Π_j M_j · 2^(100(K+1))), is below
// 2^(16 − 1022 + 800) Π_j M_j = 2^-206 Π_j M_j, far below the margin's share
// 2^-30·ε·Π_j M_j ≥ 2^-79 Π_j M_j (every ε here is at least 2^-49). So the
// filter's answers hold in any rounding mode and with FTZ/DAZ on.
// Inputs outside the domain go to the interval stage, which has no such limit.
#pragma once

namespace dewall::kernel::error_bounds {

/// The relative error of one operation in any rounding mode (model above).
inline constexpr double unit_roundoff = 0x1p-52;

/// c(r): rounding factors accumulated by an r×r minor of `determinant`.
constexpr int expansion_factors(int r) { return r * (r + 1) / 2 - 1; }

constexpr int orientation_factors(int d) { return expansion_factors(d) + d; }
constexpr int side_of_sphere_factors(int d) { return expansion_factors(d + 1) + d + (d + 2); }

constexpr double factorial(int k) { return k <= 1 ? 1.0 : k * factorial(k - 1); }

constexpr double gamma(int n) { return n * unit_roundoff / (1 - n * unit_roundoff); }

/// ε such that |fl(det)| > ε·Π_j M̂_j proves the sign, for a K×K determinant
/// whose monomials carry `factors` rounding factors (steps 1–3 above).
/// Computed in double at compile time; the (1 + 2^-30) margin is far larger than
/// the few ulps of this computation and than the step-3 factors.
constexpr double filter_epsilon(int factors, int k) {
  return gamma(factors) * factorial(k) * (1 + 0x1p-30);
}

constexpr double orientation_epsilon(int d) { return filter_epsilon(orientation_factors(d), d); }
constexpr double side_of_sphere_epsilon(int d) {
  return filter_epsilon(side_of_sphere_factors(d), d + 1);
}

/// The permanent stage (filtered_predicate.hpp): step 2 before its last
/// inequality, |fl(det) − det| ≤ γ_N·perm(|X|), with the same margin as
/// filter_epsilon for the computed permanent (the derivation is there).
constexpr double permanent_epsilon(int factors) { return gamma(factors) * (1 + 0x1p-30); }

/// 2^e, at compile time.
constexpr double power_of_two(int e) {
  double v = 1;
  for (; e > 0; --e) v *= 2;
  for (; e < 0; ++e) v /= 2;
  return v;
}

/// Step 4: the range of spatial column maxima inside which the filter is valid.
inline constexpr double min_column_max = 0x1p-100;
inline constexpr double max_column_max = 0x1p+100;

static_assert(orientation_factors(2) == 4 && orientation_factors(3) == 8);
static_assert(side_of_sphere_factors(2) == 11 && side_of_sphere_factors(3) == 17);

}  // namespace dewall::kernel::error_bounds
