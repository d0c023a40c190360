// The CGAL drop-in builders (dewall/cgal/*.hpp) return genuine CGAL
// triangulations equal to CGAL's own: the same finite cells (by the input index
// of the first occurrence of each vertex's point), valid, and behaving like
// CGAL's own object under locate, nearest_vertex, insert, remove, dual and
// stream I/O. Random and degenerate sets in 2D, 3D, 4D; lower-dimensional
// input through the documented fallback to CGAL's insertion.
#include <catch2/catch.hpp>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Epick_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <map>
#include <random>
#include <sstream>

#include "dewall/cgal/delaunay_triangulation_2.hpp"
#include "dewall/cgal/delaunay_triangulation_3.hpp"
#include "dewall/cgal/delaunay_triangulation_d.hpp"
#include "support/dewall_point_sets.hpp"
#include "support/cgal_reference.hpp"

using dewall::kernel::Point_d;

namespace {

using K = CGAL::Epick;
using DT2 = CGAL::Delaunay_triangulation_2<K>;
using DT3 = CGAL::Delaunay_triangulation_3<K>;
template <int D>
using Kd = CGAL::Epick_d<CGAL::Dimension_tag<D>>;
template <int D>
using DTd = CGAL::Delaunay_triangulation<Kd<D>>;

// Per dimension: the CGAL type, conversions, the builder and CGAL's own construction.
template <int D>
struct Flavour;

template <>
struct Flavour<2> {
  using DT = DT2;
  using Point = K::Point_2;
  static Point point(const Point_d<2>& p) { return {p[0], p[1]}; }
  static std::array<double, 2> coords(const Point& p) { return {p.x(), p.y()}; }
  static DT ours(const std::vector<Point>& p) { return dewall::cgal::make_delaunay_triangulation_2<DT>(p.begin(), p.end()); }
  static DT cgal(const std::vector<Point>& p) { return DT(p.begin(), p.end()); }
  static int dimension(const DT& t) { return t.dimension(); }
  template <class F>
  static void for_each_finite_cell(const DT& t, F&& f) {
    for (auto c = t.finite_faces_begin(); c != t.finite_faces_end(); ++c) f(c);
  }
  static std::pair<int, DT::Face_handle> locate(const DT& t, const Point& q) {
    DT::Locate_type lt;
    int li;
    const auto c = t.locate(q, lt, li);
    return {static_cast<int>(lt), lt == DT::OUTSIDE_CONVEX_HULL || lt == DT::OUTSIDE_AFFINE_HULL ? DT::Face_handle() : c};
  }
};

template <>
struct Flavour<3> {
  using DT = DT3;
  using Point = K::Point_3;
  static Point point(const Point_d<3>& p) { return {p[0], p[1], p[2]}; }
  static std::array<double, 3> coords(const Point& p) { return {p.x(), p.y(), p.z()}; }
  static DT ours(const std::vector<Point>& p) { return dewall::cgal::make_delaunay_triangulation_3<DT>(p.begin(), p.end()); }
  static DT cgal(const std::vector<Point>& p) { return DT(p.begin(), p.end()); }
  static int dimension(const DT& t) { return t.dimension(); }
  template <class F>
  static void for_each_finite_cell(const DT& t, F&& f) {
    for (auto c = t.finite_cells_begin(); c != t.finite_cells_end(); ++c) f(c);
  }
  static std::pair<int, DT::Cell_handle> locate(const DT& t, const Point& q) {
    DT::Locate_type lt;
    int li, lj;
    const auto c = t.locate(q, lt, li, lj);
    return {static_cast<int>(lt), lt == DT::OUTSIDE_CONVEX_HULL || lt == DT::OUTSIDE_AFFINE_HULL ? DT::Cell_handle() : c};
  }
};

template <>
struct Flavour<4> {
  using DT = DTd<4>;
  using Point = Kd<4>::Point_d;
  static Point point(const Point_d<4>& p) { return Point(p.x.begin(), p.x.end()); }
  static std::array<double, 4> coords(const Point& p) { return {p[0], p[1], p[2], p[3]}; }
  static DT ours(const std::vector<Point>& p) { return dewall::cgal::make_delaunay_triangulation_d<DT>(p.begin(), p.end()); }
  static DT cgal(const std::vector<Point>& p) {
    DT t(4);
    // CGAL 5.5's spatial_sort dereferences begin() of an empty range (UBSan).
    if (!p.empty()) t.insert(p.begin(), p.end());
    return t;
  }
  static int dimension(const DT& t) { return t.current_dimension(); }
  template <class F>
  static void for_each_finite_cell(const DT& t, F&& f) {
    for (auto c = t.finite_full_cells_begin(); c != t.finite_full_cells_end(); ++c) f(c);
  }
  static std::pair<int, DT::Full_cell_handle> locate(const DT& t, const Point& q) {
    DT::Locate_type lt;
    DT::Face f(t.maximal_dimension());
    DT::Facet ft;
    const auto c = t.locate(q, lt, f, ft);
    return {static_cast<int>(lt),
            lt == DT::OUTSIDE_CONVEX_HULL || lt == DT::OUTSIDE_AFFINE_HULL ? DT::Full_cell_handle() : c};
  }
};

/// The finite cells of t as sorted tuples of input indices (first occurrence
/// of each point), comparable across triangulations of the same points.
template <int D>
std::set<std::vector<std::size_t>> cells_by_index(const typename Flavour<D>::DT& t,
                                                  const std::vector<typename Flavour<D>::Point>& points) {
  using F = Flavour<D>;
  std::map<std::array<double, D>, std::size_t> first;
  for (std::size_t i = points.size(); i-- > 0;) first[F::coords(points[i])] = i;
  std::set<std::vector<std::size_t>> out;
  const int dim = F::dimension(t);
  F::for_each_finite_cell(t, [&](auto c) {
    std::vector<std::size_t> s;
    for (int i = 0; i <= dim; ++i) s.push_back(first.at(F::coords(c->vertex(i)->point())));
    std::sort(s.begin(), s.end());
    out.insert(s);
  });
  return out;
}

/// Builds with dewall and with CGAL, compares, then runs the same follow-up
/// operations on both and compares again.
template <int D>
void check_builder(const std::vector<Point_d<D>>& input, std::uint64_t seed) {
  using F = Flavour<D>;
  INFO("D = " << D << ", n = " << input.size() << ", seed = " << seed);
  std::vector<typename F::Point> points;
  for (const auto& p : input) points.push_back(F::point(p));
  typename F::DT ours = F::ours(points);
  typename F::DT theirs = F::cgal(points);
  REQUIRE(ours.is_valid(true));
  REQUIRE(F::dimension(ours) == F::dimension(theirs));
  CHECK(ours.number_of_vertices() == theirs.number_of_vertices());
  const auto cells = cells_by_index<D>(ours, points);
  CHECK(cells == cells_by_index<D>(theirs, points));
  if (F::dimension(theirs) == D) CHECK(cells.size() == dewall::test::cgal_delaunay<D>(input).size());

  // Queries at random points of the bounding box: the cell or vertex found
  // must be the same (generic queries have a unique answer).
  std::array<double, D> lo, hi;
  lo.fill(std::numeric_limits<double>::max());
  hi.fill(std::numeric_limits<double>::lowest());
  if (input.empty()) lo.fill(0), hi.fill(1);
  for (const auto& p : input)
    for (int j = 0; j < D; ++j) lo[j] = std::min(lo[j], p[j]), hi[j] = std::max(hi[j], p[j]);
  std::mt19937_64 rng(seed);
  std::vector<typename F::Point> queries;
  for (int q = 0; q < 20; ++q) {
    Point_d<D> x;
    for (int j = 0; j < D; ++j) x[j] = std::uniform_real_distribution<double>(lo[j] - 0.25, hi[j] + 0.25)(rng);
    queries.push_back(F::point(x));
  }
  auto finite_cell_points = [&](const auto& t, auto c) {
    std::set<std::array<double, D>> s;
    for (int i = 0; i <= F::dimension(t); ++i)
      if (!t.is_infinite(c->vertex(i))) s.insert(F::coords(c->vertex(i)->point()));
    return s;
  };
  // Outside the hull several infinite cells are valid answers: compare the
  // located cell only when it is finite, the locate type always.
  auto located = [&](const auto& t, const auto& q) {
    const auto [lt, c] = F::locate(t, q);
    return std::pair(lt, c == decltype(c)() ? std::set<std::array<double, D>>{} : finite_cell_points(t, c));
  };
  for (const auto& q : queries) {
    if (F::dimension(theirs) < 1) break;  // nothing to locate in
    CHECK(located(ours, q) == located(theirs, q));
    if constexpr (D != 4)  // the dD triangulation offers no nearest_vertex
      CHECK(F::coords(ours.nearest_vertex(q)->point()) == F::coords(theirs.nearest_vertex(q)->point()));
  }

  if constexpr (D != 4) {
    // The dual of each finite cell (its circumcentre) is CGAL's for the same
    // cell, up to rounding: the construction is inexact and its rounding
    // depends on the order of the cell's vertices.
    std::map<std::set<std::array<double, D>>, typename F::Point> dual;
    F::for_each_finite_cell(theirs, [&](auto c) { dual.emplace(finite_cell_points(theirs, c), theirs.dual(c)); });
    std::size_t same = 0;
    F::for_each_finite_cell(ours, [&](auto c) {
      const auto a = F::coords(dual.at(finite_cell_points(ours, c)));
      const auto b = F::coords(ours.dual(c));
      bool close = true;
      for (int j = 0; j < D; ++j) close = close && std::abs(a[j] - b[j]) <= 1e-9 * (1 + std::abs(a[j]));
      same += close;
    });
    CHECK(same == dual.size());
  }

  // Stream round trip: CGAL's own writer and reader, on ours and on CGAL's
  // object. (CGAL 5.5's dD reader gives an invalid triangulation for
  // lower-dimensional input, from CGAL's own object too: compare, not require.)
  auto round_trip = [&](const typename F::DT& t) {
    std::stringstream ss;
    ss.precision(17);  // CGAL writes points with the stream's precision
    ss << t;
    typename F::DT back = F::cgal({});
    ss >> back;
    return std::pair(back.is_valid(), cells_by_index<D>(back, points));
  };
  {
    const auto [ours_valid, ours_cells] = round_trip(ours);
    const auto [theirs_valid, theirs_cells] = round_trip(theirs);
    CHECK(ours_valid == theirs_valid);
    if (F::dimension(theirs) == D) CHECK(ours_valid);
    if (ours_valid) CHECK(ours_cells == cells);
  }

  // Insert the queries, then remove every third vertex: both stay equal.
  for (const auto& q : queries) {
    ours.insert(q);
    theirs.insert(q);
  }
  std::vector<typename F::Point> all = points;
  all.insert(all.end(), queries.begin(), queries.end());
  CHECK(ours.is_valid());
  CHECK(cells_by_index<D>(ours, all) == cells_by_index<D>(theirs, all));
  std::vector<typename F::Point> victims;
  for (std::size_t i = 0; i < points.size(); i += 3) victims.push_back(points[i]);
  for (const auto& v : victims) {
    // dD offers no nearest_vertex; inserting a present point returns its vertex.
    auto vertex_at = [&](auto& t) {
      if constexpr (D == 4) return t.insert(v);
      else return t.nearest_vertex(v);
    };
    const auto a = vertex_at(ours);
    const auto b = vertex_at(theirs);
    if (F::coords(a->point()) != F::coords(v) || F::coords(b->point()) != F::coords(v)) continue;  // removed as a duplicate
    ours.remove(a);
    theirs.remove(b);
  }
  CHECK(ours.is_valid());
  CHECK(cells_by_index<D>(ours, all) == cells_by_index<D>(theirs, all));
}

template <int D>
void check_families(std::size_t n, std::uint64_t seed) {
  namespace t = dewall::test;
  std::mt19937_64 rng(seed);
  SECTION("uniform random") { check_builder<D>(t::uniform<D>(n, rng), seed); }
  SECTION("integer lattice") { check_builder<D>(t::lattice<D>(n), seed); }
  SECTION("lattice with duplicates, random order") { check_builder<D>(t::lattice_samples<D>(n, 3, rng), seed); }
  SECTION("cospherical integer points") { check_builder<D>(t::cospherical<D>(false), seed); }
  SECTION("cospherical integer points and the centre") { check_builder<D>(t::cospherical<D>(true), seed); }
  SECTION("lower-dimensional: points in a hyperplane (CGAL fallback)") {
    auto p = t::uniform<D>(n / 4 + D, rng);
    for (auto& q : p) q[D - 1] = 0.5;
    check_builder<D>(p, seed);
  }
  SECTION("lower-dimensional: D distinct points with duplicates (CGAL fallback)") {
    auto p = t::uniform<D>(D, rng);
    p.push_back(p[0]);
    check_builder<D>(p, seed);
  }
  SECTION("no points") { check_builder<D>({}, seed); }
}

}  // namespace

