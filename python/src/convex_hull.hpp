// The convex hull of points in E^D (D = 2 … 6) by Quickhull (Barber, Dobkin,
// Huhdanpaa, "The Quickhull algorithm for convex hulls", ACM TOMS 22(4),
// 1996), every decision by the library's exact orientation predicate. What
// dewall.ConvexHull reports, without triangulating the interior.
//
// 1. A first simplex of D + 1 points, chosen in floating point (the extremes
//    along x, then the point furthest from the affine hull of those chosen),
//    accepted only when its exact orientation is non-zero.
// 2. Each other point goes to the outside set of the first facet it lies
//    strictly outside of (orientation > 0); points outside no facet are inside
//    the simplex, or on its boundary, and are never hull vertices.
// 3. While a facet has an outside set: its furthest point p (floating-point
//    height: a ranking only) is strictly outside the hull, hence a vertex of
//    the hull with p. The facets p sees strictly (exact orientation > 0) form
//    a connected region (whole flat faces: the facets of one face share their
//    plane); its boundary ridges, each joined to p, are the new facets. The
//    points of the seen facets' outside sets are tested against the new facets
//    only (a point strictly outside the new hull is strictly outside one of
//    them: the paper's partition argument); the others are inside.
//
// Each facet stores its D vertices so that orientation(facet, x) > 0 exactly
// when x is strictly outside its hyperplane. A new facet is a seen facet with
// the vertex opposite its horizon ridge replaced by p, which keeps that rule.
// Points on the hull's boundary are not outside any facet, so they become
// vertices only when added before the points that later surround them: the
// caller merges facets in one hyperplane (`flat`) where it wants only extreme
// points (python/dewall/_boundary.py).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "dewall/kernel/error_bounds.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall_python {

template <int D>
struct Convex_hull {
  /// The facets, each oriented: orientation(facet, x) > 0 exactly when x is strictly outside.
  std::vector<std::array<std::uint32_t, D>> facets;
  /// neighbors[f][j]: the facet across the ridge of f opposite its vertex j.
  std::vector<std::array<std::int32_t, D>> neighbors;
  /// For each facet, an input point strictly inside its hyperplane (a vertex of the first simplex).
  std::vector<std::uint32_t> below;
  /// Whether two neighbouring facets lie in one hyperplane (exact orientation zero).
  bool flat = false;
};

namespace detail {

using dewall::kernel::Point_d;

/// The determinant of an n × n matrix (n ≤ 6) by Gaussian elimination with partial pivoting:
/// floating point, used for ranking only.
template <int N>
double determinant(std::array<std::array<double, N>, N> a, int n) {
  double det = 1;
  for (int c = 0; c < n; ++c) {
    int pivot = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    if (a[pivot][c] == 0) return 0;
    if (pivot != c) {
      std::swap(a[pivot], a[c]);
      det = -det;
    }
    det *= a[c][c];
    for (int r = c + 1; r < n; ++r) {
      const double f = a[r][c] / a[c][c];
      for (int k = c; k < n; ++k) a[r][k] -= f * a[c][k];
    }
  }
  return det;
}

template <int D>
class Quickhull {
 public:
  explicit Quickhull(std::span<const Point_d<D>> p) : p_(p) {}

  std::optional<Convex_hull<D>> run() {
    for (const auto& q : p_)
      if (!dewall::kernel::is_finite(q)) return std::nullopt;  // the caller's checks name the point
    if (p_.size() < D + 1 || !first_simplex()) return std::nullopt;
    partition_all();
    while (!pending_.empty()) {
      const std::int32_t f = pending_.back();
      pending_.pop_back();
      if (facets_[f].alive && !facets_[f].outside.empty()) add_point(f);
    }
    return collect();
  }

 private:
  struct Facet {
    std::array<std::uint32_t, D> v;
    std::array<std::int32_t, D> nb;
    std::array<double, D> normal;  // orientation(v, x) ≈ normal · (x − v[0]), for ranking
    std::vector<std::uint32_t> outside;
    std::uint32_t furthest = 0;
    double height = -1;
    std::uint32_t stamp = 0;  // the step that last tested this facet
    bool seen = false;        // ... and whether that step's point saw it
    bool alive = true;
  };

