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
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "dewall/kernel/determinant.hpp"
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
  /// For each facet, a normal to its hyperplane in floating point, not unit, either way round:
  /// the cofactors of the orientation determinant along the last row (the generalised cross
  /// product of the edges from the first vertex).
  std::vector<std::array<double, D>> normals;
};

namespace detail {

using dewall::kernel::Point_d;

template <int D>
class Quickhull {
 public:
  /// `progress`: told a rough fraction done every few hundred facets; what it throws stops the work.
  Quickhull(std::span<const Point_d<D>> p, const std::function<void(double)>& progress) : p_(p), progress_(progress) {}

  std::optional<Convex_hull<D>> run() {
    for (const auto& q : p_)
      if (!dewall::kernel::is_finite(q)) return std::nullopt;  // the caller's checks name the point
    if (p_.size() < D + 1 || !first_simplex()) return std::nullopt;
    partition_all();
    // Oldest facet first (a queue, not a stack: 2.5-3 times fewer tests in 5-D and 6-D, where
    // the big early facets then take their points out of the running sooner)
    for (std::size_t next = 0; next < pending_.size(); ++next) {
      const std::int32_t f = pending_[next];
      if (facets_[f].alive && facets_[f].outside != none) add_point(f);
      // (the queue grows as it goes: its share done, never back)
      reported_ = std::max(reported_, static_cast<double>(next) / static_cast<double>(pending_.size()));
      if (next % 16 == 15) progress_(reported_);
    }
    return collect();
  }

 private:
  static constexpr std::uint32_t none = UINT32_MAX;  // the end of an outside set
  struct Facet {
    std::array<std::uint32_t, D> v;
    std::array<std::int32_t, D> nb;
    std::array<double, D> normal;  // orientation(v, x) ≈ normal · (x − v[0]), for ranking
    std::uint32_t outside = none;  // the outside set: its first point, the others chained by next_
    std::uint32_t furthest = 0;
    double height = -1;
    std::uint32_t stamp = 0;  // the step that last tested this facet
    bool seen = false;        // ... and whether that step's point saw it
    bool alive = true;
  };

  /// orientation(f's vertices, x), exact. A static filter decides first: height(f, x) is the
  /// orientation determinant expanded along x's row, with f's cofactors computed once by the
  /// kernel's own expansion (set_normal). Each of its monomials then carries the rounding
  /// factors of error_bounds.hpp's orientation_factors(D): the D differences, c(D − 1) in the
  /// cofactor, one product and D − 1 sums along x's row, c(D − 1) + 1 + (D − 1) = c(D). So
  /// error_bounds.hpp's steps 2–4 bound its error by orientation_epsilon(D)·Π_j S_j with S_j
  /// the bounding box's extents (enlarged as static_filter.hpp does; valid in the same domain).
  dewall::kernel::Sign orientation(const Facet& f, std::uint32_t x) const {
    return orientation(f, x, height(f.normal, p_[f.v[0]].x, x));
  }
  /// The same, given h = height(f.normal, f's first vertex, x).
  dewall::kernel::Sign orientation(const Facet& f, std::uint32_t x, double h) const {
    if (bound_ > 0) {
      if (h > bound_) return dewall::kernel::POSITIVE;
      if (h < -bound_) return dewall::kernel::NEGATIVE;
    }
    dewall::kernel::Orientation_points<D> s;
    for (int j = 0; j < D; ++j) s[j] = &p_[f.v[j]];
    s[D] = &p_[x];
    return dewall::kernel::orientation_d<D>(s);
  }

  double height(const std::array<double, D>& normal, const std::array<double, D>& origin, std::uint32_t x) const {
    double h = 0;
    for (int i = 0; i < D; ++i) h += normal[i] * (p_[x][i] - origin[i]);
    return h;
  }

