// The CGAL builders' two assemblies (dewall/cgal/detail/): from the
// incremental engine's cells and adjacency (Graph_assembly, what the default
// options take) and from a simplex list (assemble(), for DeWall's walls and
// Engine::cgal). Each must give CGAL's own triangulation: the same finite
// cells, valid, and equal to CGAL's object after insertions and removals;
// on degenerate input (lattices: every cell's sphere through more points,
// duplicates, cospherical points), with vertex info, Parallel_tag and in 4D.
#include <catch2/catch.hpp>

#include <CGAL/Alpha_shape_3.h>
#include <CGAL/Alpha_shape_cell_base_3.h>
#include <CGAL/Alpha_shape_vertex_base_3.h>
#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Epick_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "dewall/cgal/delaunay_triangulation_2.hpp"
#include "dewall/cgal/delaunay_triangulation_3.hpp"
#include "dewall/cgal/delaunay_triangulation_d.hpp"
#include "dewall/certify/cgal.hpp"
#include "dewall/io/point_reader.hpp"
#include "dewall/io/simplex_reader.hpp"
#include "support/dewall_point_sets.hpp"

using dewall::kernel::Point_d;
using dewall::cgal::detail::Assembly;

namespace {

using K = CGAL::Epick;
using Kd4 = CGAL::Epick_d<CGAL::Dimension_tag<4>>;

std::array<double, 2> coords_of(const K::Point_2& p) { return {p.x(), p.y()}; }
std::array<double, 3> coords_of(const K::Point_3& p) { return {p.x(), p.y(), p.z()}; }
std::array<double, 4> coords_of(const Kd4::Point_d& p) { return {p[0], p[1], p[2], p[3]}; }

template <class P>
P to_point(const Point_d<2>& p) { return P(p[0], p[1]); }
template <class P>
P to_point(const Point_d<3>& p) { return P(p[0], p[1], p[2]); }
template <class P>
P to_point(const Point_d<4>& p) { return P(p.x.begin(), p.x.end()); }

template <class T>
const auto& point_of(const T& item) {
  if constexpr (requires { item.first; }) return item.first;
  else return item;
}

/// The finite cells of t as sorted tuples of input indices (the first
/// occurrence of each vertex's point), sorted.
template <int D, class DT, class Items>
std::vector<std::array<std::size_t, D + 1>> cells_by_index(const DT& t, const Items& items) {
  std::map<std::array<double, D>, std::size_t> first;
  for (std::size_t i = items.size(); i-- > 0;) first[coords_of(point_of(items[i]))] = i;
  std::vector<std::array<std::size_t, D + 1>> out;
  const auto add = [&](auto c) {
    std::array<std::size_t, D + 1> s;
    for (int i = 0; i <= D; ++i) s[static_cast<std::size_t>(i)] = first.at(coords_of(c->vertex(i)->point()));
    std::sort(s.begin(), s.end());
    out.push_back(s);
  };
  if constexpr (D == 2) {
    for (auto c = t.finite_faces_begin(); c != t.finite_faces_end(); ++c) add(c);
  } else if constexpr (D == 3) {
    for (auto c = t.finite_cells_begin(); c != t.finite_cells_end(); ++c) add(c);
  } else {
    for (auto c = t.finite_full_cells_begin(); c != t.finite_full_cells_end(); ++c) add(c);
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// dt built by the builder's internals with `options`, through the assembly
/// `expected` names; checked against CGAL's own construction `theirs`:
/// valid, the same vertices and finite cells, then the same after inserting
/// points and removing every fifth input point.
template <int D, class DT, class Items>
void check_assembly(const Items& items, const dewall::Options& options, Assembly expected, DT theirs, DT ours) {
  Assembly built;
  Items copy = items;  // the builder empties it
  if constexpr (D == 2) built = dewall::cgal::detail::build_with_dewall_2(ours, copy, options);
  else built = dewall::cgal::detail::build_with_dewall_3(ours, copy, options);
  REQUIRE(built == expected);
  REQUIRE(ours.is_valid(true));
  CHECK(ours.number_of_vertices() == theirs.number_of_vertices());
  CHECK(cells_by_index<D>(ours, items) == cells_by_index<D>(theirs, items));
  // A vertex's info: its point's first occurrence (the items' second).
  if constexpr (requires { items[0].second; }) {
    std::map<std::array<double, D>, typename Items::value_type::second_type> first;
    for (std::size_t i = items.size(); i-- > 0;) first[coords_of(items[i].first)] = items[i].second;
    for (auto v = ours.finite_vertices_begin(); v != ours.finite_vertices_end(); ++v)
      CHECK(v->info() == first.at(coords_of(v->point())));
  }

  std::mt19937_64 rng(20261207);
  std::vector<typename DT::Point> all;
  for (const auto& item : items) all.push_back(point_of(item));
  for (const auto& p : dewall::test::uniform<D>(30, rng)) {
    const auto q = to_point<typename DT::Point>(p);
    ours.insert(q);
    theirs.insert(q);
    all.push_back(q);
  }
  for (std::size_t i = 0; i < items.size(); i += 5) {
    const auto& p = point_of(items[i]);
    const auto a = ours.nearest_vertex(p), b = theirs.nearest_vertex(p);
    if (coords_of(a->point()) != coords_of(p)) continue;  // a duplicate, removed already
    ours.remove(a);
    theirs.remove(b);
  }
  CHECK(ours.is_valid(true));
  CHECK(cells_by_index<D>(ours, all) == cells_by_index<D>(theirs, all));
}

dewall::Options with_engine(dewall::Engine e) {
  dewall::Options o;
  o.engine = e;
  return o;
}

/// Both assemblies of points (as DT's items, made by `item(point, i)`) against CGAL.
template <int D, class DT, class Make_item>
void check_both(const std::vector<Point_d<D>>& input, Make_item&& item) {
  using Item = decltype(item(input[0], std::size_t{0}));
  std::vector<Item> items;
  for (std::size_t i = 0; i < input.size(); ++i) items.push_back(item(input[i], i));
  INFO("D = " << D << ", " << items.size() << " points");
  const DT theirs(items.begin(), items.end());
  SECTION("from the engine's adjacency (default options)") {
    check_assembly<D>(items, {}, Assembly::from_adjacency, theirs, DT());
  }
  SECTION("from the engine's adjacency (Engine::incremental)") {
    check_assembly<D>(items, with_engine(dewall::Engine::incremental), Assembly::from_adjacency, theirs, DT());
  }
  SECTION("from simplices (Engine::dewall)") {
    check_assembly<D>(items, with_engine(dewall::Engine::dewall), Assembly::from_simplices, theirs, DT());
  }
  SECTION("from simplices (Engine::cgal)") {
    check_assembly<D>(items, with_engine(dewall::Engine::cgal), Assembly::from_simplices, theirs, DT());
  }
}

template <int D, class DT, class Make_item>
void check_families(std::size_t n, std::uint64_t seed, Make_item&& item) {
  namespace t = dewall::test;
  std::mt19937_64 rng(seed);
  SECTION("uniform") { check_both<D, DT>(t::uniform<D>(n, rng), item); }
  SECTION("integer lattice (cospherical ties everywhere)") { check_both<D, DT>(t::lattice<D>(n), item); }
  SECTION("lattice samples with duplicates, random order") { check_both<D, DT>(t::lattice_samples<D>(n, 3, rng), item); }
  SECTION("cospherical points and the centre") { check_both<D, DT>(t::cospherical<D>(true), item); }
}

template <class P>
auto plain() {
  return [](const auto& p, std::size_t) { return to_point<P>(p); };
}
template <class P>
auto with_info() {
  return [](const auto& p, std::size_t i) { return std::pair<P, std::size_t>(to_point<P>(p), i); };
}

using DT2 = CGAL::Delaunay_triangulation_2<K>;
using DT3 = CGAL::Delaunay_triangulation_3<K>;
using DT2_info = CGAL::Delaunay_triangulation_2<
    K, CGAL::Triangulation_data_structure_2<CGAL::Triangulation_vertex_base_with_info_2<std::size_t, K>,
                                            CGAL::Triangulation_face_base_2<K>>>;
using DT3_info = CGAL::Delaunay_triangulation_3<
    K, CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_with_info_3<std::size_t, K>,
                                            CGAL::Delaunay_triangulation_cell_base_3<K>>>;
using DT3_parallel = CGAL::Delaunay_triangulation_3<
    K, CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_3<K>,
                                            CGAL::Delaunay_triangulation_cell_base_3<K>, CGAL::Parallel_tag>>;

}  // namespace

TEST_CASE("CGAL builders, both assemblies: 2D equals CGAL", "[cgal][builders][assembly][2d]") {
  check_families<2, DT2>(2000, 20261201, plain<K::Point_2>());
}
TEST_CASE("CGAL builders, both assemblies: 3D equals CGAL", "[cgal][builders][assembly][3d]") {
  check_families<3, DT3>(1500, 20261202, plain<K::Point_3>());
}
TEST_CASE("CGAL builders, both assemblies: 2D with vertex info", "[cgal][builders][assembly][2d]") {
  check_families<2, DT2_info>(1000, 20261203, with_info<K::Point_2>());
}
TEST_CASE("CGAL builders, both assemblies: 3D with vertex info", "[cgal][builders][assembly][3d]") {
  check_families<3, DT3_info>(1000, 20261204, with_info<K::Point_3>());
}

TEST_CASE("CGAL builders, both assemblies: 3D Parallel_tag", "[cgal][builders][assembly][parallel]") {
  std::mt19937_64 rng(20261205);
  for (const auto& input : {dewall::test::uniform<3>(1500, rng), dewall::test::lattice_samples<3>(1000, 3, rng)}) {
    std::vector<K::Point_3> points;
    for (const auto& p : input) points.push_back(to_point<K::Point_3>(p));
    DT3_parallel::Lock_data_structure ours_lock(CGAL::Bbox_3(0, 0, 0, 1, 1, 1), 20);
    DT3_parallel::Lock_data_structure theirs_lock(CGAL::Bbox_3(0, 0, 0, 1, 1, 1), 20);
    DT3_parallel theirs(points.begin(), points.end(), K(), &theirs_lock);
    for (const dewall::Engine engine : {dewall::Engine::automatic, dewall::Engine::dewall}) {
      DT3_parallel ours(K(), &ours_lock);
      std::vector<K::Point_3> copy = points;  // the builder empties it
      const Assembly built = dewall::cgal::detail::build_with_dewall_3(ours, copy, with_engine(engine));
      CHECK(built == (engine == dewall::Engine::automatic ? Assembly::from_adjacency : Assembly::from_simplices));
      REQUIRE(ours.is_valid(true));
      CHECK(cells_by_index<3>(ours, points) == cells_by_index<3>(theirs, points));
      // A parallel insertion afterwards (more than 50 points and a lock data structure).
      std::vector<K::Point_3> more;
      for (const auto& p : dewall::test::uniform<3>(500, rng)) more.push_back(to_point<K::Point_3>(p));
      DT3_parallel again(points.begin(), points.end(), K(), &theirs_lock);
      ours.insert(more.begin(), more.end());
      again.insert(more.begin(), more.end());
      std::vector<K::Point_3> all = points;
      all.insert(all.end(), more.begin(), more.end());
      CHECK(ours.is_valid(true));
      CHECK(cells_by_index<3>(ours, all) == cells_by_index<3>(again, all));
    }
  }
}

TEST_CASE("CGAL builders, both assemblies: 4D equals CGAL", "[cgal][builders][assembly][4d]") {
  using DT = CGAL::Delaunay_triangulation<Kd4>;
  std::mt19937_64 rng(20261206);
  for (const auto& input : {dewall::test::uniform<4>(300, rng), dewall::test::lattice<4>(200)}) {
    std::vector<Kd4::Point_d> points;
    for (const auto& p : input) points.push_back(to_point<Kd4::Point_d>(p));
    DT theirs(4);
    theirs.insert(points.begin(), points.end());
    for (const dewall::Engine engine : {dewall::Engine::automatic, dewall::Engine::dewall}) {
      const DT ours = dewall::cgal::make_delaunay_triangulation_d<DT>(points, with_engine(engine));
      REQUIRE(ours.is_valid(true));
      CHECK(cells_by_index<4>(ours, points) == cells_by_index<4>(theirs, points));
    }
  }
}

// Above 2^16 points the engine inserts in zones, which leave unused slots
// among the cells (free slots the assembly skips).
TEST_CASE("CGAL builders, adjacency assembly: zoned insertion's free slots", "[cgal][builders][assembly][heavy]") {
  std::mt19937_64 rng(20261208);
  SECTION("2D") {
    std::vector<K::Point_2> points;
    for (const auto& p : dewall::test::uniform<2>(80000, rng)) points.push_back(to_point<K::Point_2>(p));
    DT2 ours;
    std::vector<K::Point_2> copy = points;
    REQUIRE(dewall::cgal::detail::build_with_dewall_2(ours, copy, {}) == Assembly::from_adjacency);
    REQUIRE(ours.is_valid(true));
    CHECK(cells_by_index<2>(ours, points) == cells_by_index<2>(DT2(points.begin(), points.end()), points));
  }
  SECTION("3D") {
    std::vector<K::Point_3> points;
    for (const auto& p : dewall::test::uniform<3>(75000, rng)) points.push_back(to_point<K::Point_3>(p));
    DT3 ours;
    std::vector<K::Point_3> copy = points;
    REQUIRE(dewall::cgal::detail::build_with_dewall_3(ours, copy, {}) == Assembly::from_adjacency);
    REQUIRE(ours.is_valid(true));
    CHECK(cells_by_index<3>(ours, points) == cells_by_index<3>(DT3(points.begin(), points.end()), points));
  }
}

TEST_CASE("CGAL builders: CGAL's constructor forms and classes derived from the triangulation", "[cgal][builders]") {
  std::mt19937_64 rng(20261209);
  std::vector<K::Point_3> points;
  for (const auto& p : dewall::test::uniform<3>(1000, rng)) points.push_back(to_point<K::Point_3>(p));
  SECTION("DT(first, last, &lock_ds)") {
    DT3_parallel::Lock_data_structure lock(CGAL::Bbox_3(0, 0, 0, 1, 1, 1), 20);
    const DT3_parallel ours = dewall::cgal::make_delaunay_triangulation_3<DT3_parallel>(points.begin(), points.end(), &lock);
    const DT3_parallel theirs(points.begin(), points.end(), &lock);
    CHECK(ours.get_lock_data_structure() == &lock);
    REQUIRE(ours.is_valid(true));
    CHECK(cells_by_index<3>(ours, points) == cells_by_index<3>(theirs, points));
  }
  SECTION("Alpha_shape_3<DT>: made from the assembled triangulation, as its range constructor does") {
    using Tds = CGAL::Triangulation_data_structure_3<CGAL::Alpha_shape_vertex_base_3<K>, CGAL::Alpha_shape_cell_base_3<K>>;
    using Alpha_shape = CGAL::Alpha_shape_3<CGAL::Delaunay_triangulation_3<K, Tds>>;
    const Alpha_shape ours = dewall::cgal::make_delaunay_triangulation_3<Alpha_shape>(points.begin(), points.end());
    const Alpha_shape theirs(points.begin(), points.end());
    REQUIRE(ours.is_valid(true));
    CHECK(cells_by_index<3>(ours, points) == cells_by_index<3>(theirs, points));
    // The alphas are squared radii, constructed inexactly: their rounding
    // depends on the order of each cell's vertices.
    const auto close = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::abs(b); };
    REQUIRE(ours.number_of_alphas() == theirs.number_of_alphas());
    CHECK(std::equal(ours.alpha_begin(), ours.alpha_end(), theirs.alpha_begin(), close));
    CHECK(close(*ours.find_optimal_alpha(1), *theirs.find_optimal_alpha(1)));
    const auto classified = [](const Alpha_shape& a, Alpha_shape::Classification_type type) {
      std::vector<Alpha_shape::Cell_handle> cells;
      a.get_alpha_shape_cells(std::back_inserter(cells), type);
      return cells.size();
    };
    CHECK(classified(ours, Alpha_shape::INTERIOR) == classified(theirs, Alpha_shape::INTERIOR));
    CHECK(ours.get_mode() == theirs.get_mode());
  }
}

namespace {
/// Flips the first interior facet of a 3D triangulation that CGAL can flip
/// (its two cells' union convex): the result is no longer Delaunay.
template <class DT>
bool flip_a_finite_facet(DT& dt) {
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c)
    for (int i = 0; i < 4; ++i)
      if (!dt.is_infinite(c->neighbor(i)) && dt.flip(c, i)) return true;
  return false;
}
}  // namespace