  /// orientation(f's vertices, x), exact. In 2-D and 3-D a static filter decides first:
  /// height(f, x) is the orientation determinant, expanded along x's row with f's cofactors
  /// computed once (set_normal), and each of its monomials carries at most the rounding factors
  /// the library's filter allows for (2-D: two differences, a product, a sum: 4; 3-D: three
  /// differences, two products, three sums: 8 — error_bounds.hpp's orientation_factors(D)), so
  /// error_bounds.hpp's steps 2–4 bound its error by orientation_epsilon(D)·Π_j S_j with S_j
  /// the bounding box's extents (enlarged as static_filter.hpp does; valid in the same domain).
  dewall::kernel::Sign orientation(const Facet& f, std::uint32_t x) const {
    if constexpr (D <= 3) {
      if (bound_ > 0) {
        const double h = height(f, x);
        if (h > bound_) return dewall::kernel::POSITIVE;
        if (h < -bound_) return dewall::kernel::NEGATIVE;
      }
    }
    dewall::kernel::Orientation_points<D> s;
    for (int j = 0; j < D; ++j) s[j] = &p_[f.v[j]];
    s[D] = &p_[x];
    return dewall::kernel::orientation_d<D>(s);
  }

  double height(const Facet& f, std::uint32_t x) const {
    double h = 0;
    for (int i = 0; i < D; ++i) h += f.normal[i] * (p_[x][i] - p_[f.v[0]][i]);
    return h;
  }

  /// normal[i]: the cofactor of (x − v0)_i in det[v1 − v0, …, v_{D−1} − v0, x − v0]; in 2-D
  /// and 3-D written out (the filter's error bound counts these operations).
  void set_normal(Facet& f) const {
    const auto& a = p_[f.v[0]];
    if constexpr (D == 2) {
      const double ex = p_[f.v[1]][0] - a[0], ey = p_[f.v[1]][1] - a[1];
      f.normal = {-ey, ex};  // det[e; w] = ex·wy − ey·wx
      return;
    } else if constexpr (D == 3) {
      const auto& b = p_[f.v[1]];
      const auto& c = p_[f.v[2]];
      const double bx = b[0] - a[0], by = b[1] - a[1], bz = b[2] - a[2];
      const double cx = c[0] - a[0], cy = c[1] - a[1], cz = c[2] - a[2];
      f.normal = {by * cz - bz * cy, bz * cx - bx * cz, bx * cy - by * cx};  // det[b; c; w] = w · (b × c)
      return;
    }
    for (int i = 0; i < D; ++i) {
      std::array<std::array<double, D>, D> minor{};
      for (int r = 1; r < D; ++r)
        for (int c = 0, k = 0; c < D; ++c)
          if (c != i) minor[r - 1][k++] = p_[f.v[r]][c] - p_[f.v[0]][c];
      f.normal[i] = ((D - 1 + i) % 2 ? -1.0 : 1.0) * determinant<D>(minor, D - 1);
    }
  }

  std::int32_t new_facet(const std::array<std::uint32_t, D>& v) {
    std::int32_t id;
    if (!free_.empty()) {
      id = free_.back();
      free_.pop_back();
      facets_[id] = Facet{};
    } else {
      id = static_cast<std::int32_t>(facets_.size());
      facets_.emplace_back();
    }
    facets_[id].v = v;
    set_normal(facets_[id]);
    return id;
  }

  void assign(std::int32_t f, std::uint32_t x) {
    Facet& g = facets_[f];
    const double h = height(g, x);
    if (g.outside.empty() || h > g.height) {
      g.height = h;
      g.furthest = x;
    }
    g.outside.push_back(x);
  }

