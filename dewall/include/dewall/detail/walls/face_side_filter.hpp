// Face_side_filter: orientation(f_0 … f_{D−1}, q) for one face f and many q,
// at the cost of a dot product per q, with a proven error bound.
//
// Expanding det[f_1 − f_0, …, f_{D−1} − f_0, q − f_0] along its last row gives
// Σ_j (q_j − f0_j)·C_j, where the cofactors C_j, (D−1)×(D−1) determinants of the
// face's differences, are computed once per face by the kernel's `determinant`.
// By error_bounds.hpp (steps 1–4 with D − 1), |Ĉ_j − C_j| ≤ e_j =
// ε_{D−1}·Π_{k≠j} M_k when the face's column maxima M_k lie in the filter domain.
// For x̂_j = fl(q_j − f0_j) = x_j(1 + δ) and S = fl(Σ_j x̂_j·Ĉ_j) (one product and
// at most D − 1 sums per term):
//   |S − Σ_j x_j C_j| ≤ γ_{D+1}·Σ_j |x̂_j|(|Ĉ_j| + e_j) + (1 + γ_{D+1})·Σ_j |x̂_j| e_j
// (using |x_j| ≤ |x̂_j|/(1 − u), absorbed with the rounding of this bound itself by
// the (1 + 2^-30) margin), plus at most D·2^-1075 lost to underflow in the
// products, covered by the absolute term 2^-1000. Overflow gives an infinite
// or NaN S or bound, which never passes the test. Undecided cases return
// nothing and go to the kernel's exact predicate.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "dewall/detail/common/coords.hpp"
#include "dewall/kernel/determinant.hpp"
#include "dewall/kernel/error_bounds.hpp"
#include "dewall/kernel/interval.hpp"
#include "dewall/kernel/sign.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <int D>
class Face_side_filter {
 public:
  /// f: the face's vertex coordinates; [lo, hi]: a box holding every query
  /// (the bounding box of all points), which gives a per-face error bound.
  Face_side_filter(const std::array<const Coords<D>*, D>& f, const Coords<D>& lo, const Coords<D>& hi)
      : origin_(*f[0]) {
    namespace eb = kernel::error_bounds;
    std::array<std::array<double, D>, D - 1> rows;
    std::array<double, D> col_max{};
    for (int i = 0; i + 1 < D; ++i)
      for (int j = 0; j < D; ++j) {
        rows[i][j] = (*f[i + 1])[j] - origin_[j];
        col_max[j] = std::max(col_max[j], std::fabs(rows[i][j]));
      }
    valid_ = true;
    for (int j = 0; j < D; ++j)
      // A zero column makes every minor containing it exactly 0 (each of its
      // products has a zero factor), so it needs no domain check.
      if (col_max[j] != 0 && !(col_max[j] >= eb::min_column_max && col_max[j] <= eb::max_column_max))
        valid_ = false;
    for (int j = 0; j < D; ++j) {
      // Cofactor of (D−1, j): (−1)^(D−1+j) times the minor without column j.
      kernel::Matrix<double, D - 1> minor;
      double product = 1;
      for (int i = 0; i + 1 < D; ++i)
        for (int k = 0, c = 0; k < D; ++k)
          if (k != j) minor[i][c++] = rows[i][k];
      for (int k = 0; k < D; ++k)
        if (k != j) product *= col_max[k];
      const double value = kernel::determinant<double, D - 1>(minor);
      cofactor_[j] = (D - 1 + j) % 2 == 0 ? value : -value;
      error_[j] = eb::orientation_epsilon(D - 1) * product;
    }
    region_bound_ = region_bound(lo, hi);
  }

