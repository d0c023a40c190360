// dewall::cgal::certify: certifies a CGAL Delaunay triangulation object in
// place — a CGAL::Delaunay_triangulation_2, a CGAL::Delaunay_triangulation_3
// or a dD CGAL::Delaunay_triangulation of static dimension (or a class
// derived from one) — with the independent certifier (certify.hpp), no file
// written: the finite vertices are read as the points, the finite cells as the
// rows, a block at a time.
//
//   DT dt(points.begin(), points.end());
//   const dewall::certify::Report report = dewall::cgal::certify(dt);
//   if (!report.delaunay) std::puts(dewall::certify::describe(*report.first_fatal()).c_str());
//
// The report numbers the points in the order of dt's finite vertices and the
// simplices in the order of its finite cells (faces in 2D, full cells in dD).
// The certifier decides from the cells' vertex sets and the coordinates
// alone: nothing of CGAL's own adjacency or predicates is trusted.
//
// The certifier's only CGAL header, and header-only: a program that includes
// it has CGAL; the certifier's library needs none, and nothing here comes
// from dewall's triangulator.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "dewall/certify/certify.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"
#include "dewall/kernel/point.hpp"

namespace dewall::cgal {

namespace certify_detail {

template <class DT>
inline constexpr bool is_full_cell_triangulation = requires { typename DT::Full_cell_handle; };
template <class DT>
inline constexpr bool is_cell_triangulation = requires { typename DT::Cell_handle; };
template <class DT>
inline constexpr bool is_face_triangulation = requires { typename DT::Face_handle; };

/// The dimension of the triangulation type: 2, 3, or the static maximal
/// dimension of a dD triangulation (0 when there is none).
template <class DT>
constexpr int dimension_of() {
  if constexpr (is_full_cell_triangulation<DT>) {
    if constexpr (requires { DT::Maximal_dimension::value; }) return int{DT::Maximal_dimension::value};
    else return 0;
  } else if constexpr (is_cell_triangulation<DT>) {
    return 3;
  } else if constexpr (is_face_triangulation<DT>) {
    return 2;
  } else {
    return 0;
  }
}

/// The finite vertices' numbers, looked up by address. A CGAL container hands
/// out its elements in blocks, so the addresses of vertices numbered in
/// iteration order mostly follow one another at the element's stride: the map
/// is the list of such runs, sorted by address (any other layout only makes
/// more runs). An address in no run (not a finite vertex) gets `none`.
template <class Vertex>
class Vertex_numbers {
 public:
  /// The next vertex, in numbering order.
  void add(const Vertex* v) {
    const auto a = reinterpret_cast<std::uintptr_t>(v);
    if (!runs_.empty() && a == runs_.back().start + runs_.back().count * sizeof(Vertex)) ++runs_.back().count;
    else runs_.push_back({a, count_, 1});
    ++count_;
  }
  void finish() {
    std::sort(runs_.begin(), runs_.end(), [](const Run& x, const Run& y) { return x.start < y.start; });
  }
  std::uint32_t operator()(const Vertex* v, std::uint32_t none) const {
    const auto a = reinterpret_cast<std::uintptr_t>(v);
    auto it = std::upper_bound(runs_.begin(), runs_.end(), a, [](std::uintptr_t x, const Run& r) { return x < r.start; });
    if (it == runs_.begin()) return none;
    --it;
    const std::uintptr_t offset = a - it->start;
    if (offset % sizeof(Vertex) != 0 || offset / sizeof(Vertex) >= it->count) return none;
    return static_cast<std::uint32_t>(it->first + offset / sizeof(Vertex));
  }

 private:
  struct Run {
    std::uintptr_t start;
    std::size_t first, count;
  };
  std::vector<Run> runs_;
  std::size_t count_ = 0;
};

/// The finite cells of a triangulation as rows of vertex numbers.
template <int D, class Cell_iterator, class Numbers>
class Cell_source final : public certify::Simplex_source<D> {
 public:
  Cell_source(Cell_iterator begin, Cell_iterator end, std::size_t count, const Numbers& numbers, std::uint32_t none)
      : it_(begin), end_(end), left_(count), numbers_(numbers), none_(none) {}
  std::size_t read(std::span<certify::Simplex_indices<D>> rows) override {
    std::size_t k = 0;
    for (; k < rows.size() && it_ != end_; ++k, ++it_)
      for (int i = 0; i <= D; ++i) rows[k][static_cast<std::size_t>(i)] = numbers_(&*it_->vertex(i), none_);
    left_ -= std::min(left_, k);
    return k;
  }
  std::size_t remaining() const override { return left_; }

