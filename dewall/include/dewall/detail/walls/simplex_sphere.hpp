// Simplex_sphere: the circumsphere of one simplex, for the many queries of a
// search: a proven in-sphere filter at the cost of a dot product per query,
// and a box proven to contain the closed ball, for pruning the search.
//
// Derivation. With y_i = s_i − s_0 (i = 1..D) and x = q − s_0, the lifted
// determinant translated by s_0 and expanded along its row of s_0 is
// (−1)^(D+1)·M', with M' = det[(y_1, |y_1|²); …; (y_D, |y_D|²); (x, |x|²)]. The
// kernel's M (translated by q, side_of_sphere.hpp) is the same (D+2)×(D+2)
// determinant expanded along q's row, and the predicate is (−1)^D·sign(M), so
//   q inside the sphere  ⇔  M' < 0.
// Expanding M' along its last row: M'(x) = Σ_j x_j·A_j + |x|²·A_L, where the
// cofactors A are D×D determinants of the y rows, computed once per simplex by
// the kernel's `determinant` with the bounds of error_bounds.hpp: A_L has the
// orientation's rounding factors, each A_j one lifted column (D + 2 factors
// instead of 1). A_L ≠ 0 for a non-degenerate simplex, and
//   M'(x) = A_L·(|x − c|² − r²) with c = −A/(2·A_L), r = |c|,
// so the same cofactors give the centre c (relative to s_0) and radius.
//
// In-sphere filter. Per query, S = fl(Σ_j x̂_j Â_j + l̂·Â_L) with l̂ = fl(Σ x̂_j²):
// every term carries at most N = (D + 2) + 1 + D rounding factors, so
//   |S − M'| ≤ γ_N·Σ_t |x̂_t|(|Â_t| + e_t) + (1 + γ_N)·Σ_t |x̂_t|·e_t
// (t over the coordinates and the lifted term), covered together with the
// rounding of the bound itself by the (1 + 2^-30) margin, plus 2^-1000 for
// underflow in the products. Undecided cases go to the kernel's predicate.
//
// Box. c_j ∈ −[Â_j ± e_j] / (2·[Â_L ± e_L]) in interval arithmetic; then the ball
// lies in s_0 + c ± max|c|.
//
// Scale. Simplices far outside [2^-50, 2^50] are first scaled by a power of two
// (exact up to underflow of entries that are negligible, whose absolute error
// ≤ 2^-1075 the allowances above cover); queries are scaled alike and the box
// scaled back.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "dewall/detail/common/coords.hpp"
#include "dewall/detail/walls/face_side_filter.hpp"
#include "dewall/kernel/determinant.hpp"
#include "dewall/kernel/error_bounds.hpp"
#include "dewall/kernel/interval.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <int D>
struct Ball_box {
  Coords<D> lo, hi;
  bool bounded = false;  // false: no proven box (degenerate or extreme simplex); search everywhere
  // The centre lies in [centre_lo, centre_hi] and the radius r satisfies
  // r² · (1 + 2^-40) + 2^-1000 ≤ radius2_limit.
  Coords<D> centre_lo, centre_hi;
  double radius2_limit = 0;

  /// False only when the box [lo, hi] and the closed ball are proven disjoint.
  /// Proof: with G_j ≥ 0 the exact gap between [lo_j, hi_j] and [centre_lo_j,
  /// centre_hi_j], every point of the box is at distance ≥ (Σ G_j²)^½ from the
  /// centre. Each g_j below is one subtraction (≤ G_j(1 + 2^-52) in any rounding
  /// mode; exact when subnormal), and the sum of squares adds at most D + 1
  /// more such factors and D·2^-1022 lost to underflow or flushing, which the
  /// margins of radius2_limit exceed for D ≤ 6: gap2 > radius2_limit proves
  /// Σ G_j² > r².
  bool may_meet(const Coords<D>& box_lo, const Coords<D>& box_hi) const {
    if (!bounded) return true;
    double gap2 = 0;
    for (int j = 0; j < D; ++j) {
      // At most one difference is positive (lo ≤ hi on both sides); branch-free.
      const double g = std::max(std::max(box_lo[j] - centre_hi[j], centre_lo[j] - box_hi[j]), 0.0);
      gap2 += g * g;
    }
    return !(gap2 > radius2_limit);
  }
};

