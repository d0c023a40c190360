// The certifier as it was before its facet matching moved to compact records
// (certify/include/dewall/certify/facet_table.hpp): a cell copy per row, facets
// grouped through Face_buckets, the covering test serial. Kept as a test oracle
// only: the new certifier must give the same report, rule and witness, on every
// input and mutant (tests/certify/test_facet_table.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <span>
#include <system_error>
#include <thread>
#include <vector>
#ifdef __linux__
#include <sched.h>
#endif

#include "dewall/certify/face_grouping.hpp"
#include "dewall/certify/report.hpp"
#include "dewall/certify/witness_point.hpp"
#include "dewall/kernel/concepts.hpp"
#include "dewall/kernel/first_occurrence.hpp"
#include "dewall/kernel/floating_point.hpp"

namespace dewall::test {

using certify::Options;
using certify::Report;
using certify::Rule;
using certify::Violation;

template <kernel::DelaunayKernel K>
class Certifier_reference {
 public:
  static constexpr int D = K::dimension;
  using Point = typename K::Point_d;
  using Cell = std::array<std::uint32_t, D + 1>;
  using Cell_points = std::array<const Point*, D + 1>;

  Certifier_reference(const K& k, std::span<const Point> points, std::span<const Cell> rows, const Options& options)
      : k_(k), points_(points), rows_(rows), options_(options), orientation_(k.orientation_d_object()) {}

  Report run() {
    report_.dimension = D;
    report_.points = points_.size();
    report_.simplices = rows_.size();
    check_points();
    if (!stop()) check_simplices();
    if (!stop()) check_vertices();
    if (!stop()) check_facets();
    if (!stop() && !cells_.empty()) check_boundary();
    if (!stop() && !cells_.empty()) check_covering();
    // Structural violations first, then the Delaunay ones, then notes.
    auto& v = report_.violations;
    v = std::move(fatal_);
    if (options_.all || v.empty()) v.insert(v.end(), delaunay_.begin(), delaunay_.end());
    report_.delaunay = v.empty();
    report_.canonical = report_.delaunay && notes_.empty();
    v.insert(v.end(), notes_.begin(), notes_.end());
    return report_;
  }

 private:
  bool stop() const { return !options_.all && !fatal_.empty(); }
  void fail(Violation v) {
    if (!stop()) fatal_.push_back(std::move(v));
  }

  Cell_points at(const Cell& c) const {
    Cell_points p;
    for (std::size_t i = 0; i <= D; ++i) p[i] = &points_[c[i]];
    return p;
  }
  std::vector<std::uint32_t> facet_of(const Cell& c, int skip) const {
    std::vector<std::uint32_t> f;
    for (int i = 0; i <= D; ++i)
      if (i != skip) f.push_back(c[static_cast<std::size_t>(i)]);
    std::sort(f.begin(), f.end());
    return f;
  }
  /// orientation of `cell` with its vertex at position i replaced by point q.
  kernel::Sign replaced(const Cell& cell, int i, std::uint32_t q) const {
    Cell_points p = at(cell);
    p[static_cast<std::size_t>(i)] = &points_[q];
    return orientation_(p);
  }

  /// Non-finite coordinates (when the kernel's points are doubles), then the
  /// first occurrence of every point: hashed, decided by the exact lexicographic order.
  void check_points() {
    const std::size_t n = points_.size();
    bad_point_.assign(n, false);
    if constexpr (kernel::approximate_coordinates_are_exact<K>) {
      const auto coords = k_.approximate_coordinates_object();
      for (std::size_t i = 0; i < n; ++i) {
        const auto& x = coords(points_[i]);
        for (double c : x)
          if (!kernel::is_finite(c)) bad_point_[i] = true;
        if (bad_point_[i]) fail({.rule = Rule::non_finite_point, .point = i});
      }
    }
    first_ = kernel::first_occurrences(points_, k_.compare_lexicographically_d_object(),
                                       k_.approximate_coordinates_object(), [&](std::size_t i) { return bool(bad_point_[i]); });
    for (std::size_t i = 0; i < n; ++i)
      if (!bad_point_[i] && first_[i] == i) ++report_.distinct_points;
  }

