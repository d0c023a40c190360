// Pencil_rank: the paper's dd metric as one number per candidate, for ranking.
//
// The spheres through the D vertices of a face f form a pencil whose centres
// lie on the line c_f + t·n, c_f the circumcentre of f in its hyperplane and n
// the outer normal. The sphere through f and an outer point q has
//   t_q = (|q − c_f|² − r_f²) / (2 (q − c_f)·n) = (|x|² − 2 x·w) / (2 x·n),
// with x = q − f_0 and w = c_f − f_0 (c_f − f_0 ⟂ n and r_f = |w|). The apex of
// the Delaunay simplex on the outer side is the outer point of smallest t_q
// (the pencil of spheres through f: the paper's dd metric as one parameter). Computed in floating point, it only
// chooses which candidate the exact search tries first.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include "dewall/detail/common/coords.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <int D>
class Pencil_rank {
 public:
  /// f: the face's vertex coordinates; normal: an outer normal (any length).
  Pencil_rank(const std::array<const Coords<D>*, D>& f, const std::array<double, D>& normal)
      : origin_(*f[0]), normal_(normal) {
    // w = Σ λ_i a_i with a_i = f_i − f_0 and (a_k · w) = |a_k|²/2: a Gram system.
    constexpr int M = D - 1;
    std::array<std::array<double, D>, M> a;
    std::array<std::array<double, M + 1>, M> g;
    for (int i = 0; i < M; ++i)
      for (int j = 0; j < D; ++j) a[i][j] = (*f[i + 1])[j] - origin_[j];
    for (int i = 0; i < M; ++i) {
      for (int k = 0; k < M; ++k) g[i][k] = dot(a[i], a[k]);
      g[i][M] = 0.5 * dot(a[i], a[i]);
    }
    for (int c = 0; c < M; ++c) {  // Gaussian elimination, partial pivoting
      int p = c;
      for (int r = c + 1; r < M; ++r)
        if (std::fabs(g[r][c]) > std::fabs(g[p][c])) p = r;
      std::swap(g[c], g[p]);
      if (g[c][c] == 0) return;  // degenerate face: no ranking
      for (int r = c + 1; r < M; ++r) {
        const double m = g[r][c] / g[c][c];
        for (int k = c; k <= M; ++k) g[r][k] -= m * g[c][k];
      }
    }
    std::array<double, M> lambda;
    for (int c = M - 1; c >= 0; --c) {
      double v = g[c][M];
      for (int k = c + 1; k < M; ++k) v -= g[c][k] * lambda[k];
      lambda[c] = v / g[c][c];
    }
    w_.fill(0);
    for (int i = 0; i < M; ++i)
      for (int j = 0; j < D; ++j) w_[j] += lambda[i] * a[i][j];
    w_norm2_ = dot(w_, w_);
    valid_ = true;
  }

  bool valid() const { return valid_; }

  /// A priority for a box [lo, hi] of candidates (best-first search): about the
  /// smallest t_q of a point of the box on the outer side, +infinity when the
  /// box looks wholly inner. With power(x) = |x − w|² − |w|² and h(x) = x·n:
  /// t_q = power/h ≥ min power / max h when min power ≥ 0, ≥ min power / min h
  /// when min power < 0 < min h; a box straddling the face's hyperplane with
  /// negative power gets min power / max h (a rank, not a bound). Only orders.
  double box_key(const Coords<D>& lo, const Coords<D>& hi) const {
    if (!valid_) return 0.0;
    double power = -w_norm2_, h_max = 0, h_min = 0;
    for (int j = 0; j < D; ++j) {
      const double a = lo[j] - origin_[j], b = hi[j] - origin_[j];
      const double gap = w_[j] < a ? a - w_[j] : w_[j] > b ? w_[j] - b : 0.0;
      power += gap * gap;
      h_max += normal_[j] > 0 ? b * normal_[j] : a * normal_[j];
      h_min += normal_[j] > 0 ? a * normal_[j] : b * normal_[j];
    }
    if (!(h_max > 0)) return std::numeric_limits<double>::infinity();
    return power >= 0 || !(h_min > 0) ? power / h_max : power / h_min;
  }

  /// t_q up to a positive factor; +infinity when q does not look outer.
  double operator()(const Coords<D>& q) const {
    std::array<double, D> x;
    for (int j = 0; j < D; ++j) x[j] = q[j] - origin_[j];
    const double side = dot(x, normal_);
    if (!(side > 0)) return std::numeric_limits<double>::infinity();
    return (dot(x, x) - 2 * dot(x, w_)) / side;
  }

 private:
  static double dot(const std::array<double, D>& u, const std::array<double, D>& v) {
    double s = 0;
    for (int j = 0; j < D; ++j) s += u[j] * v[j];
    return s;
  }
  Coords<D> origin_;
  std::array<double, D> normal_, w_{};
  double w_norm2_ = 0;
  bool valid_ = false;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