  /// For approximations within `coordinate_error` (δ) of the points (kernel/
  /// concepts.hpp), for pruning only (box_may_hold_outer, clip_to_outer_side,
  /// given boxes widened by 2δ; not operator()). With d = x − f_0 for the exact
  /// x and f_0, d = x' − f̂_0 for x' = x − (f_0 − f̂_0), within 2δ of x̂: the
  /// proofs below hold for x' when the cofactors' errors e_j cover the exact
  /// face's, here by interval arithmetic on the rows widened by 2δ, and the
  /// constructor's box is widened by 2δ.
  Face_side_filter(const std::array<const Coords<D>*, D>& f, const Coords<D>& lo, const Coords<D>& hi,
                   double coordinate_error)
      : Face_side_filter(f, lo, hi) {
    using kernel::Interval;
    const double w = 2 * coordinate_error;
    valid_ = std::isfinite(w);
    if (!valid_) return;
    const Interval spread(-w, w);
    for (int j = 0; j < D; ++j) {
      kernel::Matrix<Interval, D - 1> minor;
      for (int i = 0; i + 1 < D; ++i)
        for (int k = 0, c = 0; k < D; ++k)
          if (k != j) minor[i][c++] = Interval((*f[i + 1])[k]) - Interval(origin_[k]) + spread;
      const Interval value = kernel::determinant<Interval, D - 1>(minor);
      const Interval exact = (D - 1 + j) % 2 == 0 ? value : -value;
      error_[j] = error_from(exact, cofactor_[j]);
      if (!std::isfinite(error_[j])) valid_ = false;
    }
    region_bound_ = region_bound(widened_lower(lo, w), widened_upper(hi, w));
  }

  /// The largest |v − c| for v in `exact`, rounded up; NaN (not finite) when
  /// either is not finite.
  static double error_from(const kernel::Interval& exact, double c) {
    using kernel::Interval;
    const double above = (Interval(exact.hi()) - Interval(c)).hi(), below = (Interval(c) - Interval(exact.lo())).hi();
    return std::isfinite(above) && std::isfinite(below) ? std::max(above, below)
                                                        : std::numeric_limits<double>::quiet_NaN();
  }

  /// The box [lo − w, hi + w], rounded outwards.
  static Coords<D> widened_lower(Coords<D> lo, double w) {
    for (double& v : lo) v = (kernel::Interval(v) - kernel::Interval(w)).lo();
    return lo;
  }
  static Coords<D> widened_upper(Coords<D> hi, double w) {
    for (double& v : hi) v = (kernel::Interval(v) + kernel::Interval(w)).hi();
    return hi;
  }

  /// The cofactors: orientation(f, q) ≈ Σ_j (q_j − f0_j)·C_j, so C is a normal
  /// pointing to the outer side (for ranking; not a proof).
  const std::array<double, D>& normal() const { return cofactor_; }

  /// Shrinks the box [lo, hi] to a box that still holds every point of it
  /// strictly on the outer side of f; false when no point of it can be there.
  /// Proof: with d = x − f_0 (exact) and |Ĉ_j − C_j| ≤ e_j, orientation(f, x) =
  /// Σ_j d_j C_j ≤ Σ_j (d_j Ĉ_j + |d_j| e_j). An outer x therefore has
  ///   d_k Ĉ_k + |d_k| e_k > −u_k,   u_k = Σ_{j≠k} max over the box of (d_j Ĉ_j + |d_j| e_j).
  /// When Ĉ_k > e_k (the sign of C_k is certain), d_k < 0 needs d_k (Ĉ_k − e_k) > −u_k,
  /// a lower bound on x_k; when u_k ≤ 0 even d_k > 0 is needed: x_k > f0_k
  /// strictly, so a hull face whose plane carries other points (a lattice's
  /// side) leaves nothing to scan. Symmetrically when Ĉ_k < −e_k. Everything is
  /// evaluated in outward-rounded interval arithmetic.
  bool clip_to_outer_side(Coords<D>& lo, Coords<D>& hi) const {
    if (!valid_) return true;
    using kernel::Interval;
    constexpr double inf = std::numeric_limits<double>::infinity();
    std::array<double, D> worst;  // max over the box of d_j Ĉ_j + |d_j| e_j, rounded up
    for (int j = 0; j < D; ++j) {
      const Interval dl = Interval(lo[j]) - Interval(origin_[j]);
      const Interval dh = Interval(hi[j]) - Interval(origin_[j]);
      const Interval d(std::min(dl.lo(), dh.lo()), std::max(dl.hi(), dh.hi()));
      // A term known to be 0 (an axis-aligned face) stays exactly 0: the outward
      // rounding would make it 2^-1074, which turns the strict test below for a
      // hull face's hyperplane (a lattice's side) into a scan of that side.
      worst[j] = cofactor_[j] == 0 && error_[j] == 0
                     ? 0.0
                     : ((d * Interval(cofactor_[j])) + Interval(d.magnitude()) * Interval(error_[j])).hi();
    }
    for (int k = 0; k < D; ++k) {
      const bool positive = cofactor_[k] > error_[k], negative = cofactor_[k] < -error_[k];
      if (!positive && !negative) continue;
      Interval u(0.0);
      for (int j = 0; j < D; ++j)
        if (j != k && worst[j] != 0) u += Interval(worst[j]);
      if (positive) {
        // d_k > −u/(Ĉ_k − e_k) when u > 0; d_k > 0 when u ≤ 0.
        const double limit = u.hi() > 0
                                 ? (Interval(origin_[k]) - u / (Interval(cofactor_[k]) - Interval(error_[k]))).lo()
                                 : std::nextafter(origin_[k], inf);
        lo[k] = std::max(lo[k], limit);
      } else {
        const double limit = u.hi() > 0
                                 ? (Interval(origin_[k]) + u / (Interval(-cofactor_[k]) - Interval(error_[k]))).hi()
                                 : std::nextafter(origin_[k], -inf);
        hi[k] = std::min(hi[k], limit);
      }
      if (!(lo[k] <= hi[k])) return false;
    }
    return true;
  }