  /// Indices, repeated vertices, later duplicates, degeneracy; orient
  /// positively. Ranges of rows on all cores (one orientation test each),
  /// merged in order as far as the serial walk would have gone.
  void check_simplices() {
    struct Results {
      std::vector<Cell> cells;
      std::vector<std::size_t> rows;
      std::vector<Violation> fatal;
    };
    const std::size_t m = rows_.size();
    const std::size_t ranges = std::clamp<std::size_t>(m / 16384, 1, 256);
    std::vector<Results> results(ranges);
    for_each_parallel(ranges, [&](std::size_t k) {
      Results& out = results[k];
      for (std::size_t r = m * k / ranges; r < m * (k + 1) / ranges && (options_.all || out.fatal.empty()); ++r)
        if (const auto c = checked_simplex(r, out.fatal)) {
          out.cells.push_back(*c);
          out.rows.push_back(r);
        }
    });
    used_.assign(points_.size(), false);
    for (Results& res : results) {
      if (stop()) break;
      for (Violation& v : res.fatal) fail(std::move(v));
      for (std::size_t i = 0; i < res.cells.size(); ++i) {
        for (std::uint32_t v : res.cells[i]) used_[v] = true;  // a vertex of a proper simplex only
        cells_.push_back(res.cells[i]);
        cell_row_.push_back(res.rows[i]);
      }
    }
  }

  /// Row r positively oriented, or nothing (its violations appended to `fatal`).
  std::optional<Cell> checked_simplex(std::size_t r, std::vector<Violation>& fatal) const {
    const std::size_t n = points_.size();
    Cell c = rows_[r];
    bool ok = true;
    for (std::uint32_t v : c)
      if (v >= n) {
        fatal.push_back({.rule = Rule::index_out_of_range, .simplex = r, .point = v});
        ok = false;
      }
    if (!ok) return std::nullopt;
    Cell sorted = c;
    std::sort(sorted.begin(), sorted.end());
    if (const auto dup = std::adjacent_find(sorted.begin(), sorted.end()); dup != sorted.end()) {
      fatal.push_back({.rule = Rule::repeated_vertex, .simplex = r, .point = *dup});
      return std::nullopt;
    }
    for (std::uint32_t v : c) {
      if (bad_point_[v]) ok = false;  // reported with the point
      else if (first_[v] != v) {
        fatal.push_back({.rule = Rule::duplicate_point_used, .simplex = r, .point = v});
        ok = false;
      }
    }
    if (!ok) return std::nullopt;
    const kernel::Sign s = orientation_(at(c));
    if (s == kernel::ZERO) {
      fatal.push_back({.rule = Rule::degenerate_simplex, .simplex = r});
      return std::nullopt;
    }
    if (s == kernel::NEGATIVE) std::swap(c[0], c[1]);
    return c;
  }


  void check_vertices() {
    for (std::size_t i = 0; i < points_.size() && !stop(); ++i)
      if (!bad_point_[i] && first_[i] == i && !used_[i]) fail({.rule = Rule::point_not_a_vertex, .point = i});
  }

  /// What the facet checks of a range of buckets found, in bucket order.
  struct Facet_results {
    std::vector<certify::detail::Face_ref> boundary;
    std::vector<Violation> fatal, delaunay, notes;
    std::size_t interior_facets = 0, cospherical_facets = 0;
  };

  /// Facet matching, opposite sides, and the local Delaunay tests. The facets
  /// are filed by smallest vertex, and ranges of those buckets are checked on
  /// all cores (most of the certifier's time; docs/engines.md). The ranges
  /// are fixed by the number of points
  /// and merged in order, each as far as the serial walk would have gone (it
  /// stops at the first fatal violation, and tests no sphere after the first
  /// Delaunay one), so the report is the same for any number of threads.
  void check_facets() {
    const certify::detail::Face_buckets<D + 1> buckets(points_.size(), std::span<const Cell>(cells_));
    const std::size_t n = points_.size();
    const std::size_t ranges = std::clamp<std::size_t>(n / 4096, 1, 256);
    std::vector<Facet_results> results(ranges);
    for_each_parallel(ranges, [&](std::size_t r) {
      buckets.for_buckets(n * r / ranges, n * (r + 1) / ranges,
                          [&](std::span<const certify::detail::Face_ref> g) { check_facet_group(g, results[r]); });
    });
    for (Facet_results& r : results) {
      if (stop()) break;
      boundary_.insert(boundary_.end(), r.boundary.begin(), r.boundary.end());
      report_.interior_facets += r.interior_facets;
      for (Violation& v : r.fatal) fail(std::move(v));
      if (!options_.all && !delaunay_.empty()) continue;  // the serial walk tested no more spheres
      report_.cospherical_facets += r.cospherical_facets;
      delaunay_.insert(delaunay_.end(), r.delaunay.begin(), r.delaunay.end());
      for (Violation& v : r.notes)
        if (options_.all || notes_.empty()) notes_.push_back(std::move(v));
    }
  }

