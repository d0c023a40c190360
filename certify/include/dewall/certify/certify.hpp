// certify: does a list of simplices form a Delaunay triangulation of a point
// set — and is it *the* canonical one, the symbolically perturbed triangulation
// that CGAL and dewall build?
//
// Independent of the triangulator: it uses the DelaunayKernel's exact
// predicates (orientation, the perturbed sphere test, the lexicographic order)
// and the kernel library's exact unperturbed sphere test, nothing from dewall/.
// Every decision is the sign of an exact determinant; doubles are only ever
// compared when they are the input coordinates themselves.
//
// The checks follow the program-checking approach of K. Mehlhorn, S. Näher,
// M. Seel, R. Seidel, T. Schilz, S. Schirra, C. Uhrig, "Checking geometric
// programs or verification of geometric structures", CGTA 12 (1999) 85–103,
// and O. Devillers, G. Liotta, F. P. Preparata, R. Tamassia, "Checking the
// convexity of polytopes and the planarity of subdivisions", CGTA 11 (1998)
// 187–208: local conditions, each cheap, plus one global test that rules out
// the configurations local tests cannot see (a surface wound twice around).
//
// Why these checks suffice. Orient every simplex positively (input rows may
// come in either orientation). Let C be the chain of these simplices and, for
// a point x on no facet, deg(x) the number of simplices containing x.
//  1. Every facet is in at most two simplices, and the two lie on opposite
//     sides: crossing such an interior facet leaves one simplex and enters
//     another, so deg is constant off the boundary B (facets in one simplex;
//     ridges have codimension 2 and do not separate), and ∂C = B, with each
//     boundary facet oriented away from its simplex.
//  2. The witness point o (witness_point.hpp) lies strictly inside simplex 0
//     and in no other simplex: deg(o) = 1. It is strictly on the inner side of
//     every boundary facet, so a ray from o crosses B only outwards, and the
//     number of crossings equals the winding number of ∂C around o, deg(o) = 1:
//     B is star-shaped around o — Mehlhorn et al.'s ray condition.
//  3. Each boundary ridge lies in exactly two boundary facets, and neither
//     facet's far vertex lies strictly outside the other's hyperplane: B is a
//     closed, locally (weakly) convex surface. With 2, it bounds a convex
//     polytope Q (Mehlhorn et al., Devillers et al.), deg = 1 in Q and 0
//     outside: the simplices tile Q, face to face (an improper contact would
//     leave an unmatched facet inside Q or cover some point twice).
//  4. Every point is a vertex unless it duplicates an earlier point, whose
//     first occurrence must be the vertex (CGAL's and dewall's convention):
//     the vertices are the distinct points, so Q = conv(points) and no input
//     point lies outside B.
//  5. Every interior facet is locally Delaunay: the far vertex of one simplex
//     is not strictly inside the circumsphere of the other (unperturbed, exact).
//     The lifted triangulation is then locally convex at every interior facet,
//     hence convex (Delaunay's lemma): no point is inside any circumsphere.
//     With the perturbed predicate the same argument shows the triangulation
//     is the Delaunay triangulation of the perturbed points, which is unique:
//     the canonical one. A facet that passes 5 only unperturbed is cospherical
//     and flipped against the perturbation: Delaunay, not canonical.
//
// Cost: O(n) expected to find duplicates (hashing) and to renumber the points
// along a Z-order curve (spatial_order.hpp: the certifier's own numbering, so
// that the points and facets of neighbouring simplices sit side by side in
// memory), one orientation test per simplex and one sphere test per interior
// facet, and O(m·(D+1)) facet records filed by a counting sort on the smallest
// vertex (facet_table.hpp), for n points and m simplices. Memory: a copy of the
// points, the rows (4(D+1) bytes each; streaming: in temporary files, bucketed
// by vertex ranges, row_buckets.hpp), and the facet records of one window of
// vertices at a time. The reports name the input's numbers and follow the
// serial walk in them (rows in order, then facets in order of their sorted
// vertices); the work in the certifier's numbering collects what it finds and
// sorts it into that order, and when a first violation of a facet must be
// found without Options::all it walks the facets again in the input's numbers.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>
#ifdef __linux__
#include <sched.h>
#endif

#include "dewall/certify/face_grouping.hpp"
#include "dewall/certify/facet_table.hpp"
#include "dewall/certify/report.hpp"
#include "dewall/certify/row_buckets.hpp"
#include "dewall/certify/share_screen.hpp"
#include "dewall/certify/simplex_source.hpp"
#include "dewall/certify/spatial_order.hpp"
#include "dewall/certify/uninitialized.hpp"
#include "dewall/certify/witness_point.hpp"
#include "dewall/kernel/concepts.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"
#include "dewall/kernel/first_occurrence.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/static_filter.hpp"

namespace dewall::certify {

/// One share of a certification (certify_share): `part` of `parts`. A share
/// checks the facets whose smallest vertex, in the certifier's numbering of the
/// points (the same for every share), lies in the part's range of vertices,
/// the rows whose smallest vertex lies there (a row with an index out of range:
/// row r in part r mod parts), and the points there; merge_shares makes one
/// report of all parts.
struct Share {
  std::size_t part = 0, parts = 1;
};

/// A facet of one simplex: its vertices (input numbers, increasing), the apex
/// of its simplex, whether (facet…, apex) is positively oriented, and the
/// simplex's row.
template <int D>
struct Boundary_facet {
  std::array<std::uint32_t, D> facet;
  std::uint32_t apex;
  bool positive;
  std::size_t row;
};

/// What one share found, for merge_shares: its violations (fatal ones,
/// Delaunay ones and notes, each list in the certifier's order, the facets of
/// duplicate_simplex kept as sort keys), its counts, and its boundary facets
/// (in facet order), which the boundary checks need all together.
template <int D>
struct Share_report {
  Report report;
  std::vector<Boundary_facet<D>> boundary;
  std::size_t first_row = npos;     // the first proper simplex (the same in every share)
  Simplex_indices<D> first_cell{};  // its vertices, positively oriented
  /// How it was made, for merge_shares to check that the shares fit: which
  /// share, of how many points, and whether its ranges of vertices are in
  /// the input's numbering (streaming, or Options::spatial_order off) or in
  /// the certifier's Z order.
  Share share{};
  std::size_t point_count = 0;
  bool input_numbering = false;
};

}  // namespace dewall::certify

namespace dewall::certify::detail {

/// certify() with the project's kernel, compiled into dewall::certify with the
/// project's flags (certify/src/certify_filtered.cpp), D = 2 … 6.
template <int D>
Report certify_filtered(std::span<const kernel::Point_d<D>> points, Simplex_source<D>& simplices, const Options& options);
template <int D>
Share_report<D> certify_share_filtered(std::span<const kernel::Point_d<D>> points, Simplex_source<D>& simplices, Share share,
                                       const Options& options);
template <int D>
Report merge_shares_filtered(std::span<const kernel::Point_d<D>> points, std::span<const Share_report<D>> shares,
                             const Options& options);

template <class>
inline constexpr bool always_false = false;

}  // namespace dewall::certify::detail