  /// Step 1. Floating point chooses (extremes, then the furthest from the affine hull of the
  /// chosen ones, by Gram–Schmidt); the exact orientation accepts or refuses.
  bool first_simplex() {
    const std::size_t n = p_.size();
    std::size_t lo = 0, hi = 0;
    std::array<double, D> low = p_[0].x, high = p_[0].x;
    for (std::size_t i = 1; i < n; ++i) {
      if (p_[i][0] < p_[lo][0]) lo = i;
      if (p_[i][0] > p_[hi][0]) hi = i;
      for (int c = 0; c < D; ++c) low[c] = std::min(low[c], p_[i][c]), high[c] = std::max(high[c], p_[i][c]);
    }
    if (lo == hi) return false;
    set_bound(low, high);
    simplex_[0] = static_cast<std::uint32_t>(lo);
    simplex_[1] = static_cast<std::uint32_t>(hi);
    std::vector<std::array<double, D>> basis;
    const auto add_direction = [&](std::uint32_t i) {
      std::array<double, D> u;
      for (int c = 0; c < D; ++c) u[c] = p_[i][c] - p_[lo][c];
      for (const auto& b : basis) {
        double dot = 0;
        for (int c = 0; c < D; ++c) dot += u[c] * b[c];
        for (int c = 0; c < D; ++c) u[c] -= dot * b[c];
      }
      double norm = 0;
      for (int c = 0; c < D; ++c) norm += u[c] * u[c];
      norm = std::sqrt(norm);
      if (!(norm > 0)) return false;
      for (int c = 0; c < D; ++c) u[c] /= norm;
      basis.push_back(u);
      return true;
    };
    if (!add_direction(simplex_[1])) return false;
    for (int k = 2; k <= D; ++k) {
      double best = -1;
      std::size_t arg = 0;
      for (std::size_t i = 0; i < n; ++i) {
        std::array<double, D> u;
        double d2 = 0;
        for (int c = 0; c < D; ++c) d2 += (u[c] = p_[i][c] - p_[lo][c]) * u[c];
        for (const auto& b : basis) {
          double dot = 0;
          for (int c = 0; c < D; ++c) dot += u[c] * b[c];
          d2 -= dot * dot;
        }
        if (d2 > best) best = d2, arg = i;
      }
      simplex_[k] = static_cast<std::uint32_t>(arg);
      if (!add_direction(simplex_[k])) return false;
    }
    dewall::kernel::Orientation_points<D> s;
    for (int j = 0; j <= D; ++j) s[j] = &p_[simplex_[j]];
    if (dewall::kernel::orientation_d<D>(s) == dewall::kernel::ZERO) return false;
    // Facet i: the simplex without vertex i; its neighbour opposite vertex s_m is facet m.
    for (int i = 0; i <= D; ++i) {
      std::array<std::uint32_t, D> v;
      std::array<std::int32_t, D> nb;
      for (int m = 0, j = 0; m <= D; ++m)
        if (m != i) v[j] = simplex_[m], nb[j++] = m;
      const std::int32_t f = new_facet(v);
      facets_[f].nb = nb;
      if (orientation(facets_[f], simplex_[i]) == dewall::kernel::POSITIVE) {  // s_i must be inside
        std::swap(facets_[f].v[0], facets_[f].v[1]);
        std::swap(facets_[f].nb[0], facets_[f].nb[1]);
        set_normal(facets_[f]);
      }
    }
    return true;
  }

  /// The static filter's bound for points in [low, high] (static_filter.hpp's construction),
  /// or 0 (no filter) outside its domain or above 3-D.
  void set_bound(const std::array<double, D>& low, const std::array<double, D>& high) {
    namespace eb = dewall::kernel::error_bounds;
    if constexpr (D <= 3) {
      constexpr double margin = 1 + 0x1p-40;
      double bound = eb::orientation_epsilon(D) * margin;
      for (int c = 0; c < D; ++c) {
        const double s = (high[c] - low[c]) * margin;
        if (!(s >= eb::min_column_max && s <= eb::max_column_max)) return;
        bound *= s;
      }
      bound_ = bound;
    }
  }

  /// Step 2.
  void partition_all() {
    std::vector<bool> in_simplex(p_.size());
    for (auto s : simplex_) in_simplex[s] = true;
    for (std::uint32_t x = 0; x < p_.size(); ++x) {
      if (in_simplex[x]) continue;
      for (std::int32_t f = 0; f <= D; ++f)
        if (orientation(facets_[f], x) == dewall::kernel::POSITIVE) {
          assign(f, x);
          break;
        }
    }
    for (std::int32_t f = 0; f <= D; ++f)
      if (!facets_[f].outside.empty()) pending_.push_back(f);
  }