  /// The checks of one facet's group (its simplices), into `out`.
  void check_facet_group(std::span<const certify::detail::Face_ref> g, Facet_results& out) const {
    if (!options_.all && !out.fatal.empty()) return;
    const Cell& c1 = cells_[g[0].row];
    const int i1 = g[0].position;
    if (g.size() == 1) {
      out.boundary.push_back({g[0].row, i1});
      return;
    }
    if (g.size() > 2) {
      out.fatal.push_back({.rule = Rule::facet_shared_by_many, .simplex = cell_row_[g[0].row],
                           .other_simplex = cell_row_[g[1].row], .face = facet_of(c1, i1)});
      return;
    }
    const Cell& c2 = cells_[g[1].row];
    const std::uint32_t a = c1[static_cast<std::size_t>(i1)], b = c2[static_cast<std::size_t>(g[1].position)];
    if (a == b) {
      out.fatal.push_back({.rule = Rule::duplicate_simplex, .simplex = cell_row_[g[0].row], .other_simplex = cell_row_[g[1].row]});
      return;
    }
    // c1 is positive, so a is on the positive side of the facet: b must be on the negative one.
    if (replaced(c1, i1, b) != kernel::NEGATIVE) {
      out.fatal.push_back({.rule = Rule::facet_same_side, .simplex = cell_row_[g[0].row],
                           .other_simplex = cell_row_[g[1].row], .face = facet_of(c1, i1)});
      return;
    }
    ++out.interior_facets;
    if (!options_.all && !out.delaunay.empty()) return;  // one witness is enough
    std::array<const Point*, D + 2> s;
    const Cell_points p = at(c1);
    std::copy(p.begin(), p.end(), s.begin());
    s[D + 1] = &points_[b];
    const kernel::Oriented_side side = k_.side_of_oriented_sphere_unperturbed_d_object()(s);
    const auto witness = [&](Rule rule) {
      return Violation{.rule = rule, .simplex = cell_row_[g[0].row], .other_simplex = cell_row_[g[1].row],
                       .face = facet_of(c1, i1), .point = b};
    };
    if (side == kernel::ON_POSITIVE_SIDE) {
      out.delaunay.push_back(witness(Rule::not_locally_delaunay));
    } else if (side == kernel::ON_ORIENTED_BOUNDARY) {
      ++out.cospherical_facets;
      if (k_.side_of_oriented_sphere_d_object()(s) == kernel::ON_POSITIVE_SIDE && (options_.all || out.notes.empty()))
        out.notes.push_back(witness(Rule::not_canonical));
    }
  }

  /// The cores this process may run on: its affinity mask (taskset, a
  /// container's cpuset), which hardware_concurrency ignores.
  static unsigned available_cores() {
#ifdef __linux__
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
#endif
    return std::max(1u, std::thread::hardware_concurrency());
  }

  /// Calls f(0) … f(count − 1), on up to Options::threads threads (0: all
  /// cores), then rethrows the exception of the first call that threw (out
  /// of memory, say). Each worker sets the floating-point environment the
  /// kernel's filters assume (floating_point.hpp).
  template <class F>
  void for_each_parallel(std::size_t count, F&& f) const {
    unsigned threads = options_.threads ? options_.threads : available_cores();
    threads = static_cast<unsigned>(std::min<std::size_t>(threads, count));
    std::vector<std::exception_ptr> errors(count);
    std::atomic<std::size_t> next{0};
    auto work = [&] {
      const kernel::Fp_environment_guard guard;
      for (std::size_t i; (i = next.fetch_add(1)) < count;) {
        try {
          f(i);
        } catch (...) {
          errors[i] = std::current_exception();
        }
      }
    };
    std::vector<std::thread> pool;
    try {
      for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    } catch (const std::system_error&) {
      // No more threads to be had: those started and this one do the work.
    }
    work();
    for (auto& t : pool) t.join();
    for (const auto& e : errors)
      if (e) std::rethrow_exception(e);
  }

