// The CGAL builders are never silently wrong (issue 24): for every traits
// class, range and concurrency tag CGAL's construction accepts, the builder
// gives CGAL's triangulation (cells as point tuples, kept vertices, infos,
// is_valid(true)), by DeWall where the traits are provably DeWall's
// predicates on the coordinates it reads, by CGAL's own insertion otherwise.
#include <catch2/catch.hpp>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Projection_traits_3.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Projection_traits_xz_3.h>
#include <CGAL/Projection_traits_yz_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <boost/iterator/counting_iterator.hpp>
#include <boost/iterator/transform_iterator.hpp>
#include <boost/iterator/zip_iterator.hpp>

#include <algorithm>
#include <iterator>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <vector>

#include "dewall/cgal/delaunay_triangulation_2.hpp"
#include "dewall/cgal/delaunay_triangulation_3.hpp"

namespace {

using K = CGAL::Epick;
using P3 = K::Point_3;

#ifndef CGAL_LINKED_WITH_TBB
#error "dewall::dewall brings CGAL::TBB_support: CGAL_LINKED_WITH_TBB must be defined here"
#endif

template <class DT>
auto finite_cells(const DT& dt) {
  std::set<std::vector<typename DT::Point>> out;
  auto add = [&](auto c) {
    std::vector<typename DT::Point> s;
    for (int i = 0; i <= dt.dimension(); ++i) s.push_back(c->vertex(i)->point());
    std::sort(s.begin(), s.end());
    out.insert(s);
  };
  if constexpr (requires { dt.finite_cells_begin(); }) {
    for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) add(c);
  } else {
    for (auto c = dt.finite_faces_begin(); c != dt.finite_faces_end(); ++c) add(c);
  }
  return out;
}

/// The finite vertices as (point, info) pairs, or points when there is no info.
template <class DT>
auto vertices(const DT& dt) {
  if constexpr (requires { dt.finite_vertices_begin()->info(); }) {
    std::multiset<std::pair<typename DT::Point, typename DT::Vertex::Info>> out;
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) out.emplace(v->point(), v->info());
    return out;
  } else {
    std::multiset<typename DT::Point> out;
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) out.insert(v->point());
    return out;
  }
}

template <class DT>
void check_same(const DT& ours, const DT& theirs) {
  REQUIRE(ours.is_valid(true));
  CHECK(ours.dimension() == theirs.dimension());
  CHECK(vertices(ours) == vertices(theirs));
  CHECK(finite_cells(ours) == finite_cells(theirs));
}

std::vector<P3> random_points(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<P3> out;
  for (std::size_t i = 0; i < n; ++i) out.emplace_back(u(rng), u(rng), u(rng));
  return out;
}

/// Integer grid points in the plane of `axes` (every triangle cocircular: the
/// perturbation order decides), the third coordinate random.
std::vector<P3> grid_points(int axis_u, int axis_v, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<P3> out;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) {
      double c[3] = {std::uniform_real_distribution<double>(0, 1)(rng), 0, 0};
      c[2] = c[0];
      c[1] = c[0];
      c[axis_u] = i;
      c[axis_v] = j;
      out.emplace_back(c[0], c[1], c[2]);
    }
  std::shuffle(out.begin(), out.end(), rng);
  return out;
}

/// DeWall built dt: the builder's DeWall path, called directly (the result
/// equals CGAL's either way; this says which path produced it).
template <class DT, class Items>
bool dewall_applies(const Items& items, const typename DT::Geom_traits& gt = {}) {
  DT dt(gt);
  Items copy = items;  // the builder empties it
  if constexpr (requires { dt.finite_cells_begin(); })
    return dewall::cgal::detail::build_with_dewall_3(dt, copy, dewall::Options{}) != dewall::cgal::detail::Assembly::none;
  else
    return dewall::cgal::detail::build_with_dewall_2(dt, copy, dewall::Options{}) != dewall::cgal::detail::Assembly::none;
}

template <class Gt>
void check_projection(const std::vector<P3>& points, bool expect_dewall, const Gt& gt = Gt()) {
  using DT = CGAL::Delaunay_triangulation_2<Gt>;
  const DT ours = dewall::cgal::make_delaunay_triangulation_2<DT>(points.begin(), points.end(), {}, gt);
  const DT theirs(points.begin(), points.end(), gt);
  check_same(ours, theirs);
  CHECK(dewall_applies<DT>(points, gt) == expect_dewall);
}

}  // namespace