TEST_CASE("CGAL builders: make_delaunay_triangulation_2 equals CGAL", "[cgal][builders][2d]") {
  check_families<2>(300, 20260501);
}
TEST_CASE("CGAL builders: make_delaunay_triangulation_3 equals CGAL", "[cgal][builders][3d]") {
  check_families<3>(250, 20260502);
}
TEST_CASE("CGAL builders: make_delaunay_triangulation_d equals CGAL in 4D", "[cgal][builders][4d]") {
  check_families<4>(80, 20260503);
}

TEST_CASE("CGAL builders: vertex info from std::pair<Point, Info>, first occurrence kept", "[cgal][builders]") {
  std::mt19937_64 rng(20260504);
  auto input = dewall::test::lattice_samples<3>(200, 4, rng);  // many duplicates
  SECTION("3D") {
    using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::size_t, K>;
    using DT = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb, CGAL::Delaunay_triangulation_cell_base_3<K>>>;
    std::vector<std::pair<K::Point_3, std::size_t>> items;
    for (std::size_t i = 0; i < input.size(); ++i) items.emplace_back(Flavour<3>::point(input[i]), i);
    const DT dt = dewall::cgal::make_delaunay_triangulation_3<DT>(items.begin(), items.end());
    REQUIRE(dt.is_valid(true));
    std::map<std::array<double, 3>, std::size_t> first;
    for (std::size_t i = input.size(); i-- > 0;) first[input[i].x] = i;
    CHECK(dt.number_of_vertices() == first.size());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
      CHECK(v->info() == first.at(Flavour<3>::coords(v->point())));
  }
  SECTION("2D") {
    using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, K>;
    using DT = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb, CGAL::Triangulation_face_base_2<K>>>;
    std::vector<std::pair<K::Point_2, std::size_t>> items;
    for (std::size_t i = 0; i < input.size(); ++i) items.emplace_back(K::Point_2(input[i][0], input[i][1]), i);
    const DT dt = dewall::cgal::make_delaunay_triangulation_2<DT>(items.begin(), items.end());
    REQUIRE(dt.is_valid(true));
    std::map<std::array<double, 2>, std::size_t> first;
    for (std::size_t i = input.size(); i-- > 0;) first[{input[i][0], input[i][1]}] = i;
    CHECK(dt.number_of_vertices() == first.size());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
      CHECK(v->info() == first.at(Flavour<2>::coords(v->point())));
  }
}

TEST_CASE("CGAL builders: Fast_location (Delaunay hierarchy) falls back to CGAL's insertion", "[cgal][builders]") {
  using DT = CGAL::Delaunay_triangulation_3<K, CGAL::Default, CGAL::Fast_location>;
  std::mt19937_64 rng(20260505);
  std::vector<K::Point_3> points;
  for (const auto& p : dewall::test::uniform<3>(300, rng)) points.push_back(Flavour<3>::point(p));
  const DT dt = dewall::cgal::make_delaunay_triangulation_3<DT>(points);
  CHECK(dt.is_valid());
  CHECK(dt.number_of_vertices() == points.size());
}

TEST_CASE("CGAL builders: non-finite coordinates are rejected", "[cgal][builders]") {
  std::vector<K::Point_3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, std::numeric_limits<double>::quiet_NaN()}};
  CHECK_THROWS_AS(dewall::cgal::make_delaunay_triangulation_3<DT3>(points), dewall::Invalid_input);
}