#ifndef DEWALL_UNSAFE_FP_FLAGS
DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::certify::detail {

template <kernel::DelaunayKernel K>
class Certifier {
 public:
  static constexpr int D = K::dimension;
  using Point = typename K::Point_d;
  using Cell = std::array<std::uint32_t, D + 1>;
  using Cell_points = std::array<const Point*, D + 1>;

  Certifier(const K& k, std::span<const Point> points, const Options& options)
      : k_(k), points_(points), work_(points), options_(options), orientation_(k.orientation_d_object()) {}

  Report run(Simplex_source<D>& source) {
    report_.dimension = D;
    report_.points = points_.size();
    const auto bound = [&](std::size_t p) {
      __extension__ using U128 = unsigned __int128;
      return static_cast<std::size_t>(U128{points_.size()} * p / share_.parts);
    };
    lo_ = bound(share_.part);
    hi_ = bound(share_.part + 1);
    check_points();
    make_static_filter();
    if (!stop() && options_.spatial_order && !options_.stream) renumber();
    decltype(z_sorted_)().swap(z_sorted_);  // renumber's (also when it did not run)
    read_rows(source);
    if (!stop()) check_vertices();
    std::vector<bool>().swap(duplicate_);
    // A share keeps the map: a walk in the input's numbers picks its facets by it.
    if (!sharing_) std::vector<std::uint32_t>().swap(to_work_);
    if (!stop() && first_row_ != npos) check_facets();
    if (!stop() && first_row_ != npos) {
      if (sharing_) report_.boundary_facets = boundary_.size();  // checked once all shares are in
      else check_boundary();
    }
    if (!stop() && first_row_ != npos) check_covering();
    // Structural violations first, then the Delaunay ones, then notes.
    auto& v = report_.violations;
    v = std::move(fatal_);
    if (options_.all || v.empty() || sharing_) v.insert(v.end(), delaunay_.begin(), delaunay_.end());
    report_.delaunay = v.empty();
    report_.canonical = report_.delaunay && notes_.empty();
    v.insert(v.end(), notes_.begin(), notes_.end());
    return report_;
  }

  /// run() for one share (Share says which); \pre share.part < share.parts.
  Share_report<D> run_share(Simplex_source<D>& source, Share share) {
    sharing_ = true;
    share_ = share;
    Report r = run(source);
    return {std::move(r), std::move(boundary_), first_row_, first_cell_, share, points_.size(),
            options_.stream || !options_.spatial_order};
  }

  /// The report of the whole from the reports of all its shares (any order):
  /// the violations in the certifier's order (Violation_order), the boundary
  /// checked as run() checks it, and, without Options::all, what the serial
  /// walk would have kept.
  Report merge_shares(std::span<const Share_report<D>> shares) {
    Report out;
    out.dimension = D;
    out.points = points_.size();
    std::vector<Violation> fatal, delaunay, notes;
    for (const Share_report<D>& s : shares) {
      out.distinct_points = s.report.distinct_points;
      out.simplices = s.report.simplices;
      out.interior_facets += s.report.interior_facets;
      out.boundary_facets += s.report.boundary_facets;
      out.cospherical_facets += s.report.cospherical_facets;
      for (const Violation& v : s.report.violations)
        (v.rule == Rule::not_locally_delaunay ? delaunay : v.rule == Rule::not_canonical ? notes : fatal).push_back(v);
      if (s.first_row != npos) first_row_ = s.first_row, first_cell_ = s.first_cell;
    }
    const auto sort = [](std::vector<Violation>& list) { std::stable_sort(list.begin(), list.end(), violation_before); };
    sort(fatal);
    // The boundary is checked when the serial walk gets there: every check
    // before it passed (a share that stopped earlier has not handed over all of
    // its boundary, and its violation comes first).
    if (first_row_ != npos && (options_.all || fatal.empty() || violation_phase(fatal[0].rule) > facet_phase)) {
      for (const Share_report<D>& s : shares) boundary_.insert(boundary_.end(), s.boundary.begin(), s.boundary.end());
      std::sort(boundary_.begin(), boundary_.end(), [](const Boundary_facet& a, const Boundary_facet& b) { return a.facet < b.facet; });
      check_boundary();
      fatal.insert(fatal.end(), fatal_.begin(), fatal_.end());
      sort(fatal);
    }
    sort(delaunay);
    sort(notes);
    if (!options_.all) {
      // The serial walk: one fatal violation; the spheres tested up to the
      // first Delaunay one, the facets walked up to a facet's fatal one, and
      // none at all after a row's or a point's.
      if (fatal.size() > 1) fatal.resize(1);
      if (delaunay.size() > 1) delaunay.resize(1);
      const auto note_seen = [&](const Violation& n) {
        if (!fatal.empty() && violation_phase(fatal[0].rule) < facet_phase) return false;
        if (!fatal.empty() && violation_phase(fatal[0].rule) == facet_phase && !(n.face < fatal[0].face)) return false;
        return delaunay.empty() || n.face < delaunay[0].face;
      };
      if (!notes.empty() && !note_seen(notes[0])) notes.clear();
      if (notes.size() > 1) notes.resize(1);
    }
    for (Violation& v : fatal)
      if (v.rule == Rule::duplicate_simplex) v.face.clear();
    auto& v = out.violations;
    v = std::move(fatal);
    if (options_.all || v.empty()) v.insert(v.end(), delaunay.begin(), delaunay.end());
    out.delaunay = v.empty();
    out.canonical = out.delaunay && notes.empty();
    v.insert(v.end(), notes.begin(), notes.end());
    return out;
  }

 private:
  /// A boundary facet (in the certifier's numbers while the facets are walked).
  using Boundary_facet = certify::Boundary_facet<D>;

  /// The checks in the order of the reports: points, rows, unused points,
  /// facets, boundary, covering, then the Delaunay ones and notes.
  static constexpr int facet_phase = 3;
  static int violation_phase(Rule r) {
    switch (r) {
      case Rule::non_finite_point: return 0;
      case Rule::index_out_of_range:
      case Rule::repeated_vertex:
      case Rule::duplicate_point_used:
      case Rule::degenerate_simplex: return 1;
      case Rule::point_not_a_vertex: return 2;
      case Rule::facet_shared_by_many:
      case Rule::duplicate_simplex:
      case Rule::facet_same_side: return facet_phase;
      case Rule::boundary_ridge_not_manifold:
      case Rule::boundary_not_convex:
      case Rule::boundary_facet_inward: return 4;
      case Rule::multiple_covering: return 5;
      case Rule::not_locally_delaunay: return 6;
      case Rule::not_canonical: return 7;
    }
    return 8;
  }
  /// Whether a comes before b in a report (a strict weak order: a row's own
  /// violations, and the boundary's, are equal, and keep their order).
  static bool violation_before(const Violation& a, const Violation& b) {
    const int pa = violation_phase(a.rule), pb = violation_phase(b.rule);
    if (pa != pb) return pa < pb;
    switch (pa) {
      case 0:
      case 2: return a.point < b.point;
      case 1:
      case 5: return a.simplex < b.simplex;
      case 4: return false;
      default: return a.face < b.face;
    }
  }

  /// Whether this share reports on point i (input number): non-finite points by
  /// input number, the others by the certifier's.
  bool owns_bad_point(std::size_t i) const { return !sharing_ || i % share_.parts == share_.part; }
  bool owns_vertex(std::uint32_t w) const { return lo_ <= w && w < hi_; }
  /// Whether row r (input numbers) matters to this share (a vertex in its
  /// range), and whether the share reports its checks (its smallest vertex
  /// there; an index out of range: r mod parts).
  std::pair<bool, bool> share_of_row(const Cell& c, std::size_t r) const {
    if (!sharing_) return {true, true};
    bool any = false;
    for (std::uint32_t v : c) {
      if (v >= points_.size()) {
        const bool own = r % share_.parts == share_.part;
        return {own, own};
      }
      any = any || mine_.contains(v);
    }
    if (!any) return {false, false};
    std::uint32_t smallest = std::numeric_limits<std::uint32_t>::max();
    for (std::uint32_t v : c) smallest = std::min(smallest, work_number(v));
    return {true, owns_vertex(smallest)};
  }
  /// Whether the facet (smallest vertex v, the others `rest`, in the numbers of
  /// the walk) is this share's: its smallest vertex in the certifier's numbers is.
  template <class Rest>
  bool facet_in_share(std::uint32_t v, const Rest& rest) const {
    if (!sharing_) return true;
    std::uint32_t w = v;
    if (!renumbered() && !to_work_.empty()) {  // the walk in the input's numbers
      w = to_work_[v];
      for (std::uint32_t u : rest) w = std::min(w, to_work_[u]);
    }
    return owns_vertex(w);
  }
  /// A proper row in the certifier's numbers: its vertices in increasing
  /// order, and whether that order is positively oriented.
  struct Checked_row {
    Cell sorted;
    bool positive;
  };
  using Bucket_entry = typename Row_buckets<D + 1>::Entry;

  /// Rows read, then checked on all cores, at a time: enough for each
  /// parallel section to last tens of milliseconds, so that a thread woken on
  /// a core busy with other work still gets its share.
  static constexpr std::size_t block_rows = std::size_t{1} << 20;

  bool stop() const { return !options_.all && !fatal_.empty(); }
  void fail(Violation v) {
    if (!stop()) fatal_.push_back(std::move(v));
  }

  /// The certifier's number of input point v, and back.
  std::uint32_t work_number(std::uint32_t v) const { return to_work_.empty() ? v : to_work_[v]; }
  std::uint32_t input_number(std::uint32_t v) const { return to_input_.empty() ? v : to_input_[v]; }
  bool renumbered() const { return !to_input_.empty(); }

  Cell_points at(std::span<const Point> points, const Cell& c) const {
    Cell_points p;
    for (std::size_t i = 0; i <= D; ++i) p[i] = &points[c[i]];
    return p;
  }
  /// The points of a facet and an apex, positively oriented: (facet…, apex),
  /// with the first two swapped when that order is negative.
  static Cell_points oriented(std::span<const Point> points, std::span<const std::uint32_t> facet, std::uint32_t apex,
                              bool positive) {
    Cell_points p;
    for (std::size_t i = 0; i < D; ++i) p[i] = &points[facet[i]];
    p[D] = &points[apex];
    if (!positive) std::swap(p[0], p[1]);
    return p;
  }
  /// Asks for point v's cache lines (a point may straddle two).
  void prefetch(std::uint32_t v) const {
    const char* p = reinterpret_cast<const char*>(&work_[v]);
    __builtin_prefetch(p);
    __builtin_prefetch(p + sizeof(Point) - 1);
  }
  static std::vector<std::uint32_t> without(std::span<const std::uint32_t> sorted, std::uint32_t skip) {
    std::vector<std::uint32_t> f;
    for (std::uint32_t v : sorted)
      if (v != skip) f.push_back(v);
    return f;
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
        if (bad_point_[i] && owns_bad_point(i)) fail({.rule = Rule::non_finite_point, .point = i});
      }
    }
    const auto excluded = [&](std::size_t i) { return bool(bad_point_[i]); };
    std::vector<std::uint32_t> first;
    if (options_.spatial_order && !options_.stream && n >= 2) {
      // The Z order (renumber's) puts equal points in one cell: they are
      // compared there, without a table of all points.
      z_sorted_ = z_order_keys<D>(points_, k_.approximate_coordinates_object(), [&](std::size_t i) { return !bad_point_[i]; },
                                  loop(), 4 * threads_for(n));
      first = first_occurrences_in_z_order(points_, std::span<const std::uint64_t>(z_sorted_), k_.compare_lexicographically_d_object(), excluded);
    } else {
      // Streaming, the duplicates' table stays within the working memory too.
      first = kernel::first_occurrences(points_, k_.compare_lexicographically_d_object(), k_.approximate_coordinates_object(),
                                        excluded, options_.stream ? stream_budget() : 0, loop(), threads_for(n));
    }
    // Only whether a point repeats an earlier one is asked later: a bit each.
    duplicate_.assign(n, false);
    for (std::size_t i = 0; i < n; ++i) {
      duplicate_[i] = first[i] != i;
      if (!bad_point_[i] && !duplicate_[i]) ++report_.distinct_points;
    }
  }

  /// The certifier's numbering: along a Z-order curve, the points copied in it.
  void renumber() {
    const std::size_t n = points_.size();
    if (n < 2) return;
    to_input_.resize(n);
    to_work_.resize(n);
    work_points_.resize(n);
    const std::size_t parts = std::clamp<std::size_t>(n / 65536, 1, 4 * threads_for(n));
    for_each_parallel(parts, [&](std::size_t k) {
      for (std::size_t i = n * k / parts; i < n * (k + 1) / parts; ++i) {
        const auto v = static_cast<std::uint32_t>(z_sorted_[i]);  // the index in the key's low half
        to_input_[i] = v;
        to_work_[v] = static_cast<std::uint32_t>(i);
        work_points_[i] = points_[v];
      }
    });
    work_ = work_points_;
  }

  /// Reads the rows a block at a time and checks each (indices, repeated
  /// vertices, later duplicates, degeneracy: one orientation test) on all
  /// cores, merged in order as far as the serial walk would have gone. The same
  /// pass stores each proper row in the certifier's numbers (encode_row: in
  /// memory, or in the bucket files when streaming), counts its facets by
  /// smallest vertex, marks its vertices used, and collects the rows that
  /// contain the witness point (the covering test, reported in its turn).
  void read_rows(Simplex_source<D>& source) {
    const std::size_t n = points_.size();
    const std::size_t rows_left = source.remaining();
    std::vector<Cell> block(rows_left == npos ? block_rows : std::clamp<std::size_t>(rows_left, 1, block_rows)), encoded;
    if (!stop()) {
      used_.assign(n, 0);
      usable_.assign(n, 0);
      for (std::size_t i = 0; i < n; ++i)
        if (!bad_point_[i] && !duplicate_[i]) usable_[work_number(static_cast<std::uint32_t>(i))] = 1;
      if (options_.stream) {
        facet_count_.assign(n, 0);
        // Ranges of vertices whose files hold about a quarter of a window each,
        // assuming (D + 1)(D + 3) facets per point (a little more than uniform
        // points have); a larger file is read once per window it spans.
        const double records = double(n) * (D + 1) * (D + 3) * 4 * sizeof(Facet_record<D, std::uint64_t>);
        const auto files = static_cast<std::size_t>(
            std::clamp(records / double(stream_budget()), 1.0, std::clamp(double(n) / 64, 1.0, 512.0)));
        buckets_.emplace(n, files, options_.temp_directory, std::max<std::size_t>(64, (1 << 16) / sizeof(Bucket_entry)));
        encoded.resize(block.size());
      } else if (compact()) {
        encoded.resize(block.size());  // the share's rows are then kept, with their numbers
        // Its part of the rows, and a little for those that cross into other parts.
        if (const std::size_t m = source.remaining(); m != npos) {
          const std::size_t expected = std::min(m, m / share_.parts + m / 16);
          rows_.reserve(expected);
          row_of_.reserve(expected);
        }
      } else if (const std::size_t m = source.remaining(); m != npos) {
        rows_.reserve(m);
      }
      if (sharing_) {
        mine_ = Vertex_set(n);
        for (std::size_t i = 0; i < n; ++i)
          if (owns_vertex(work_number(static_cast<std::uint32_t>(i)))) mine_.insert(i);
      }
    }
    std::optional<Witness_point<K>> witness;
    std::size_t r0 = 0;
    for (std::size_t k; (k = source.read(block)) > 0; r0 += k) {
      if (stop()) continue;  // the serial walk stopped: the rest is only counted
      const std::span<const Cell> in(block.data(), k);
      // The witness lies in the first proper simplex, found before the others are checked.
      if (first_row_ == npos) {
        std::vector<Violation> ignored;
        for (std::size_t i = 0; i < k && first_row_ == npos; ++i)
          if (checked_simplex(in[i], r0 + i, ignored)) first_row_ = r0 + i;
        if (first_row_ != npos) {
          first_cell_ = in[first_row_ - r0];
          if (orientation_(at(points_, first_cell_)) == kernel::NEGATIVE) std::swap(first_cell_[0], first_cell_[1]);
          Cell w;
          for (std::size_t i = 0; i <= D; ++i) w[i] = work_number(first_cell_[i]);
          witness.emplace(k_, at(work_, w));
        }
      }
      Cell* out = encoded.data();
      if (!options_.stream && !compact()) {
        rows_.resize(r0 + k);
        out = rows_.data() + r0;
      }
      struct Results {
        std::size_t proper = 0;
        std::vector<std::size_t> covering;
        std::vector<Violation> fatal;
      };
      const std::size_t ranges = std::clamp<std::size_t>(k / 4096, 1, 64);
      std::vector<Results> results(ranges);
      const bool concurrent = threads_for(ranges) > 1;
      // A share of several screens the rows first (share_screen.hpp) and goes
      // on with those that matter to it, listed by range; out[] is written
      // only for those.
      const bool screened = sharing_ && share_.parts > 1;
      std::vector<std::vector<std::uint32_t>> listed(screened ? ranges : 0);
      for_each_parallel(ranges, [&](std::size_t j) {
        Results& res = results[j];
        std::vector<Violation> others;  // another share's to report
        const std::size_t a = k * j / ranges, b = k * (j + 1) / ranges;
        const std::uint32_t* list = nullptr;
        std::size_t todo = b - a;
        if (screened) {
          screen_rows<D + 1>(in, a, b, r0, mine_, share_.part, share_.parts, listed[j]);
          list = listed[j].data();
          todo = listed[j].size();
        }
        const auto row = [&](std::size_t t) { return list ? std::size_t{list[t]} : a + t; };
        for (std::size_t t = 0; t < todo; ++t) {
          const std::size_t i = row(t);
          out[i] = invalid_row<D + 1>();
          if (!options_.all && !res.fatal.empty()) continue;
          // The rows come in order, their points at random: ask for them a few rows ahead.
          if (t + 8 < todo)
            for (std::uint32_t v : in[row(t + 8)])
              if (v < n) prefetch(work_number(v));
          if (!to_work_.empty() && t + 16 < todo)
            for (std::uint32_t v : in[row(t + 16)])
              if (v < n) __builtin_prefetch(&to_work_[v]);
          // A share checks the rows with a vertex in its range (every share
          // decides a row's validity alike) and reports those it owns.
          const auto [relevant, owned] = share_of_row(in[i], r0 + i);
          if (!relevant) continue;
          others.clear();
          const auto s = checked_simplex(in[i], r0 + i, owned ? res.fatal : others);
          if (!s) continue;
          out[i] = encode_row(s->sorted, s->positive);
          ++res.proper;
          if (options_.stream) {
            count(facet_count_[s->sorted[0]], D, concurrent);
            count(facet_count_[s->sorted[1]], 1, concurrent);
          }
          for (std::uint32_t v : s->sorted) std::atomic_ref<std::uint8_t>(used_[v]).store(1, std::memory_order_relaxed);
          if (owned && r0 + i != first_row_ && contains_witness(*witness, s->sorted, s->positive)) res.covering.push_back(r0 + i);
        }
      });
      for (Results& res : results) {
        if (stop()) break;
        proper_rows_ += res.proper;
        for (Violation& v : res.fatal) fail(std::move(v));
        covering_.insert(covering_.end(), res.covering.begin(), res.covering.end());
      }
      // The rows checked, in order: all of the block, or a share's listed ones.
      const auto for_each_checked = [&](auto&& f) {
        if (!screened)
          for (std::size_t i = 0; i < k; ++i) f(i);
        else
          for (const auto& list : listed)
            for (std::uint32_t i : list) f(std::size_t{i});
      };
      if (compact() && !stop())
        for_each_checked([&](std::size_t i) {
          if (!is_valid_row(out[i])) return;
          rows_.push_back(out[i]);
          row_of_.push_back(r0 + i);
        });
      if (options_.stream && !stop())
        for_each_checked([&](std::size_t i) {
          if (!is_valid_row(out[i])) return;
          Cell sorted = out[i];
          decode_row(sorted);
          buckets_->add(r0 + i, out[i], sorted);
        });
    }
    report_.simplices = r0;
    std::vector<std::uint8_t>().swap(usable_);
    mine_ = {};
    if (buckets_) buckets_->finish();
  }

  static void count(std::uint32_t& c, std::uint32_t k, bool concurrent) {
    if (concurrent) std::atomic_ref<std::uint32_t>(c).fetch_add(k, std::memory_order_relaxed);
    else c += k;
  }

  /// Whether the witness point lies inside a proper simplex (the certifier's
  /// numbers, increasing, with that order's orientation).
  bool contains_witness(const Witness_point<K>& o, const Cell& sorted, bool positive) const {
    if constexpr (kernel::approximate_coordinates_are_exact<K>) {
      // o is infinitesimally close to its anchor, an input point: a cell whose
      // bounding box (exact: the coordinates are the points) misses the anchor
      // cannot contain o.
      const auto coords = k_.approximate_coordinates_object();
      const auto& x = coords(o.anchor());
      for (int j = 0; j < D; ++j) {
        bool below = true, above = true;
        for (std::uint32_t v : sorted) {
          const double c = coords(work_[v])[static_cast<std::size_t>(j)];
          below = below && x[static_cast<std::size_t>(j)] < c;
          above = above && x[static_cast<std::size_t>(j)] > c;
        }
        if (below || above) return false;
      }
    }
    Cell_points p = at(work_, sorted);
    if (!positive) std::swap(p[0], p[1]);
    return o.inside(p);
  }

  /// Row r (input numbers) in the certifier's numbers, sorted, with its
  /// orientation, or nothing (its violations appended to `fatal`).
  std::optional<Checked_row> checked_simplex(const Cell& c, std::size_t r, std::vector<Violation>& fatal) const {
    const std::size_t n = points_.size();
    // The common case first: indices in range, usable points (usable_, in the
    // certifier's numbers, where the row's points sit close together),
    // distinct vertices. Anything else takes the walk below, which names
    // the violations in their order.
    Cell w;
    bool fast = true;
    for (std::size_t i = 0; i <= D && fast; ++i) {
      fast = c[i] < n;
      if (fast) w[i] = work_number(c[i]);
    }
    if (fast) {
      for (std::size_t i = 0; i <= D; ++i) fast = fast && usable_[w[i]];
      const Cell s = sort_row(w).v;
      for (std::size_t i = 0; i < D; ++i) fast = fast && s[i] != s[i + 1];
      if (fast) {
        const kernel::Sign o = row_orientation(at(work_, s));
        if (o == kernel::ZERO) {
          fatal.push_back({.rule = Rule::degenerate_simplex, .simplex = r});
          return std::nullopt;
        }
        return Checked_row{s, o == kernel::POSITIVE};
      }
    }
    bool ok = true;
    for (std::uint32_t v : c)
      if (v >= n) {
        fatal.push_back({.rule = Rule::index_out_of_range, .simplex = r, .point = v});
        ok = false;
      }
    if (!ok) return std::nullopt;
    const Cell sorted = sort_row(c).v;
    if (const auto dup = std::adjacent_find(sorted.begin(), sorted.end()); dup != sorted.end()) {
      fatal.push_back({.rule = Rule::repeated_vertex, .simplex = r, .point = *dup});
      return std::nullopt;
    }
    for (std::uint32_t v : c) {
      if (bad_point_[v]) ok = false;  // reported with the point
      else if (duplicate_[v]) {
        fatal.push_back({.rule = Rule::duplicate_point_used, .simplex = r, .point = v});
        ok = false;
      }
    }
    if (!ok) return std::nullopt;
    const Cell s = to_work_.empty() ? sorted : sort_row(w).v;
    const kernel::Sign o = row_orientation(at(work_, s));
    if (o == kernel::ZERO) {
      fatal.push_back({.rule = Rule::degenerate_simplex, .simplex = r});
      return std::nullopt;
    }
    return Checked_row{s, o == kernel::POSITIVE};
  }

  void check_vertices() {
    for (std::size_t i = 0; i < points_.size() && !stop(); ++i)
      if (!bad_point_[i] && !duplicate_[i] && owns_vertex(work_number(static_cast<std::uint32_t>(i))) &&
          !used_[work_number(static_cast<std::uint32_t>(i))])
        fail({.rule = Rule::point_not_a_vertex, .point = i});
  }

  /// What the facet checks of a range of vertices found, in vertex order.
  struct Facet_results {
    std::vector<Boundary_facet> boundary;
    std::vector<Violation> fatal, delaunay, notes;
    std::size_t interior_facets = 0, cospherical_facets = 0;
  };

  std::size_t stream_budget() const {
    return options_.working_memory ? options_.working_memory : std::size_t{1} << 29;
  }

  /// The facet checks in the certifier's numbers; when a first violation of a
  /// facet must be named (not Options::all), the walk that finds it runs in the
  /// input's numbers, whose order the reports follow.
  void check_facets() {
    facets_pass();
    if (renumbered() && !options_.all && (!facet_fatal_.empty() || !delaunay_.empty())) {
      to_input_numbers();
      facets_pass();
    }
    if (renumbered()) {
      // What the walk in the certifier's numbers found, in the input's order.
      const auto by_face = [](const Violation& a, const Violation& b) { return a.face < b.face; };
      for (auto* list : {&facet_fatal_, &delaunay_, &notes_}) {
        std::stable_sort(list->begin(), list->end(), by_face);
        for (Violation& v : *list)
          if (v.rule == Rule::duplicate_simplex && !sharing_) v.face.clear();  // a share's are sort keys
      }
      for (Boundary_facet& b : boundary_) {
        std::array<std::uint32_t, D> f;
        for (std::size_t i = 0; i < D; ++i) f[i] = to_input_[b.facet[i]];
        const auto s = sort_row(f);
        b = {s.v, to_input_[b.apex], b.positive != s.odd, b.row};
      }
      std::sort(boundary_.begin(), boundary_.end(), [](const Boundary_facet& a, const Boundary_facet& b) { return a.facet < b.facet; });
    }
    for (Violation& v : facet_fatal_) fail(std::move(v));
    std::vector<std::uint32_t>().swap(facet_count_);
    decltype(rows_)().swap(rows_);
    std::vector<std::size_t>().swap(row_of_);
    buckets_.reset();
  }

  /// Back to the input's numbers: the rows renumbered in place.
  void to_input_numbers() {
    for_each_parallel(std::max<std::size_t>(1, rows_.size() / 65536), [&](std::size_t j) {
      const std::size_t parts = std::max<std::size_t>(1, rows_.size() / 65536);
      for (std::size_t r = rows_.size() * j / parts; r < rows_.size() * (j + 1) / parts; ++r) {
        Cell c = rows_[r];
        if (!is_valid_row(c)) continue;
        const bool positive = decode_row(c);
        for (auto& v : c) v = to_input_[v];
        const auto s = sort_row(c);
        rows_[r] = encode_row(s.v, positive != s.odd);
      }
    });
    std::vector<std::uint32_t>().swap(to_input_);
    decltype(work_points_)().swap(work_points_);
    work_ = points_;
    boundary_.clear();
    facet_fatal_.clear();
    delaunay_.clear();
    notes_.clear();
    report_.interior_facets = report_.cospherical_facets = 0;
  }

  void facets_pass() {
    if (2 * report_.simplices < (std::size_t{1} << 32)) facets_pass<std::uint32_t>();
    else facets_pass<std::uint64_t>();
  }

  /// Facet matching, opposite sides, and the local Delaunay tests. The facets
  /// are filed by smallest vertex (facet_table.hpp), a window of vertices at a
  /// time so that the records stay within a budget of memory, and ranges of
  /// vertices are checked on all cores. The ranges are fixed by the number of
  /// points and the budget, and merged in order, each as far as the serial walk
  /// would have gone (it stops at the first fatal violation, and tests no
  /// sphere after the first Delaunay one), so the report is the same for any
  /// number of threads.
  template <class Row>
  void facets_pass() {
    if (!buckets_) {
      memory_facets_pass<Row>();
      return;
    }
    using Record = Facet_record<D, Row>;
    const std::size_t n = points_.size();
    std::size_t total = 0;
    for (std::uint32_t c : facet_count_) total += c;
    // Streaming (the rows in memory take memory_facets_pass): a window's
    // records take at most the working memory.
    const std::size_t budget = std::max<std::size_t>(1, stream_budget() / sizeof(Record));
    const std::size_t ranges =
        std::clamp<std::size_t>(std::max(std::min<std::size_t>(n / 4096, 256), 4 * (total / budget + 1)), 1, std::max<std::size_t>(n, 1));
    const auto range_first = [&](std::size_t r) { return n * r / ranges; };
    std::vector<std::size_t> range_facets(ranges, 0);
    for (std::size_t r = 0; r < ranges; ++r)
      for (std::size_t v = range_first(r); v < range_first(r + 1); ++v) range_facets[r] += facet_count_[v];
    // The windows: consecutive ranges, as many as fit the budget (one at least).
    std::vector<std::size_t> window_first{0};
    std::size_t largest = 0;
    for (std::size_t r = 0, sum = 0; r < ranges; ++r) {
      if (r > window_first.back() && sum + range_facets[r] > budget) {
        window_first.push_back(r);
        sum = 0;
      }
      sum += range_facets[r];
      largest = std::max(largest, sum);
    }
    window_first.push_back(ranges);
    std::vector<Record> storage(largest);
    std::vector<Facet_results> results(ranges);
    std::vector<Bucket_entry> chunk(std::max<std::size_t>(1024, std::min<std::size_t>(1 << 16, budget / 8)));
    for (std::size_t w = 0; w + 1 < window_first.size() && !stop_facets(); ++w) {
      const std::size_t first = window_first[w], last = window_first[w + 1];
      const std::size_t a = range_first(first), b = range_first(last);
      Facet_window<D, Row> window(std::span<const std::uint32_t>(facet_count_).subspan(a, b - a), a, b, storage);
      // One part of the window's vertices per thread, each reading every row.
      const std::size_t parts = threads_for(b - a);
      const auto part = [&](std::size_t lo, std::size_t hi, std::size_t k) {
        return std::pair{lo + (hi - lo) * k / parts, lo + (hi - lo) * (k + 1) / parts};
      };
      // The files of the ranges of vertices the window meets; from each, only
      // the facets whose smallest vertex is in both (a row is in two files
      // when its two smallest vertices are in two ranges).
      for (std::size_t f = buckets_->bucket_of(static_cast<std::uint32_t>(a)); f < buckets_->size() && buckets_->first_vertex(f) < b; ++f) {
        const std::size_t lo = std::max(a, buckets_->first_vertex(f)), hi = std::min(b, buckets_->first_vertex(f + 1));
        buckets_->for_each(f, chunk, [&](std::span<const Bucket_entry> entries) {
          for_each_parallel(parts, [&](std::size_t k) {
            const auto [plo, phi] = part(lo, hi, k);
            for (const Bucket_entry& e : entries) window.file(e.cell, static_cast<std::size_t>(e.row), plo, phi);
          });
        });
      }
      for_each_parallel(last - first, [&](std::size_t i) {
        const std::size_t r = first + i;
        check_window_groups<Row>(window, range_first(r), range_first(r + 1), results[r]);
      });
      merge(std::span<Facet_results>(results).subspan(first, last - first));
    }
  }

  /// The facet groups of a window's vertices [lo, hi), checked into `out`.
  /// The points of a bucket are its vertex's neighbours: asked for one bucket
  /// ahead, their cache misses overlap. Renumbered, the order of the facets
  /// does not matter: what is found is sorted afterwards, and a walk in the
  /// input's numbers names the first.
  template <class Row>
  void check_window_groups(Facet_window<D, Row>& window, std::size_t lo, std::size_t hi, Facet_results& out) const {
    using Record = Facet_record<D, Row>;
    window.for_groups(
        lo, hi, [&](std::size_t v, std::span<const Record> g) { check_facet_group<Row>(static_cast<std::uint32_t>(v), g, out); },
        [&](std::size_t v, std::span<const Record> next) {
          prefetch(static_cast<std::uint32_t>(v));
          for (const Record& rec : next) {
            prefetch(rec.apex);
            for (std::uint32_t u : rec.rest) prefetch(u);
          }
        },
        !renumbered());
  }

  /// The two smallest vertices of a valid encoded row (encode_row).
  static std::pair<std::uint32_t, std::uint32_t> smallest_two(const Cell& c) {
    if constexpr (D == 2) return {c[0], std::min(c[1], c[2])};
    else return {c[0], c[1]};
  }

  /// The facet pass with the rows in memory. The vertices are cut into ranges
  /// of equal width (a power of two) whose records fit a core's cache, and the
  /// rows are listed once by range (a counting sort of row numbers): a row is
  /// in the list of the range of its smallest vertex and, when that differs,
  /// of its second smallest (the smallest vertex of the facet opposite the
  /// first). Each range's facets are then filed from its list and grouped at
  /// once, while they are in cache, ranges on all cores, merged in order.
  template <class Row>
  void memory_facets_pass() {
    using Record = Facet_record<D, Row>;
    const std::size_t n = points_.size(), m = rows_.size();
    const std::size_t total = proper_rows_ * (D + 1);
    const unsigned workers = threads_for(std::numeric_limits<std::size_t>::max());
    // Records of a range: about 256 KB (a core's cache), within the working
    // memory when one is set; at most 2^20 ranges.
    std::size_t target = std::size_t{1} << 18;
    if (options_.working_memory) target = std::min(target, options_.working_memory / workers);
    target = std::max<std::size_t>(1, target / sizeof(Record));
    // A share walks its range of vertices when the walk is in the certifier's
    // numbers: its facets are filed there, and the ranges' width follows.
    std::size_t v_lo = 0, v_hi = n;
    if (sharing_ && (renumbered() || to_work_.empty())) v_lo = lo_, v_hi = hi_;
    std::size_t width = std::bit_floor(std::max<std::size_t>(1, target * (v_hi - v_lo) / std::max<std::size_t>(total, 1)));
    width = std::max(width, std::bit_ceil(std::max<std::size_t>(1, (n + (std::size_t{1} << 20) - 1) >> 20)));
    const int shift = std::countr_zero(width);
    const std::size_t ranges = (n + width - 1) >> shift;

    // The lists: counted by part of the rows, then filled, each part in row order.
    const std::size_t parts = threads_for(std::max<std::size_t>(1, m / 65536));
    std::vector<std::size_t> start(parts * ranges, 0);
    const auto part_rows = [&](std::size_t p) { return std::pair{m * p / parts, m * (p + 1) / parts}; };
    for_each_parallel(parts, [&](std::size_t p) {
      std::size_t* count = start.data() + p * ranges;
      const auto [a, b] = part_rows(p);
      for (std::size_t r = a; r < b; ++r) {
        if (!is_valid_row(rows_[r])) continue;
        const auto [s0, s1] = smallest_two(rows_[r]);
        ++count[s0 >> shift];
        if ((s1 >> shift) != (s0 >> shift)) ++count[s1 >> shift];
      }
    });
    // offset[R * parts + p]: where part p's rows of range R go (the counts are
    // laid out by part, the lists by range, then part).
    std::vector<std::size_t> offset(ranges * parts + 1, 0);
    std::size_t listed = 0;
    for (std::size_t R = 0; R < ranges; ++R)
      for (std::size_t p = 0; p < parts; ++p) {
        offset[R * parts + p] = listed;
        listed += start[p * ranges + R];
      }
    offset[ranges * parts] = listed;
    std::vector<std::size_t>().swap(start);
    Uninitialized_vector<Row> list(listed);
    for_each_parallel(parts, [&](std::size_t p) {
      std::vector<std::size_t> next(ranges);
      for (std::size_t R = 0; R < ranges; ++R) next[R] = offset[R * parts + p];
      const auto [a, b] = part_rows(p);
      for (std::size_t r = a; r < b; ++r) {
        if (!is_valid_row(rows_[r])) continue;
        const auto [s0, s1] = smallest_two(rows_[r]);
        list[next[s0 >> shift]++] = static_cast<Row>(r);
        if ((s1 >> shift) != (s0 >> shift)) list[next[s1 >> shift]++] = static_cast<Row>(r);
      }
    });

    std::vector<std::vector<Record>> storage(workers);
    std::vector<std::vector<std::uint32_t>> counts(workers);
    std::vector<Facet_results> results(ranges);
    const std::size_t batch = 64 * std::size_t{workers};
    const std::size_t first_range = v_lo >> shift, end_range = v_hi > v_lo ? ((v_hi - 1) >> shift) + 1 : first_range;
    for (std::size_t first = first_range; first < end_range && !stop_facets(); first += batch) {
      const std::size_t last = std::min(end_range, first + batch);
      for_each_parallel(last - first, [&](std::size_t i, unsigned worker) {
        const std::size_t R = first + i, lo = std::max(R << shift, v_lo), hi = std::min({n, (R << shift) + width, v_hi});
        const Row* begin = list.data() + offset[R * parts];
        const Row* end = list.data() + offset[(R + 1) * parts];
        // The facets per smallest vertex (counted here, from rows the filing
        // then finds in cache, rather than with atomic counters as rows are read).
        std::vector<std::uint32_t>& count = counts[worker];
        count.assign(hi - lo, 0);
        for (const Row* e = begin; e != end; ++e) {
          if (end - e > 16) __builtin_prefetch(&rows_[static_cast<std::size_t>(e[16])]);
          const auto [s0, s1] = smallest_two(rows_[static_cast<std::size_t>(*e)]);
          if (s0 >= lo && s0 < hi) count[s0 - lo] += D;
          if (s1 >= lo && s1 < hi) ++count[s1 - lo];
        }
        Facet_window<D, Row> window(count, lo, hi, storage[worker]);
        for (const Row* e = begin; e != end; ++e) {
          // The rows of a list are in increasing order, apart: ask for them ahead.
          if (end - e > 16) __builtin_prefetch(&rows_[static_cast<std::size_t>(e[16])]);
          window.file(rows_[static_cast<std::size_t>(*e)], static_cast<std::size_t>(*e), lo, hi);
        }
        check_window_groups<Row>(window, lo, hi, results[R]);
      });
      merge(std::span<Facet_results>(results).subspan(first, last - first));
    }
  }

  /// Whether the walk can stop: a facet's fatal violation is the first one in
  /// the input's order (unless Options::all), or, renumbered, the walk in the
  /// input's numbers will name it.
  bool stop_facets() const {
    if (options_.all) return false;
    return !facet_fatal_.empty() || (renumbered() && !delaunay_.empty());
  }

  void merge(std::span<Facet_results> results) {
    for (Facet_results& r : results) {
      if (stop_facets()) break;
      boundary_.insert(boundary_.end(), r.boundary.begin(), r.boundary.end());
      report_.interior_facets += r.interior_facets;
      for (Violation& v : r.fatal)
        if (options_.all || facet_fatal_.empty()) facet_fatal_.push_back(std::move(v));
      if (!options_.all && !delaunay_.empty()) continue;  // the serial walk tested no more spheres
      report_.cospherical_facets += r.cospherical_facets;
      delaunay_.insert(delaunay_.end(), r.delaunay.begin(), r.delaunay.end());
      for (Violation& v : r.notes) {
        if (options_.all || notes_.empty()) notes_.push_back(std::move(v));
        else if (renumbered() && v.face < notes_[0].face) notes_[0] = std::move(v);  // the first in the input's order
      }
      r = {};
    }
  }

  /// Whether rows_ keeps only the share's rows (in memory, a share of several).
  bool compact() const { return sharing_ && share_.parts > 1 && !options_.stream; }
  /// The row of an index into rows_ (a share keeps only its rows).
  std::size_t row_number(std::size_t k) const { return row_of_.empty() ? k : row_of_[k]; }

  /// A facet of the certifier's numbers as reported: in the input's, increasing.
  std::vector<std::uint32_t> input_face(const std::array<std::uint32_t, D>& facet) const {
    std::vector<std::uint32_t> f(facet.begin(), facet.end());
    if (renumbered()) {
      for (auto& v : f) v = to_input_[v];
      std::sort(f.begin(), f.end());
    }
    return f;
  }

  /// The checks of one facet (smallest vertex v) and its simplices, into `out`.
  /// Renumbered, every violation carries its facet (the key of the input's
  /// order), and a range keeps the note of the smallest facet.
  template <class Row>
  void check_facet_group(std::uint32_t v, std::span<const Facet_record<D, Row>> g, Facet_results& out) const {
    if (!options_.all && !out.fatal.empty()) return;
    if (!facet_in_share(v, g[0].rest)) return;
    std::array<std::uint32_t, D> facet;
    facet[0] = v;
    std::copy(g[0].rest.begin(), g[0].rest.end(), facet.begin() + 1);
    const auto face = [&] { return input_face(facet); };
    if (g.size() == 1) {
      out.boundary.push_back({facet, g[0].apex, g[0].positive(), row_number(g[0].row())});
      return;
    }
    if (g.size() > 2) {
      out.fatal.push_back({.rule = Rule::facet_shared_by_many, .simplex = row_number(g[0].row()), .other_simplex = row_number(g[1].row()), .face = face()});
      return;
    }
    const std::uint32_t a = g[0].apex, b = g[1].apex;
    if (a == b) {
      out.fatal.push_back({.rule = Rule::duplicate_simplex, .simplex = row_number(g[0].row()), .other_simplex = row_number(g[1].row()),
                           .face = renumbered() || sharing_ ? face() : std::vector<std::uint32_t>{}});
      return;
    }
    // Both rows were found proper: (facet, a) and (facet, b) have known, non-zero
    // orientations, and the apexes lie on opposite sides exactly when these differ.
    if (g[0].positive() == g[1].positive()) {
      out.fatal.push_back({.rule = Rule::facet_same_side, .simplex = row_number(g[0].row()), .other_simplex = row_number(g[1].row()), .face = face()});
      return;
    }
    ++out.interior_facets;
    if (!options_.all && !out.delaunay.empty()) return;  // one witness is enough
    // (facet…, a) positively oriented, then b; the first two exchanged without
    // a branch (the orientation bit is random: a branch would mispredict).
    std::array<const Point*, D + 2> s;
    for (std::size_t i = 0; i < D; ++i) s[i] = &work_[facet[i]];
    s[D] = &work_[a];
    s[D + 1] = &work_[b];
    const bool positive = g[0].positive();
    const Point* s0 = s[0];
    const Point* s1 = s[1];
    s[0] = positive ? s0 : s1;
    s[1] = positive ? s1 : s0;
    const kernel::Oriented_side side = sphere_side(s);
    const auto witness = [&](Rule rule) {
      return Violation{.rule = rule, .simplex = row_number(g[0].row()), .other_simplex = row_number(g[1].row()), .face = face(), .point = input_number(b)};
    };
    if (side == kernel::ON_POSITIVE_SIDE) {
      out.delaunay.push_back(witness(Rule::not_locally_delaunay));
    } else if (side == kernel::ON_ORIENTED_BOUNDARY) {
      ++out.cospherical_facets;
      if (k_.side_of_oriented_sphere_d_object()(s) == kernel::ON_POSITIVE_SIDE) {
        if (options_.all || out.notes.empty()) out.notes.push_back(witness(Rule::not_canonical));
        else if (renumbered() && face() < out.notes[0].face) out.notes[0] = witness(Rule::not_canonical);
      }
    }
  }

  /// The project's kernel, whose filters the static one stands in front of.
  static constexpr bool has_static_filter = std::is_same_v<K, kernel::Filtered_kernel_d<D>> && kernel::Static_filter_d<D>::available;

  /// The box of the finite points, for the static filter.
  void make_static_filter() {
    if constexpr (has_static_filter) {
      std::array<double, D> lo, hi;
      lo.fill(INFINITY);
      hi.fill(-INFINITY);
      for (std::size_t i = 0; i < points_.size(); ++i) {
        if (bad_point_[i]) continue;
        for (std::size_t j = 0; j < D; ++j) {
          lo[j] = std::min(lo[j], points_[i].x[j]);
          hi[j] = std::max(hi[j], points_[i].x[j]);
        }
      }
      if (lo[0] <= hi[0]) static_filter_ = kernel::Static_filter_d<D>(lo, hi);
    }
  }

  /// The unperturbed sphere test. With the project's kernel, through the
  /// static filter over the points' box, in 3D its semi-static bound first
  /// (as the triangulator's cavity search): the same sign as the kernel's own
  /// cascade, which it falls back on, without that cascade's call and its
  /// checks of each call's columns against the filter's domain (the box has
  /// passed them once).
  kernel::Oriented_side sphere_side(const std::array<const Point*, D + 2>& s) const {
    if constexpr (has_static_filter) {
      std::uint32_t left = 0;
      return static_cast<kernel::Oriented_side>(static_filter_.template side_of_oriented_sphere_sign<D == 3>(s, left));
    } else {
      return k_.side_of_oriented_sphere_unperturbed_d_object()(s);
    }
  }

  /// A row's orientation: with the project's kernel the static filter's box
  /// bound first (a simplex is small against the box: it decides nearly every
  /// row), then the kernel's cascade.
  kernel::Sign row_orientation(const Cell_points& p) const {
    if constexpr (has_static_filter)
      if (const auto sign = static_filter_.orientation(p)) return *sign;
    return orientation_(p);
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

  /// for_each_parallel as a loop object (kernel/serial_loop.hpp), for the
  /// functions that take one.
  auto loop() const {
    return [this](std::size_t count, auto&& f) { for_each_parallel(count, f); };
  }

  /// The threads for_each_parallel(count, …) runs on.
  unsigned threads_for(std::size_t count) const {
    const unsigned threads = options_.threads ? options_.threads : available_cores();
    return static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(threads, count)));
  }

  /// Calls f(0) … f(count − 1), on up to Options::threads threads (0: all
  /// cores), then rethrows the exception of the first call that threw (out
  /// of memory, say). Each worker sets the floating-point environment the
  /// kernel's filters assume (floating_point.hpp).
  /// f may also take the worker's number, below threads_for(count), as a
  /// second argument (for the worker's own scratch memory).
  template <class F>
  void for_each_parallel(std::size_t count, F&& f) const {
    const unsigned threads = threads_for(count);
    std::vector<std::exception_ptr> errors(count);
    std::atomic<std::size_t> next{0};
    auto work = [&](unsigned worker) {
      const kernel::Fp_environment_guard guard;
      for (std::size_t i; (i = next.fetch_add(1)) < count;) {
        try {
          if constexpr (std::is_invocable_v<F&, std::size_t, unsigned>) f(i, worker);
          else f(i);
        } catch (...) {
          errors[i] = std::current_exception();
        }
      }
    };
    std::vector<std::thread> pool;
    try {
      for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
    } catch (const std::system_error&) {
      // No more threads to be had: those started and this one do the work.
    }
    work(0);
    for (auto& t : pool) t.join();
    for (const auto& e : errors)
      if (e) std::rethrow_exception(e);
  }

  /// The boundary (input numbers): a closed surface (every ridge in two
  /// boundary facets), locally convex at every ridge, facing away from the
  /// witness point.
  void check_boundary() {
    report_.boundary_facets = boundary_.size();
    std::vector<std::array<std::uint32_t, D>> facets(boundary_.size());
    for (std::size_t b = 0; b < boundary_.size(); ++b) facets[b] = boundary_[b].facet;
    group_faces<D>(points_.size(), std::span<const std::array<std::uint32_t, D>>(facets),
                   [&](std::span<const Face_ref> g) {
                     if (stop()) return;
                     const Face_ref f1 = g[0];
                     if (g.size() != 2) {
                       fail({.rule = Rule::boundary_ridge_not_manifold, .simplex = boundary_[f1.row].row,
                             .face = without(facets[f1.row], facets[f1.row][static_cast<std::size_t>(f1.position)])});
                       return;
                     }
                     for (int t = 0; t < 2; ++t) {
                       const Face_ref f = g[static_cast<std::size_t>(t)], o = g[static_cast<std::size_t>(1 - t)];
                       const Boundary_facet& bf = boundary_[f.row];
                       const std::uint32_t far = facets[o.row][static_cast<std::size_t>(o.position)];
                       // The simplex's inner side is its apex's: `far` must not be strictly across.
                       if (orientation_(oriented(points_, bf.facet, far, bf.positive)) == kernel::NEGATIVE) {
                         fail({.rule = Rule::boundary_not_convex, .simplex = bf.row, .other_simplex = boundary_[o.row].row,
                               .face = without(bf.facet, bf.facet[static_cast<std::size_t>(f.position)]), .point = far});
                         return;
                       }
                     }
                   });
    const Witness_point<K> o(k_, at(points_, first_cell_));
    for (const auto& b : boundary_) {
      if (stop()) return;
      if (o.side_of_facet(oriented(points_, b.facet, b.apex, b.positive), D) != kernel::POSITIVE)
        fail({.rule = Rule::boundary_facet_inward, .simplex = b.row, .other_simplex = first_row_,
              .face = std::vector<std::uint32_t>(b.facet.begin(), b.facet.end())});
    }
  }

  /// The global test: no simplex but the first contains the witness point
  /// (the rows that do were collected by read_rows).
  void check_covering() {
    for (std::size_t t : covering_) {
      if (stop()) return;
      fail({.rule = Rule::multiple_covering, .simplex = t, .other_simplex = first_row_, .point = first_cell_[0]});
    }
  }

  const K& k_;
  std::span<const Point> points_;  // in the input's numbers
  std::span<const Point> work_;    // in the certifier's: work_points_, or points_
  Options options_;
  decltype(std::declval<const K&>().orientation_d_object()) orientation_;
  Report report_;
  std::vector<Violation> fatal_, facet_fatal_, delaunay_, notes_;
  std::vector<bool> bad_point_;
  kernel::Static_filter_d<D> static_filter_;  // over the finite points' box (never decides until made)
  std::vector<bool> duplicate_;            // a later occurrence of an earlier point
  Uninitialized_vector<std::uint64_t> z_sorted_;  // check_points' Z order for renumber (z_order_keys)
  std::vector<std::uint32_t> to_work_, to_input_;  // the certifier's numbering (empty: the input's)
  Uninitialized_vector<Point> work_points_;
  std::vector<std::uint8_t> used_;          // a vertex of a proper simplex (bytes: set from all cores)
  std::vector<std::uint8_t> usable_;        // finite and a first occurrence (while the rows are read)
  std::vector<std::uint32_t> facet_count_;  // facets of proper simplices by smallest vertex (streaming)
  std::size_t proper_rows_ = 0;             // rows found proper simplices
  Uninitialized_vector<Cell> rows_;         // every row, encode_row'd (in memory; a share: its valid rows)
  std::vector<std::size_t> row_of_;         // a share's: the row of each of rows_
  Vertex_set mine_;                         // a share's: its vertices, in the input's numbers
  std::optional<Row_buckets<D + 1>> buckets_;  // the proper rows (streaming)
  std::size_t first_row_ = npos;            // the first proper simplex: the witness lies in it
  Cell first_cell_{};                       // its vertices (input numbers), positively oriented
  std::vector<std::size_t> covering_;       // other rows that contain the witness
  std::vector<Boundary_facet> boundary_;    // facets of one simplex, in facet order (input numbers)
  bool sharing_ = false;                    // run_share: one share of the work
  Share share_{};
  std::size_t lo_ = 0, hi_ = 0;             // the share's vertices (the certifier's numbers)
};

}  // namespace dewall::certify::detail
DEWALL_FLOATING_POINT_CODE_END
#endif