// dewall::cgal::certify on CGAL's own triangulations (certify/include/dewall/certify/cgal.hpp):
// accepted as canonical, and rejected once an edge (2D) or a facet (3D) is flipped.
TEST_CASE("dewall::cgal::certify: CGAL's triangulations certified in place, flipped ones rejected", "[cgal][certify]") {
  std::mt19937_64 rng(20261207);
  SECTION("2D, and an edge flipped") {
    for (const auto& input : {dewall::test::uniform<2>(400, rng), dewall::test::lattice<2>(100)}) {
      std::vector<K::Point_2> points;
      for (const auto& p : input) points.push_back(to_point<K::Point_2>(p));
      DT2 dt(points.begin(), points.end());
      const auto report = dewall::cgal::certify(dt, {.threads = 2});
      CHECK((report.delaunay && report.canonical));
      CHECK(report.points == dt.number_of_vertices());
      CHECK(report.simplices == dt.number_of_faces());
    }
    std::vector<K::Point_2> points;
    for (const auto& p : dewall::test::uniform<2>(400, rng)) points.push_back(to_point<K::Point_2>(p));
    DT2 dt(points.begin(), points.end());
    bool flipped = false;
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end() && !flipped; ++f)
      for (int i = 0; i < 3 && !flipped; ++i) {
        const auto g = f->neighbor(i);
        if (dt.is_infinite(g)) continue;
        // The quadrilateral must be convex for the flip: the new diagonal crosses the old one.
        const auto& a = f->vertex(i)->point();
        const auto& b = g->vertex(g->index(f))->point();
        const auto& c = f->vertex(dt.ccw(i))->point();
        const auto& d = f->vertex(dt.cw(i))->point();
        if (CGAL::orientation(a, b, c) == CGAL::orientation(a, b, d) || CGAL::orientation(a, b, c) == CGAL::COLLINEAR ||
            CGAL::orientation(a, b, d) == CGAL::COLLINEAR)
          continue;
        dt.flip(f, i);
        flipped = true;
      }
    REQUIRE(flipped);
    const auto report = dewall::cgal::certify(dt);
    CHECK_FALSE(report.delaunay);
    REQUIRE(report.first_fatal());
    CHECK(report.first_fatal()->rule == dewall::certify::Rule::not_locally_delaunay);
  }
  SECTION("3D with vertex info, and a facet flipped") {
    std::vector<std::pair<K::Point_3, std::size_t>> points;
    for (const auto& p : dewall::test::uniform<3>(300, rng)) points.emplace_back(to_point<K::Point_3>(p), points.size());
    DT3_info dt(points.begin(), points.end());
    const auto report = dewall::cgal::certify(dt);
    CHECK((report.delaunay && report.canonical));
    CHECK(report.simplices == dt.number_of_finite_cells());
    REQUIRE(flip_a_finite_facet(dt));
    const auto flipped_report = dewall::cgal::certify(dt, {.all = true});
    CHECK_FALSE(flipped_report.delaunay);
    REQUIRE(flipped_report.first_fatal());
    CHECK(flipped_report.first_fatal()->rule == dewall::certify::Rule::not_locally_delaunay);
  }
  SECTION("4D") {
    using DT = CGAL::Delaunay_triangulation<Kd4>;
    std::vector<Kd4::Point_d> points;
    for (const auto& p : dewall::test::uniform<4>(100, rng)) points.push_back(to_point<Kd4::Point_d>(p));
    DT dt(4);
    dt.insert(points.begin(), points.end());
    const auto report = dewall::cgal::certify(dt);
    CHECK((report.delaunay && report.canonical));
    CHECK(report.simplices == dt.number_of_finite_full_cells());
  }
  SECTION("a flat triangulation has no cell to certify") {
    std::vector<K::Point_3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    const DT3 dt(points.begin(), points.end());
    CHECK_THROWS_AS(dewall::cgal::certify(dt), std::invalid_argument);
  }
}