  /// Step 3 for the furthest point of facet `start`'s outside set.
  void add_point(std::int32_t start) {
    const std::uint32_t apex = facets_[start].furthest;
    const std::uint32_t stamp = ++step_;
    // The facets the apex sees, by a search from `start` (which it sees); the horizon ridges.
    std::vector<std::int32_t> seen{start};
    std::vector<std::pair<std::int32_t, int>> horizon;  // (seen facet, slot of the ridge)
    facets_[start].stamp = stamp;
    facets_[start].seen = true;
    for (std::size_t k = 0; k < seen.size(); ++k) {
      const std::int32_t g = seen[k];
      for (int j = 0; j < D; ++j) {
        const std::int32_t h = facets_[g].nb[j];
        Facet& fh = facets_[h];
        if (fh.stamp != stamp) {
          fh.stamp = stamp;
          fh.seen = orientation(fh, apex) == dewall::kernel::POSITIVE;
          if (fh.seen) seen.push_back(h);
        }
        if (!fh.seen) horizon.emplace_back(g, j);
      }
    }
    // The new facets: each horizon ridge joined to the apex, glued to the unseen facet across it
    // and to each other across the ridges through the apex (matched by their other vertices).
    std::vector<std::int32_t> created;
    struct Ridge {
      std::array<std::uint32_t, D> key;  // the ridge's vertices but the apex, sorted (D − 2 used)
      std::int32_t facet;
      int slot;
    };
    std::vector<Ridge> ridges;
    for (const auto& [g, j] : horizon) {
      std::array<std::uint32_t, D> v = facets_[g].v;
      v[j] = apex;
      const std::int32_t h = facets_[g].nb[j];
      const std::int32_t f = new_facet(v);
      facets_[f].stamp = stamp;  // neither seen nor to be tested again in this step
      facets_[f].nb[j] = h;
      for (int k = 0; k < D; ++k)
        if (facets_[h].nb[k] == g) facets_[h].nb[k] = f;
      for (int k = 0; k < D; ++k) {
        if (k == j) continue;
        Ridge r{{}, f, k};
        int m = 0;
        for (int i = 0; i < D; ++i)
          if (i != k && i != j) r.key[m++] = v[i];
        std::sort(r.key.begin(), r.key.begin() + m);
        ridges.push_back(r);
      }
      created.push_back(f);
    }
    std::sort(ridges.begin(), ridges.end(), [](const Ridge& a, const Ridge& b) { return a.key < b.key; });
    for (std::size_t i = 0; i + 1 < ridges.size(); i += 2) {
      facets_[ridges[i].facet].nb[ridges[i].slot] = ridges[i + 1].facet;
      facets_[ridges[i + 1].facet].nb[ridges[i + 1].slot] = ridges[i].facet;
    }
    // The seen facets' outside points, against the new facets only.
    for (const std::int32_t g : seen) {
      for (const std::uint32_t x : facets_[g].outside) {
        if (x == apex) continue;
        for (const std::int32_t f : created)
          if (orientation(facets_[f], x) == dewall::kernel::POSITIVE) {
            assign(f, x);
            break;
          }
      }
      facets_[g].alive = false;
      facets_[g].outside = {};
      free_.push_back(g);
    }
    for (const std::int32_t f : created)
      if (!facets_[f].outside.empty()) pending_.push_back(f);
  }

  Convex_hull<D> collect() const {
    Convex_hull<D> out;
    // The live facets in index order; in 2-D in boundary order instead (each edge (a, b) is
    // followed by its neighbour opposite a, the edge from b: clockwise).
    std::vector<std::int32_t> order, index(facets_.size(), -1);
    for (std::size_t f = 0; f < facets_.size(); ++f)
      if (facets_[f].alive) order.push_back(static_cast<std::int32_t>(f));
    if constexpr (D == 2)
      for (std::size_t k = 1; k < order.size(); ++k) order[k] = facets_[order[k - 1]].nb[0];
    for (const std::int32_t f : order) {
      index[f] = static_cast<std::int32_t>(out.facets.size());
      out.facets.push_back(facets_[f].v);
    }
    for (const std::int32_t f : order) {
      std::array<std::int32_t, D> nb;
      for (int j = 0; j < D; ++j) {
        const std::int32_t h = facets_[f].nb[j];
        nb[j] = index[h];
        if (h > f) {  // each pair once: is the other facet's far vertex on f's plane?
          for (const std::uint32_t x : facets_[h].v)
            if (std::find(facets_[f].v.begin(), facets_[f].v.end(), x) == facets_[f].v.end() &&
                orientation(facets_[f], x) == dewall::kernel::ZERO)
              out.flat = true;
        }
      }
      out.neighbors.push_back(nb);
      std::uint32_t below = simplex_[0];
      for (const std::uint32_t s : simplex_)
        if (orientation(facets_[f], s) == dewall::kernel::NEGATIVE) {
          below = s;
          break;
        }
      out.below.push_back(below);
    }
    return out;
  }

  std::span<const Point_d<D>> p_;
  std::array<std::uint32_t, D + 1> simplex_{};
  std::vector<Facet> facets_;
  std::vector<std::int32_t> free_, pending_;
  std::uint32_t step_ = 0;
  double bound_ = 0;  // the static filter's bound, 0 for none
};

}  // namespace detail

/// The convex hull of `points` by exact Quickhull, or nothing when the points contain a
/// non-finite coordinate, number fewer than D + 1, or the first simplex chosen in floating
/// point is flat (points that do not span E^D, or nearly so): the caller then takes the
/// Delaunay triangulation's boundary, which raises the right error or copes.
/// Cost: expected O(n log h) orientation tests on random points (h hull vertices).
template <int D>
std::optional<Convex_hull<D>> convex_hull(std::span<const dewall::kernel::Point_d<D>> points) {
  return detail::Quickhull<D>(points).run();
}

}  // namespace dewall_python
DEWALL_FLOATING_POINT_CODE_END