  /// normal[j]: the cofactor of (x − v0)_j in det[v1 − v0, …, v_{D−1} − v0, x − v0], that is
  /// (−1)^(D−1+j) times the minor of the other rows without column j. Those D minors are the
  /// kernel's `determinant` expansion of [x − v0; v1 − v0; …] one level short of the top (the
  /// operations the filter's bound counts).
  void set_normal(Facet& f) const {
    const auto& a = p_[f.v[0]];
    dewall::kernel::Matrix<double, D> rows{};  // row 0, x's, is not read
    for (int r = 1; r < D; ++r)
      for (int c = 0; c < D; ++c) rows[r][c] = p_[f.v[r]][c] - a[c];
    std::array<double, (1 << D)> minor;
    dewall::kernel::lower_minors<D - 1, double, D>(rows, minor);
    for (int j = 0; j < D; ++j) {
      const double m = minor[((1u << D) - 1) & ~(1u << j)];
      f.normal[j] = (D - 1 + j) % 2 ? -m : m;
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

  /// Puts x into f's outside set; h = height(f.normal, f's first vertex, x).
  void assign(std::int32_t f, std::uint32_t x, double h) {
    Facet& g = facets_[f];
    // ties to the smaller index: of duplicates the first occurrence is the vertex, as in the Delaunay route
    if (g.outside == none || h > g.height || (h == g.height && x < g.furthest)) {
      g.height = h;
      g.furthest = x;
    }
    next_[x] = g.outside;
    g.outside = x;
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
  /// or 0 (no filter) outside its domain.
  void set_bound(const std::array<double, D>& low, const std::array<double, D>& high) {
    namespace eb = dewall::kernel::error_bounds;
    constexpr double margin = 1 + 0x1p-40;
    double bound = eb::orientation_epsilon(D) * margin;
    for (int c = 0; c < D; ++c) {
      const double s = (high[c] - low[c]) * margin;
      if (!(s >= eb::min_column_max && s <= eb::max_column_max)) return;
      bound *= s;
    }
    bound_ = bound;
  }

  /// Step 2.
  void partition_all() {
    next_.assign(p_.size(), none);
    std::vector<bool> in_simplex(p_.size());
    for (auto s : simplex_) in_simplex[s] = true;
    for (std::uint32_t x = 0; x < p_.size(); ++x) {
      if (in_simplex[x]) continue;
      for (std::int32_t f = 0; f <= D; ++f) {
        const double h = height(facets_[f].normal, p_[facets_[f].v[0]].x, x);
        if (orientation(facets_[f], x, h) == dewall::kernel::POSITIVE) {
          assign(f, x, h);
          break;
        }
      }
    }
    for (std::int32_t f = 0; f <= D; ++f)
      if (facets_[f].outside != none) pending_.push_back(f);
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
    created_.clear();
    ridges_.clear();
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
        // m is D - 2; the constant bound keeps GCC 12's -Warray-bounds from a false alarm
        std::sort(r.key.begin(), r.key.begin() + (D - 2));
        ridges_.push_back(r);
      }
      created_.push_back(f);
    }
    glue_ridges();
    // The seen facets' outside points, against the new facets only: most of the work. Their
    // planes are copied coordinate by coordinate, so that the heights of a block of facets are
    // computed side by side (vector instructions), each by height()'s operations in its order.
    const std::size_t m = created_.size();
    planes_.resize(2 * D * m);
    for (std::size_t k = 0; k < m; ++k)
      for (int i = 0; i < D; ++i) {
        planes_[i * m + k] = facets_[created_[k]].normal[i];
        planes_[(D + i) * m + k] = p_[facets_[created_[k]].v[0]][i];
      }
    for (const std::int32_t g : seen) {
      for (std::uint32_t x = facets_[g].outside, after; x != none; x = after) {
        after = next_[x];  // before assign() chains x elsewhere
        if (x == apex) continue;
        if (++tested_ % 16384 == 0) progress_(reported_);  // the first steps test most points, each
        for (std::size_t begin = 0; begin < m; begin += block) {
          const std::size_t end = std::min(m, begin + block);
          std::array<double, block> h{};
          for (int i = 0; i < D; ++i) {
            const double xi = p_[x][i];
            const double* normal = &planes_[i * m];
            const double* origin = &planes_[(D + i) * m];
            for (std::size_t k = begin; k < end; ++k) h[k - begin] += normal[k] * (xi - origin[k]);
          }
          std::size_t k = begin;
          while (k < end && orientation(facets_[created_[k]], x, h[k - begin]) != dewall::kernel::POSITIVE) ++k;
          if (k < end) {
            assign(created_[k], x, h[k - begin]);
            break;
          }
        }
      }
      facets_[g].alive = false;
      facets_[g].outside = none;
      free_.push_back(g);
    }
    for (const std::int32_t f : created_)
      if (facets_[f].outside != none) pending_.push_back(f);
  }

  /// Glues the new facets to each other: each ridge through the apex is in exactly two of them,
  /// found by its other vertices in an open-addressing table (a sort was a fifth of the time).
  void glue_ridges() {
    std::size_t size = 16;
    while (size < 2 * ridges_.size()) size *= 2;
    table_.assign(size, -1);
    for (std::size_t i = 0; i < ridges_.size(); ++i) {
      const Ridge& r = ridges_[i];
      std::uint64_t hash = 0;
      for (const std::uint32_t x : r.key) hash = (hash ^ x) * 0x9E3779B97F4A7C15ull;
      for (std::size_t slot = (hash >> 32) & (size - 1);; slot = (slot + 1) & (size - 1)) {
        const std::int32_t other = table_[slot];
        if (other < 0) {
          table_[slot] = static_cast<std::int32_t>(i);
          break;
        }
        const Ridge& q = ridges_[other];
        if (q.key == r.key) {
          facets_[r.facet].nb[r.slot] = q.facet;
          facets_[q.facet].nb[q.slot] = r.facet;
          break;
        }
      }
    }
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
      out.normals.push_back(facets_[f].normal);
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
  const std::function<void(double)>& progress_;
  double reported_ = 0;     // the last fraction told
  std::size_t tested_ = 0;  // outside points tested against new facets, all steps
  std::array<std::uint32_t, D + 1> simplex_{};
  std::vector<Facet> facets_;
  struct Ridge {
    std::array<std::uint32_t, D> key;  // the ridge's vertices but the apex, sorted (D − 2 used)
    std::int32_t facet;
    int slot;
  };
  static constexpr std::size_t block = 8;  // new facets tested together (add_point)
  std::vector<std::uint32_t> next_;  // next_[x]: the point after x in its facet's outside set
  std::vector<std::int32_t> free_, pending_, created_, table_;
  std::vector<Ridge> ridges_;
  std::vector<double> planes_;  // the new facets' normals, then first vertices, by coordinate
  std::uint32_t step_ = 0;
  double bound_ = 0;  // the static filter's bound, 0 for none
};

}  // namespace detail

/// The convex hull of `points` by exact Quickhull, or nothing when the points contain a
/// non-finite coordinate, number fewer than D + 1, or the first simplex chosen in floating
/// point is flat (points that do not span E^D, or nearly so): the caller then takes the
/// Delaunay triangulation's boundary, which raises the right error or copes.
/// Cost: expected O(n log h) orientation tests on random points (h hull vertices).
/// `progress` is told a rough fraction done every few hundred facets; what it throws stops the
/// work (and is passed on).
template <int D>
std::optional<Convex_hull<D>> convex_hull(std::span<const dewall::kernel::Point_d<D>> points,
                                          const std::function<void(double)>& progress) {
  return detail::Quickhull<D>(points, progress).run();
}

}  // namespace dewall_python
DEWALL_FLOATING_POINT_CODE_END