template <int D>
class Simplex_sphere {
 public:
  explicit Simplex_sphere(const std::array<const Coords<D>*, D + 1>& s) : origin_(*s[0]) {
    namespace eb = kernel::error_bounds;
    kernel::Matrix<double, D> y;  // rows y_1..y_D
    double largest = 0;
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) {
        y[i][j] = (*s[i + 1])[j] - origin_[j];
        // std::max, not std::fmax (a library call under -fno-fast-math): a
        // difference of finite coordinates is never NaN, nor are the sums below.
        largest = std::max(largest, std::fabs(y[i][j]));
      }
    if (!(largest >= 0x1p-50 && largest <= 0x1p50) && std::isfinite(largest) && largest > 0) {
      exponent_ = std::ilogb(largest);
      for (auto& row : y)
        for (double& v : row) v = std::ldexp(v, -exponent_);
    }
    std::array<double, D> lift;
    std::array<double, D + 1> col_max{};
    for (int i = 0; i < D; ++i) {
      double l = 0;
      for (int j = 0; j < D; ++j) {
        l += y[i][j] * y[i][j];
        col_max[j] = std::max(col_max[j], std::fabs(y[i][j]));
      }
      lift[i] = l;
      col_max[D] = std::max(col_max[D], l);
    }
    for (int j = 0; j < D; ++j)
      if (!(col_max[j] >= eb::min_column_max && col_max[j] <= eb::max_column_max)) return;
    // Cofactors of the last row of [y | lift; x | |x|²]: A_c = (−1)^(D+c)·det(top block without column c).
    constexpr int lifted_factors = eb::expansion_factors(D) + (D - 1) + (D + 2);
    for (int c = 0; c <= D; ++c) {
      kernel::Matrix<double, D> minor;
      double product = 1;
      for (int i = 0; i < D; ++i)
        for (int k = 0, m = 0; k <= D; ++k)
          if (k != c) minor[i][m++] = k < D ? y[i][k] : lift[i];
      for (int k = 0; k <= D; ++k)
        if (k != c) product *= col_max[k];
      const double value = kernel::determinant<double, D>(minor);
      cofactor_[c] = (D + c) % 2 == 0 ? value : -value;
      error_[c] = (c == D ? eb::orientation_epsilon(D) : eb::filter_epsilon(lifted_factors, D)) * product;
    }
    valid_ = true;
    box_ = compute_box();
    if (box_.bounded) {  // the per-query bound below, for the worst query in the box
      double magnitude = 0, carried = 0, lifted = 0;
      for (int j = 0; j < D; ++j) {
        double reach = std::max(std::fabs(box_.lo[j] - origin_[j]), std::fabs(box_.hi[j] - origin_[j]));
        if (exponent_ != 0) reach = std::ldexp(reach, -exponent_);
        lifted += reach * reach;
        magnitude += reach * (std::fabs(cofactor_[j]) + error_[j]);
        carried += reach * error_[j];
      }
      magnitude += lifted * (std::fabs(cofactor_[D]) + error_[D]);
      carried += lifted * error_[D];
      box_bound_ = bound(magnitude, carried);
    }
  }

  /// For approximations within `coordinate_error` (δ) of the points (kernel/
  /// concepts.hpp): only the box, for pruning; no in-sphere filter (inside()
  /// answers nothing). The cofactors' errors cover the exact simplex's by
  /// interval arithmetic on its rows widened by 2δ (and the lifted column
  /// computed from them); the centre interval is widened by δ for the exact
  /// s_0 and by δ more, as is the box, so that the approximation of a point in
  /// the closed ball lies in the box, and Ball_box::may_meet holds for boxes of
  /// approximations (a gap to the centre interval widened by δ is at most the
  /// exact point's gap to the exact centre).
  Simplex_sphere(const std::array<const Coords<D>*, D + 1>& s, double coordinate_error) : Simplex_sphere(s) {
    using kernel::Interval;
    const bool had_filter = valid_;
    valid_ = false;
    box_ = Ball_box<D>();
    box_bound_ = std::numeric_limits<double>::infinity();
    if (!had_filter || !std::isfinite(coordinate_error)) return;
    const Interval spread(-2 * coordinate_error, 2 * coordinate_error), scale(std::ldexp(1.0, -exponent_));
    std::array<std::array<Interval, D + 1>, D> rows;  // [y | |y|²], scaled like the cofactors
    for (int i = 0; i < D; ++i) {
      rows[i][D] = Interval(0.0);
      for (int j = 0; j < D; ++j) {
        rows[i][j] = (Interval((*s[i + 1])[j]) - Interval(origin_[j]) + spread) * scale;
        rows[i][D] += rows[i][j] * rows[i][j];
      }
    }
    for (int c = 0; c <= D; ++c) {
      kernel::Matrix<Interval, D> minor;
      for (int i = 0; i < D; ++i)
        for (int k = 0, m = 0; k <= D; ++k)
          if (k != c) minor[i][m++] = rows[i][k];
      const Interval value = kernel::determinant<Interval, D>(minor);
      const Interval exact = (D + c) % 2 == 0 ? value : -value;
      error_[c] = Face_side_filter<D>::error_from(exact, cofactor_[c]);
      if (!std::isfinite(error_[c])) return;
    }
    valid_ = true;
    box_ = compute_box(coordinate_error * 2);
    valid_ = false;
  }

  /// As `inside`, faster. \pre q lies in enclosing_box() (which is bounded).
  std::optional<bool> inside_box(const Coords<D>& q) const {
    double s = 0, lifted = 0;
    for (int j = 0; j < D; ++j) {
      double x = q[j] - origin_[j];
      if (exponent_ != 0) x = std::ldexp(x, -exponent_);
      lifted += x * x;
      s += x * cofactor_[j];
    }
    s += lifted * cofactor_[D];
    if (s < -box_bound_) return true;
    if (s > box_bound_) return false;
    return inside(q);
  }

  /// True/false when the filter proves q strictly inside / outside the sphere;
  /// nothing when undecided (q on or near the sphere, or no valid filter).
  std::optional<bool> inside(const Coords<D>& q) const {
    if (!valid_) return std::nullopt;
    double s = 0, magnitude = 0, carried = 0, lifted = 0;
    for (int j = 0; j < D; ++j) {
      double x = q[j] - origin_[j];
      if (exponent_ != 0) x = std::ldexp(x, -exponent_);
      const double ax = std::fabs(x);
      lifted += x * x;
      s += x * cofactor_[j];
      magnitude += ax * (std::fabs(cofactor_[j]) + error_[j]);
      carried += ax * error_[j];
    }
    s += lifted * cofactor_[D];
    magnitude += lifted * (std::fabs(cofactor_[D]) + error_[D]);
    carried += lifted * error_[D];
    const double b = bound(magnitude, carried);
    if (s < -b) return true;
    if (s > b) return false;
    return std::nullopt;
  }

  /// A box containing the closed ball.
  const Ball_box<D>& enclosing_box() const { return box_; }

 private:
  static double bound(double magnitude, double carried) {
    constexpr double gamma = kernel::error_bounds::gamma(2 * D + 3);
    return (gamma * magnitude + (1 + gamma) * carried) * (1 + 0x1p-30) + 0x1p-1000;
  }

  /// widen: added on both sides of the centre interval (and so of the box).
  Ball_box<D> compute_box(double widen = 0) const {
    using kernel::Interval;
    Ball_box<D> box;
    if (!valid_) return box;
    const Interval twice_al = Interval(2.0) * (Interval(cofactor_[D]) + Interval(-error_[D], error_[D]));
    if (!twice_al.sign()) return box;
    std::array<Interval, D> centre;
    Interval radius2(0.0);
    const Interval scale(std::ldexp(1.0, exponent_));
    for (int j = 0; j < D; ++j) {
      const Interval offset = -(Interval(cofactor_[j]) + Interval(-error_[j], error_[j])) / twice_al * scale;
      centre[j] = Interval(origin_[j]) + offset;
      if (widen != 0) centre[j] += Interval(-widen, widen);
      const double m = offset.magnitude();
      radius2 += Interval(m) * Interval(m);
    }
    const double radius = (Interval(std::sqrt(radius2.hi())) * Interval(1 + 0x1p-50)).hi();
    for (int j = 0; j < D; ++j) {
      box.lo[j] = (centre[j] - Interval(radius)).lo();
      box.hi[j] = (centre[j] + Interval(radius)).hi();
      if (!std::isfinite(box.lo[j]) || !std::isfinite(box.hi[j])) return box;
      box.centre_lo[j] = centre[j].lo();
      box.centre_hi[j] = centre[j].hi();
    }
    const Interval limit = Interval(radius) * Interval(radius) * Interval(1 + 0x1p-40) + Interval(0x1p-1000);
    box.radius2_limit = limit.hi();
    if (!std::isfinite(box.radius2_limit)) return box;
    box.bounded = true;
    return box;
  }

  Coords<D> origin_;
  std::array<double, D + 1> cofactor_{}, error_{};
  int exponent_ = 0;
  bool valid_ = false;
  Ball_box<D> box_;
  double box_bound_ = std::numeric_limits<double>::infinity();
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