// CGAL's operator<< files (io/src/mesh_formats.cpp, read by the name .cgal):
// the points and finite cells CGAL wrote, certified canonical; a flipped
// triangulation written so is rejected.
namespace {
template <int D, class DT>
dewall::certify::Report certify_cgal_file(const DT& dt, const std::string& path) {
  {
    std::ofstream out(path);
    out << std::setprecision(17) << dt;
  }
  const auto points = dewall::io::read_points_file(path);
  const auto cells = dewall::io::read_simplices_file(path, points.dimension, 0);
  REQUIRE(points.dimension == D);
  CHECK(points.size() == dt.number_of_vertices());
  std::vector<Point_d<D>> p(points.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int j = 0; j < D; ++j) p[i].x[static_cast<std::size_t>(j)] = points.coordinates[i * D + static_cast<std::size_t>(j)];
  std::vector<std::array<std::uint32_t, D + 1>> rows(cells.table.size());
  std::copy(cells.table.indices.begin(), cells.table.indices.end(), &rows[0][0]);
  std::filesystem::remove(path);
  return dewall::certify::certify<dewall::kernel::Filtered_kernel_d<D>>(p, rows);
}
}  // namespace

TEST_CASE("CGAL's triangulation files (operator<<) read and certified, 2D, 3D, dD", "[cgal][certify][formats]") {
  std::mt19937_64 rng(612);
  {
    std::vector<K::Point_2> points;
    for (const auto& p : dewall::test::uniform<2>(300, rng)) points.push_back(to_point<K::Point_2>(p));
    DT2 dt(points.begin(), points.end());
    const auto report = certify_cgal_file<2>(dt, "cgal_file_2.cgal");
    CHECK((report.delaunay && report.canonical));
    CHECK(report.simplices == dt.number_of_faces());
  }
  {
    std::vector<K::Point_3> points;
    for (const auto& p : dewall::test::uniform<3>(300, rng)) points.push_back(to_point<K::Point_3>(p));
    DT3 dt(points.begin(), points.end());
    const auto report = certify_cgal_file<3>(dt, "cgal_file_3.cgal");
    CHECK((report.delaunay && report.canonical));
    CHECK(report.simplices == dt.number_of_finite_cells());
    REQUIRE(flip_a_finite_facet(dt));
    const auto rejected = certify_cgal_file<3>(dt, "cgal_file_3_flipped.cgal");
    CHECK_FALSE(rejected.delaunay);
  }
  {
    std::vector<Kd4::Point_d> points;
    for (const auto& p : dewall::test::uniform<4>(80, rng)) points.push_back(to_point<Kd4::Point_d>(p));
    CGAL::Delaunay_triangulation<Kd4> dt(4);
    dt.insert(points.begin(), points.end());
    const auto report = certify_cgal_file<4>(dt, "cgal_file_4.cgal");
    CHECK((report.delaunay && report.canonical));
    CHECK(report.simplices == dt.number_of_finite_full_cells());
  }
}