TEST_CASE("CGAL builders: projection traits give CGAL's triangulation", "[cgal][builders][traits]") {
  using namespace dewall::cgal::detail;
  STATIC_REQUIRE(Dewall_axes<CGAL::Projection_traits_xz_3<K>, 2>::axes[1] == 2);
  STATIC_REQUIRE(Dewall_axes<CGAL::Projection_traits_yz_3<K>, 2>::axes[0] == 1);
  STATIC_REQUIRE(!Dewall_axes<CGAL::Projection_traits_3<K>, 2>::known);
  STATIC_REQUIRE(!Dewall_axes<CGAL::Simple_cartesian<double>, 3>::known);  // inexact predicates
  const auto points = random_points(600, 20260601);
  SECTION("xy, random") { check_projection<CGAL::Projection_traits_xy_3<K>>(points, true); }
  SECTION("xz, random") { check_projection<CGAL::Projection_traits_xz_3<K>>(points, true); }
  SECTION("yz, random") { check_projection<CGAL::Projection_traits_yz_3<K>>(points, true); }
  SECTION("xy, cocircular grid") { check_projection<CGAL::Projection_traits_xy_3<K>>(grid_points(0, 1, 7), true); }
  SECTION("xz, cocircular grid") { check_projection<CGAL::Projection_traits_xz_3<K>>(grid_points(0, 2, 8), true); }
  SECTION("yz, cocircular grid") { check_projection<CGAL::Projection_traits_yz_3<K>>(grid_points(1, 2, 9), true); }
  SECTION("Projection_traits_3 with a normal: CGAL's construction") {
    check_projection<CGAL::Projection_traits_3<K>>(points, false, CGAL::Projection_traits_3<K>(K::Vector_3(1, 2, 3)));
  }
  SECTION("an inexact kernel: CGAL's construction") {
    using Sc = CGAL::Simple_cartesian<double>;
    using DT = CGAL::Delaunay_triangulation_3<Sc>;
    std::vector<Sc::Point_3> q;
    for (const auto& p : points) q.emplace_back(p.x(), p.y(), p.z());
    check_same(dewall::cgal::make_delaunay_triangulation_3<DT>(q), DT(q.begin(), q.end()));
    CHECK(!dewall_applies<DT>(q));
  }
}

TEST_CASE("CGAL builders: points equal under the projection keep CGAL's vertex", "[cgal][builders][traits]") {
  // As in CGAL's terrain example: (6 1 1) third, (6 1 7) seventh, one vertex
  // for Projection_traits_xy_3; CGAL keeps the one its spatial sort reaches first.
  const std::vector<P3> terrain{{1, 1, 1}, {2, 1, 2}, {6, 1, 1}, {3, 5, 4}, {5, 7, 3}, {2, 8, 5},
                                {6, 1, 7}, {8, 3, 2}, {7, 7, 6}, {4, 4, 1}, {9, 9, 2}, {1, 9, 3}};
  using Gt = CGAL::Projection_traits_xy_3<K>;
  SECTION("points") {
    using DT = CGAL::Delaunay_triangulation_2<Gt>;
    check_same(dewall::cgal::make_delaunay_triangulation_2<DT>(terrain), DT(terrain.begin(), terrain.end()));
    CHECK(!dewall_applies<DT>(terrain));
    // Equal also in z: one point, DeWall applies.
    std::vector<P3> same = terrain;
    same[6] = same[2];
    CHECK(dewall_applies<DT>(same));
    check_same(dewall::cgal::make_delaunay_triangulation_2<DT>(same), DT(same.begin(), same.end()));
  }
  SECTION("points with info") {
    using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, Gt>;
    using DT = CGAL::Delaunay_triangulation_2<Gt, CGAL::Triangulation_data_structure_2<Vb, CGAL::Triangulation_face_base_2<Gt>>>;
    std::vector<std::pair<P3, int>> items;
    for (std::size_t i = 0; i < terrain.size(); ++i) items.emplace_back(terrain[i], int(i));
    check_same(dewall::cgal::make_delaunay_triangulation_2<DT>(items), DT(items.begin(), items.end()));
  }
}

