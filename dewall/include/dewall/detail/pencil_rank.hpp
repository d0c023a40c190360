// Pencil_rank: the paper's dd metric as one number per candidate, for ranking.
//
// The spheres through the D vertices of a face f form a pencil whose centres
// lie on the line c_f + t·n, c_f the circumcentre of f in its hyperplane and n
// the outer normal. The sphere through f and an outer point q has
//   t_q = (|q − c_f|² − r_f²) / (2 (q − c_f)·n) = (|x|² − 2 x·w) / (2 x·n),
// with x = q − f_0 and w = c_f − f_0 (c_f − f_0 ⟂ n and r_f = |w|). The apex of
// the Delaunay simplex on the outer side is the outer point of smallest t_q
// (performance model of DESIGN.md). Computed in floating point, it only
// chooses which candidate the exact search tries first.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include "dewall/detail/uniform_grid.hpp"
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
    valid_ = true;
  }

  bool valid() const { return valid_; }

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
  bool valid_ = false;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