 private:
  Cell_iterator it_, end_;
  std::size_t left_;
  const Numbers& numbers_;
  std::uint32_t none_;
};

}  // namespace certify_detail

/// Whether dt is a Delaunay triangulation of its vertices, and the canonical
/// one (certify.hpp: the report, its rules and witnesses). DT: a
/// CGAL::Delaunay_triangulation_2 or _3, or a dD CGAL::Delaunay_triangulation
/// with a static dimension (2 … 6), or a class derived from one, over a
/// kernel whose coordinates are doubles (Epick, Epick_d,
/// Simple_cartesian<double>); anything else is refused at compile time.
/// Points: dt's finite vertices in iteration order; simplices: its finite
/// cells in iteration order.
/// \throws std::invalid_argument when dt is not full-dimensional (fewer than
/// D + 1 affinely independent vertices: no D-dimensional cell to certify) or
/// has 2^32 − 1 vertices or more; std::bad_alloc.
/// Complexity: the certifier's, plus O(n + m log b) to number the vertices
/// of the m cells (b: the runs of vertex addresses, about the blocks of CGAL's
/// container).
template <class DT>
certify::Report certify(const DT& dt, const certify::Options& options = {}) {
  constexpr int D = certify_detail::dimension_of<DT>();
  static_assert(D >= 2 && D <= 6,
                "dewall::cgal::certify takes a CGAL::Delaunay_triangulation_2, _3, or a dD "
                "CGAL::Delaunay_triangulation of static dimension 2 to 6");
  static_assert(std::is_same_v<typename DT::Geom_traits::FT, double>,
                "dewall::cgal::certify reads the coordinates as doubles: use a kernel whose FT is double "
                "(Epick, Epick_d, Simple_cartesian<double>)");
  const auto fail = [](const std::string& what) { throw std::invalid_argument("dewall::cgal::certify: " + what); };
  const auto certify_rows = [&](auto vertices_begin, auto vertices_end, auto cells_begin, auto cells_end,
                                std::size_t cell_count) {
    using Vertex = std::remove_cvref_t<decltype(*vertices_begin)>;
    std::vector<kernel::Point_d<D>> points;
    certify_detail::Vertex_numbers<Vertex> numbers;
    for (auto v = vertices_begin; v != vertices_end; ++v) {
      kernel::Point_d<D> p;
      if constexpr (certify_detail::is_full_cell_triangulation<DT>) {
        const auto coordinate = dt.geom_traits().compute_coordinate_d_object();
        for (int i = 0; i < D; ++i) p.x[static_cast<std::size_t>(i)] = coordinate(v->point(), i);
      } else {
        for (int i = 0; i < D; ++i) p.x[static_cast<std::size_t>(i)] = v->point().cartesian(i);
      }
      points.push_back(p);
      numbers.add(&*v);
    }
    if (points.size() >= std::size_t{0xffffffff}) fail("2^32 - 1 vertices or more");
    numbers.finish();
    certify_detail::Cell_source<D, decltype(cells_begin), decltype(numbers)> source(
        cells_begin, cells_end, cell_count, numbers, static_cast<std::uint32_t>(points.size()));
    return certify::certify<kernel::Filtered_kernel_d<D>>(std::span<const kernel::Point_d<D>>(points), source, options);
  };
  const auto dimension_error = [&](int d) {
    fail("the triangulation has dimension " + std::to_string(d) + ", not " + std::to_string(D) +
         " (fewer than " + std::to_string(D + 1) + " affinely independent vertices): it has no cell to certify");
  };
  if constexpr (certify_detail::is_full_cell_triangulation<DT>) {
    if (dt.current_dimension() != D) dimension_error(dt.current_dimension());
    return certify_rows(dt.finite_vertices_begin(), dt.finite_vertices_end(), dt.finite_full_cells_begin(),
                        dt.finite_full_cells_end(), dt.number_of_finite_full_cells());
  } else if constexpr (certify_detail::is_cell_triangulation<DT>) {
    if (dt.dimension() != 3) dimension_error(dt.dimension());
    return certify_rows(dt.finite_vertices_begin(), dt.finite_vertices_end(), dt.finite_cells_begin(), dt.finite_cells_end(),
                        dt.number_of_finite_cells());
  } else {
    if (dt.dimension() != 2) dimension_error(dt.dimension());
    return certify_rows(dt.finite_vertices_begin(), dt.finite_vertices_end(), dt.finite_faces_begin(), dt.finite_faces_end(),
                        dt.number_of_faces());
  }
}

}  // namespace dewall::cgal