  /// False only when no point of the box [lo, hi] (inside the constructor's
  /// box) is strictly on the outer side of f: for pruning a search structure.
  /// Proof: for x in the box, with d = x − f_0, orientation(f, x) = Σ_j d_j C_j ≤
  /// Σ_j d_j Ĉ_j + Σ_j |d_j| e_j. The linear part is largest at the corner x*
  /// (hi_j where Ĉ_j > 0, lo_j otherwise); S(x*) = fl(Σ_j fl(x*_j − f0_j)·Ĉ_j)
  /// is within γ_{D+1}·Σ_j |d*_j||Ĉ_j| of it, and x* and x lie in the
  /// constructor's box, so orientation(f, x) ≤ S(x*) + region_bound_: a corner
  /// with S(x*) ≤ −region_bound_ proves orientation ≤ 0 on the whole box.
  bool box_may_hold_outer(const Coords<D>& lo, const Coords<D>& hi) const {
    if (!valid_) return true;
    double s = 0;
    for (int j = 0; j < D; ++j) s += ((cofactor_[j] > 0 ? hi[j] : lo[j]) - origin_[j]) * cofactor_[j];
    return s > -region_bound_;
  }

  /// The per-query bound of operator() with |x_j| replaced by its largest
  /// value in the box [lo, hi].
  double region_bound(const Coords<D>& lo, const Coords<D>& hi) const {
    double magnitude = 0, carried = 0;
    for (int j = 0; j < D; ++j) {
      const double reach = std::max(std::fabs(lo[j] - origin_[j]), std::fabs(hi[j] - origin_[j]));
      magnitude += reach * (std::fabs(cofactor_[j]) + error_[j]);
      carried += reach * error_[j];
    }
    return bound(magnitude, carried);
  }

  static double bound(double magnitude, double carried) {
    constexpr double gamma = kernel::error_bounds::gamma(D + 1);
    return (gamma * magnitude + (1 + gamma) * carried) * (1 + 0x1p-30) + 0x1p-1000;
  }

  /// The sign of orientation(f, q) when the filter can prove it.
  /// \pre q lies in the box given to the constructor.
  std::optional<kernel::Sign> operator()(const Coords<D>& q) const {
    if (!valid_) return std::nullopt;
    namespace eb = kernel::error_bounds;
    double s = 0;
    for (int j = 0; j < D; ++j) s += (q[j] - origin_[j]) * cofactor_[j];
    if (s > region_bound_) return kernel::POSITIVE;  // the common case: one bound per face
    if (s < -region_bound_) return kernel::NEGATIVE;
    double magnitude = 0, carried = 0;
    for (int j = 0; j < D; ++j) {
      const double ax = std::fabs(q[j] - origin_[j]);
      magnitude += ax * (std::fabs(cofactor_[j]) + error_[j]);
      carried += ax * error_[j];
    }
    const double b = bound(magnitude, carried);
    if (s > b) return kernel::POSITIVE;
    if (s < -b) return kernel::NEGATIVE;
    return std::nullopt;
  }

 private:
  Coords<D> origin_;
  std::array<double, D> cofactor_{}, error_{};
  double region_bound_ = std::numeric_limits<double>::infinity();
  bool valid_ = false;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