TEST_CASE("CGAL builders: every range CGAL's range insert takes", "[cgal][builders][ranges]") {
  const auto points = random_points(500, 20260602);
  std::vector<int> infos(points.size());
  std::iota(infos.begin(), infos.end(), 100);
  SECTION("3D: zip iterator of (point, info)") {
    using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
    using DT = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb, CGAL::Delaunay_triangulation_cell_base_3<K>>>;
    auto first = boost::make_zip_iterator(boost::make_tuple(points.begin(), infos.begin()));
    auto last = boost::make_zip_iterator(boost::make_tuple(points.end(), infos.end()));
    check_same(dewall::cgal::make_delaunay_triangulation_3<DT>(first, last), DT(first, last));
  }
  SECTION("2D: zip iterator of (point, info)") {
    using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
    using DT = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb, CGAL::Triangulation_face_base_2<K>>>;
    std::vector<K::Point_2> p2;
    for (const auto& p : points) p2.emplace_back(p.x(), p.y());
    auto first = boost::make_zip_iterator(boost::make_tuple(p2.begin(), infos.begin()));
    auto last = boost::make_zip_iterator(boost::make_tuple(p2.end(), infos.end()));
    check_same(dewall::cgal::make_delaunay_triangulation_2<DT>(first, last), DT(first, last));
  }
  SECTION("3D: transform iterator and input iterator of points") {
    using DT = CGAL::Delaunay_triangulation_3<K>;
    auto at = [&](std::size_t i) { return points[i]; };
    auto first = boost::make_transform_iterator(boost::counting_iterator<std::size_t>(0), at);
    auto last = boost::make_transform_iterator(boost::counting_iterator<std::size_t>(points.size()), at);
    const DT theirs(first, last);
    check_same(dewall::cgal::make_delaunay_triangulation_3<DT>(first, last), theirs);
    std::stringstream text;
    text.precision(17);
    for (const auto& p : points) text << p << '\n';
    check_same(dewall::cgal::make_delaunay_triangulation_3<DT>(std::istream_iterator<P3>(text), std::istream_iterator<P3>()),
               theirs);
  }
}

TEST_CASE("CGAL builders: a Parallel_tag triangulation with its lock data structure", "[cgal][builders][parallel]") {
  using Tds = CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_3<K>,
                                                   CGAL::Delaunay_triangulation_cell_base_3<K>, CGAL::Parallel_tag>;
  using DT = CGAL::Delaunay_triangulation_3<K, Tds>;
  const auto points = random_points(2000, 20260603);
  const auto more = random_points(2000, 20260604);
  typename DT::Lock_data_structure ours_lock(CGAL::Bbox_3(0, 0, 0, 1, 1, 1), 20);
  typename DT::Lock_data_structure theirs_lock(CGAL::Bbox_3(0, 0, 0, 1, 1, 1), 20);
  DT ours = dewall::cgal::make_delaunay_triangulation_3<DT>(points, {}, K(), &ours_lock);
  DT theirs(points.begin(), points.end(), K(), &theirs_lock);
  CHECK(ours.get_lock_data_structure() == &ours_lock);
  CHECK(dewall_applies<DT>(points));
  check_same(ours, theirs);

  // Parallel insertion (a range of more than 50 points with a lock data
  // structure), then parallel removal of every third vertex.
  ours.insert(more.begin(), more.end());
  theirs.insert(more.begin(), more.end());
  check_same(ours, theirs);
  auto every_third = [](DT& t) {
    std::map<P3, typename DT::Vertex_handle> by_point;
    for (auto v = t.finite_vertices_begin(); v != t.finite_vertices_end(); ++v) by_point.emplace(v->point(), v);
    std::vector<typename DT::Vertex_handle> out;
    std::size_t k = 0;
    for (const auto& [p, v] : by_point)
      if (k++ % 3 == 0) out.push_back(v);
    return out;
  };
  auto ours_victims = every_third(ours);
  auto theirs_victims = every_third(theirs);
  ours.remove(ours_victims.begin(), ours_victims.end());
  theirs.remove(theirs_victims.begin(), theirs_victims.end());
  check_same(ours, theirs);
}