  /// The boundary: a closed surface (every ridge in two boundary facets),
  /// locally convex at every ridge, facing away from the witness point.
  void check_boundary() {
    report_.boundary_facets = boundary_.size();
    // Boundary facets as rows of D vertices, in their cell's order.
    std::vector<std::array<std::uint32_t, D>> facets(boundary_.size());
    for (std::size_t b = 0; b < boundary_.size(); ++b)
      for (int j = 0, t = 0; j <= D; ++j)
        if (j != boundary_[b].position)
          facets[b][static_cast<std::size_t>(t++)] = cells_[boundary_[b].row][static_cast<std::size_t>(j)];
    const auto cell_position = [&](std::size_t b, int j) { return j < boundary_[b].position ? j : j + 1; };
    certify::detail::group_faces<D>(points_.size(), std::span<const std::array<std::uint32_t, D>>(facets),
                   [&](std::span<const certify::detail::Face_ref> g) {
                     if (stop()) return;
                     const certify::detail::Face_ref f1 = g[0];
                     const Cell& c1 = cells_[boundary_[f1.row].row];
                     if (g.size() != 2) {
                       std::vector<std::uint32_t> ridge = facet_of(c1, boundary_[f1.row].position);
                       ridge.erase(std::find(ridge.begin(), ridge.end(), facets[f1.row][static_cast<std::size_t>(f1.position)]));
                       fail({.rule = Rule::boundary_ridge_not_manifold, .simplex = cell_row_[boundary_[f1.row].row],
                             .face = ridge});
                       return;
                     }
                     for (int t = 0; t < 2; ++t) {
                       const certify::detail::Face_ref f = g[static_cast<std::size_t>(t)], o = g[static_cast<std::size_t>(1 - t)];
                       const Cell& cf = cells_[boundary_[f.row].row];
                       const std::uint32_t far = facets[o.row][static_cast<std::size_t>(o.position)];
                       // cf is positive: its inner side is the side of its vertex opposite the facet.
                       if (replaced(cf, boundary_[f.row].position, far) == kernel::NEGATIVE) {
                         std::vector<std::uint32_t> ridge = facet_of(cf, boundary_[f.row].position);
                         ridge.erase(std::find(ridge.begin(), ridge.end(),
                                               cf[static_cast<std::size_t>(cell_position(f.row, f.position))]));
                         fail({.rule = Rule::boundary_not_convex, .simplex = cell_row_[boundary_[f.row].row],
                               .other_simplex = cell_row_[boundary_[o.row].row], .face = ridge, .point = far});
                         return;
                       }
                     }
                   });
    const certify::detail::Witness_point<K> o(k_, at(cells_[0]));
    for (const auto& b : boundary_) {
      if (stop()) return;
      if (o.side_of_facet(at(cells_[b.row]), b.position) != kernel::POSITIVE)
        fail({.rule = Rule::boundary_facet_inward, .simplex = cell_row_[b.row], .other_simplex = cell_row_[0],
              .face = facet_of(cells_[b.row], b.position)});
    }
  }

  /// The global test: no simplex but cells_[0] contains the witness point.
  void check_covering() {
    const certify::detail::Witness_point<K> o(k_, at(cells_[0]));
    for (std::size_t t = 1; t < cells_.size() && !stop(); ++t) {
      if constexpr (kernel::approximate_coordinates_are_exact<K>) {
        // o is infinitesimally close to its anchor, an input point: a cell whose
        // bounding box (exact: the coordinates are the points) misses the anchor
        // cannot contain o.
        const auto coords = k_.approximate_coordinates_object();
        const auto& x = coords(o.anchor());
        bool outside = false;
        for (int j = 0; j < D && !outside; ++j) {
          bool below = true, above = true;
          for (std::uint32_t v : cells_[t]) {
            const double c = coords(points_[v])[static_cast<std::size_t>(j)];
            below = below && x[static_cast<std::size_t>(j)] < c;
            above = above && x[static_cast<std::size_t>(j)] > c;
          }
          outside = below || above;
        }
        if (outside) continue;
      }
      if (o.inside(at(cells_[t])))
        fail({.rule = Rule::multiple_covering, .simplex = cell_row_[t], .other_simplex = cell_row_[0],
              .point = cells_[0][0]});
    }
  }

  const K& k_;
  std::span<const Point> points_;
  std::span<const Cell> rows_;
  Options options_;
  decltype(std::declval<const K&>().orientation_d_object()) orientation_;
  Report report_;
  std::vector<Violation> fatal_, delaunay_, notes_;
  std::vector<bool> bad_point_, used_;
  std::vector<std::uint32_t> first_;
  std::vector<Cell> cells_;            // valid simplices, positively oriented
  std::vector<std::size_t> cell_row_;  // their rows in the input
  std::vector<certify::detail::Face_ref> boundary_;     // facets of one cell: (cell, opposite position)
};

/// The reference report of `simplices` against `points`.
template <kernel::DelaunayKernel K>
Report certify_reference(std::span<const typename K::Point_d> points,
                         std::span<const std::array<std::uint32_t, K::dimension + 1>> simplices, const Options& options = {},
                         const K& k = {}) {
  const kernel::Fp_environment_guard guard;
  return Certifier_reference<K>(k, points, simplices, options).run();
}

}  // namespace dewall::test