namespace dewall::certify {

/// Decides whether the rows of `simplices` (each D + 1 input indices, any
/// vertex order, any row order) form a Delaunay triangulation of `points`, and
/// whether it is the canonical one (the symbolically perturbed Delaunay
/// triangulation CGAL and dewall compute). Duplicate points: the first
/// occurrence must be the vertex, later copies must not appear. See the file
/// comment for the checks and why they suffice. The source is read once, in
/// blocks; with Options::stream the rows go to temporary files (row_buckets.hpp).
/// With the project's kernel the check runs in the compiled library, whatever
/// the caller's floating-point flags; with another kernel it is compiled here,
/// and refuses to compile under flags that break its arithmetic (floating_point.hpp).
/// Complexity: O(n + m·D²) predicates and bookkeeping expected, n points, m simplices.
/// \throws what the source throws; std::runtime_error when a temporary file
/// cannot be written; std::bad_alloc.
template <kernel::DelaunayKernel K>
Report certify(std::span<const typename K::Point_d> points, Simplex_source<K::dimension>& simplices,
               const Options& options = {}, const K& k = {}) {
  if constexpr (std::is_same_v<K, kernel::Filtered_kernel_d<K::dimension>>) {
    return detail::certify_filtered<K::dimension>(points, simplices, options);
  } else {
#ifdef DEWALL_UNSAFE_FP_FLAGS
    static_assert(detail::always_false<K>,
                  "dewall: certify with a kernel other than Filtered_kernel_d is compiled in this file, "
                  "which is compiled with " DEWALL_UNSAFE_FP_FLAGS "; its error bounds need IEEE "
                  "arithmetic. Compile this file without that flag, or use Filtered_kernel_d.");
    return {};
#else
    const kernel::Fp_environment_guard guard;
    return detail::Certifier<K>(k, points, options).run(simplices);
#endif
  }
}

/// One share of certify(): the checks Share names, for merge_shares, which
/// makes of the shares' reports (all parts, each computed with the same points,
/// rows and options) the report certify() gives. Each share reads every row; it
/// checks those with a vertex in its range. For a certification split over
/// processes (dewall-mpi certify).
/// \throws std::invalid_argument when share.part >= share.parts; as certify().
template <kernel::DelaunayKernel K>
Share_report<K::dimension> certify_share(std::span<const typename K::Point_d> points, Simplex_source<K::dimension>& simplices,
                                         Share share, const Options& options = {}, const K& k = {}) {
  if (share.part >= share.parts) throw std::invalid_argument("certify_share: part " + std::to_string(share.part) + " of " + std::to_string(share.parts));
  if constexpr (std::is_same_v<K, kernel::Filtered_kernel_d<K::dimension>>) {
    return detail::certify_share_filtered<K::dimension>(points, simplices, share, options);
  } else {
#ifdef DEWALL_UNSAFE_FP_FLAGS
    static_assert(detail::always_false<K>, "dewall: certify_share with a kernel other than Filtered_kernel_d: see certify()");
    return {};
#else
    const kernel::Fp_environment_guard guard;
    return detail::Certifier<K>(k, points, options).run_share(simplices, share);
#endif
  }
}

/// The report of certify() from the reports of all shares of certify_share
/// (any order; Options::all as theirs). Checks the boundary (a few predicates
/// per boundary facet). \throws std::invalid_argument unless `shares` holds
/// each part 0 … parts − 1 exactly once, all made of these points with the
/// same numbering (a missing share or one made another way would let a
/// violation go unseen).
template <kernel::DelaunayKernel K>
Report merge_shares(std::span<const typename K::Point_d> points, std::span<const Share_report<K::dimension>> shares,
                    const Options& options = {}, const K& k = {}) {
  if (shares.empty()) throw std::invalid_argument("merge_shares: no shares");
  std::vector<bool> seen(shares.size(), false);
  for (const auto& s : shares) {
    if (s.share.parts != shares.size() || s.share.part >= s.share.parts || seen[s.share.part])
      throw std::invalid_argument("merge_shares: the shares are not parts 0 to " + std::to_string(shares.size() - 1) +
                                  " of " + std::to_string(shares.size()) + ", each once");
    seen[s.share.part] = true;
    if (s.point_count != points.size() || s.input_numbering != shares[0].input_numbering)
      throw std::invalid_argument("merge_shares: the shares were not all made of these points with the same numbering");
  }
  if constexpr (std::is_same_v<K, kernel::Filtered_kernel_d<K::dimension>>) {
    return detail::merge_shares_filtered<K::dimension>(points, shares, options);
  } else {
#ifdef DEWALL_UNSAFE_FP_FLAGS
    static_assert(detail::always_false<K>, "dewall: merge_shares with a kernel other than Filtered_kernel_d: see certify()");
    return {};
#else
    const kernel::Fp_environment_guard guard;
    return detail::Certifier<K>(k, points, options).merge_shares(shares);
#endif
  }
}

/// The rows of a span (copied into the certifier's own numbering as they are read).
template <kernel::DelaunayKernel K>
Report certify(std::span<const typename K::Point_d> points,
               std::span<const Simplex_indices<K::dimension>> simplices, const Options& options = {},
               const K& k = {}) {
  Span_source<K::dimension> source(simplices);
  return certify<K>(points, source, options, k);
}

/// Convenience form for vectors.
template <kernel::DelaunayKernel K>
Report certify(const std::vector<typename K::Point_d>& points,
               const std::vector<Simplex_indices<K::dimension>>& simplices, const Options& options = {},
               const K& k = {}) {
  return certify<K>(std::span<const typename K::Point_d>(points),
                    std::span<const Simplex_indices<K::dimension>>(simplices), options, k);
}

}  // namespace dewall::certify
