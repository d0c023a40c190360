// The certifier (certify/): correct triangulations from three independent
// builders (dewall, CGAL, Qhull) are accepted; mutants are rejected, each for
// a rule that names the damage; cospherical flips are "Delaunay, not
// canonical". Then the simplex reader and `dewall certify` on the command line.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "dewall/certify/certify.hpp"
#include "dewall/dewall.hpp"
#include "dewall/io/simplex_reader.hpp"
#include "support/dewall_point_sets.hpp"
#include "support/cgal_reference.hpp"
#include "support/cli_runner.hpp"

using dewall::kernel::Point_d;
namespace certify = dewall::certify;
namespace kernel = dewall::kernel;

namespace {

template <int D>
using Cells = std::vector<certify::Simplex_indices<D>>;

template <int D>
certify::Report run_certify(const std::vector<Point_d<D>>& p, const Cells<D>& t, bool all = false) {
  return certify::certify<kernel::Filtered_kernel_d<D>>(p, t, certify::Options{.all = all});
}

template <int D>
std::string rules_of(const certify::Report& r) {
  std::string s;
  for (const auto& v : r.violations) s += certify::describe(v) + "\n";
  return s;
}

template <int D>
void expect_canonical(const std::vector<Point_d<D>>& p, const Cells<D>& t, const std::string& what) {
  INFO(what << ": " << t.size() << " simplices");
  const auto r = run_certify<D>(p, t, true);
  INFO(rules_of<D>(r));
  CHECK(r.delaunay);
  CHECK(r.canonical);
}

/// Rejected, and (when given) for `rule` as the first violation.
template <int D>
void expect_rejected(const std::vector<Point_d<D>>& p, const Cells<D>& t, const std::string& what,
                     std::optional<certify::Rule> rule = {}) {
  INFO("mutant: " << what);
  const auto first = run_certify<D>(p, t);
  const auto all = run_certify<D>(p, t, true);
  INFO(rules_of<D>(all));
  CHECK_FALSE(first.delaunay);
  CHECK_FALSE(first.canonical);
  CHECK_FALSE(all.delaunay);
  REQUIRE(first.first_fatal() != nullptr);
  // Without --all: exactly one fatal violation; with --all the first is the same.
  CHECK(std::count_if(first.violations.begin(), first.violations.end(), [](const auto& v) { return v.fatal(); }) == 1);
  CHECK(all.first_fatal()->rule == first.first_fatal()->rule);
  if (rule) CHECK(certify::rule_name(first.first_fatal()->rule) == std::string(certify::rule_name(*rule)));
}

template <int D>
Cells<D> dewall_cells(const std::vector<Point_d<D>>& p) {
  return dewall::triangulate<D>(p, dewall::Options{.engine = dewall::Engine::dewall}).simplices;
}
template <int D>
Cells<D> cgal_cells(const std::vector<Point_d<D>>& p) {
  const auto s = dewall::test::cgal_delaunay<D>(p);
  return Cells<D>(s.begin(), s.end());
}

/// Qhull's `qdelaunay Qt i` on the points, through the reader; nullopt when
/// qdelaunay is not installed.
template <int D>
std::optional<Cells<D>> qhull_cells(const std::vector<Point_d<D>>& p) {
  if (std::system("command -v qdelaunay > /dev/null 2>&1") != 0) return std::nullopt;
  const std::string in = "certify_test_qhull_in.txt";
  {
    std::ofstream f(in);
    f.precision(17);
    f << D << "\n" << p.size() << "\n";
    for (const auto& q : p) {
      for (int j = 0; j < D; ++j) f << q[j] << (j + 1 < D ? " " : "\n");
    }
  }
  FILE* pipe = popen(("qdelaunay Qt i < " + in + " 2>/dev/null").c_str(), "r");
  REQUIRE(pipe);
  std::string out;
  char buf[4096];
  while (std::size_t got = std::fread(buf, 1, sizeof buf, pipe)) out.append(buf, got);
  REQUIRE(pclose(pipe) == 0);
  std::istringstream ss(out);
  const auto list = dewall::io::read_simplices(ss, "qdelaunay", D);
  CHECK(list.format == "qhull");
  Cells<D> t(list.table.size());
  for (std::size_t r = 0; r < t.size(); ++r)
    for (int j = 0; j <= D; ++j) t[r][j] = list.table.indices[r * (D + 1) + j];
  return t;
}

template <int D>
kernel::Sign orient(const std::vector<Point_d<D>>& p, const certify::Simplex_indices<D>& s) {
  std::array<const Point_d<D>*, D + 1> q;
  for (int i = 0; i <= D; ++i) q[i] = &p[s[i]];
  return kernel::orientation_d<D>(q);
}
template <int D>
kernel::Oriented_side in_sphere(const std::vector<Point_d<D>>& p, certify::Simplex_indices<D> s, std::uint32_t q) {
  if (orient<D>(p, s) == kernel::NEGATIVE) std::swap(s[0], s[1]);
  std::array<const Point_d<D>*, D + 2> a;
  for (int i = 0; i <= D; ++i) a[i] = &p[s[i]];
  a[D + 1] = &p[q];
  return kernel::side_of_oriented_sphere_d<D>(a);
}

/// Interior facets: sorted facet → the (simplex, opposite vertex) pairs.
template <int D>
std::map<std::array<std::uint32_t, D>, std::vector<std::pair<std::size_t, std::uint32_t>>> facets(const Cells<D>& t) {
  std::map<std::array<std::uint32_t, D>, std::vector<std::pair<std::size_t, std::uint32_t>>> m;
  for (std::size_t s = 0; s < t.size(); ++s)
    for (int i = 0; i <= D; ++i) {
      std::array<std::uint32_t, D> f;
      for (int j = 0, k = 0; j <= D; ++j)
        if (j != i) f[k++] = t[s][j];
      std::sort(f.begin(), f.end());
      m[f].push_back({s, t[s][i]});
    }
  return m;
}

template <int D>
Cells<D> without(const Cells<D>& t, const std::vector<std::size_t>& drop) {
  Cells<D> out;
  for (std::size_t s = 0; s < t.size(); ++s)
    if (std::find(drop.begin(), drop.end(), s) == drop.end()) out.push_back(t[s]);
  return out;
}

/// A 2-2 flip in 2D (cocircular or not, as asked): the other diagonal of a
/// convex quadrilateral formed by two triangles.
std::optional<Cells<2>> flip_2_2(const std::vector<Point_d<2>>& p, const Cells<2>& t, bool cocircular) {
  for (const auto& [f, sides] : facets<2>(t)) {
    if (sides.size() != 2) continue;
    const std::uint32_t a = f[0], b = f[1], c = sides[0].second, d = sides[1].second;
    const auto s1 = orient<2>(p, {c, d, a}), s2 = orient<2>(p, {c, d, b});
    if (s1 == kernel::ZERO || s1 != -s2) continue;  // not strictly convex
    if ((in_sphere<2>(p, {a, b, c}, d) == kernel::ON_ORIENTED_BOUNDARY) != cocircular) continue;
    Cells<2> out = without<2>(t, {sides[0].first, sides[1].first});
    out.push_back({c, d, a});
    out.push_back({d, c, b});
    return out;
  }
  return std::nullopt;
}

/// A 2-3 flip in 3D: two tetrahedra abc·d, abc·e whose segment de crosses the
/// triangle abc become three around the edge de.
std::optional<Cells<3>> flip_2_3(const std::vector<Point_d<3>>& p, const Cells<3>& t, bool cospherical) {
  for (const auto& [f, sides] : facets<3>(t)) {
    if (sides.size() != 2) continue;
    const std::uint32_t a = f[0], b = f[1], c = f[2], d = sides[0].second, e = sides[1].second;
    const auto o1 = orient<3>(p, {d, e, a, b}), o2 = orient<3>(p, {d, e, b, c}), o3 = orient<3>(p, {d, e, c, a});
    if (o1 == kernel::ZERO || o1 != o2 || o2 != o3) continue;
    if ((in_sphere<3>(p, {a, b, c, d}, e) == kernel::ON_ORIENTED_BOUNDARY) != cospherical) continue;
    Cells<3> out = without<3>(t, {sides[0].first, sides[1].first});
    out.push_back({d, e, a, b});
    out.push_back({d, e, b, c});
    out.push_back({d, e, c, a});
    return out;
  }
  return std::nullopt;
}

/// A 3-2 flip in 3D: the three tetrahedra around an edge de of degree 3, whose
/// link triangle abc is crossed by de, become abc·d and abc·e.
std::optional<Cells<3>> flip_3_2(const std::vector<Point_d<3>>& p, const Cells<3>& t, bool cospherical) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> around;
  for (std::size_t s = 0; s < t.size(); ++s)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        around[{std::min(t[s][i], t[s][j]), std::max(t[s][i], t[s][j])}].push_back(s);
  for (const auto& [edge, ring] : around) {
    if (ring.size() != 3) continue;
    const auto [d, e] = edge;
    std::map<std::uint32_t, int> link;
    for (std::size_t s : ring)
      for (std::uint32_t v : t[s])
        if (v != d && v != e) ++link[v];
    if (link.size() != 3) continue;  // not a closed ring: the edge is on the boundary
    auto it = link.begin();
    const std::uint32_t a = (it++)->first, b = (it++)->first, c = it->first;
    const auto o1 = orient<3>(p, {d, e, a, b}), o2 = orient<3>(p, {d, e, b, c}), o3 = orient<3>(p, {d, e, c, a});
    if (o1 == kernel::ZERO || o1 != o2 || o2 != o3) continue;
    if ((in_sphere<3>(p, {a, b, c, d}, e) == kernel::ON_ORIENTED_BOUNDARY) != cospherical) continue;
    Cells<3> out = without<3>(t, ring);
    out.push_back({a, b, c, d});
    out.push_back({a, c, b, e});
    return out;
  }
  return std::nullopt;
}

/// The generic mutants, for any dimension: each must be rejected.
template <int D>
void check_mutants(const std::vector<Point_d<D>>& p, const Cells<D>& t, std::mt19937_64& rng) {
  REQUIRE(t.size() > 4);
  std::uniform_int_distribution<std::size_t> pick(0, t.size() - 1);
  std::uniform_int_distribution<std::uint32_t> point(0, static_cast<std::uint32_t>(p.size() - 1));
  const auto present = dewall::test::as_set<D>(t);
  {
    Cells<D> m = t;
    m.erase(m.begin() + static_cast<long>(pick(rng)));
    expect_rejected<D>(p, m, "drop a simplex");
  }
  {
    Cells<D> m = t;
    m.erase(m.begin());  // the witness point's simplex
    expect_rejected<D>(p, m, "drop the first simplex");
  }
  {
    Cells<D> m = t;
    auto s = t[pick(rng)];
    std::reverse(s.begin(), s.end());
    m.push_back(s);
    expect_rejected<D>(p, m, "duplicate a simplex (other vertex order)");
  }
  {
    Cells<D> m = t;
    const std::size_t s = pick(rng);
    std::uint32_t q;
    do q = point(rng);
    while (std::find(m[s].begin(), m[s].end(), q) != m[s].end());
    m[s][std::uniform_int_distribution<int>(0, D)(rng)] = q;
    expect_rejected<D>(p, m, "replace a vertex");
  }
  {
    Cells<D> m = t;
    m[pick(rng)][0] = static_cast<std::uint32_t>(p.size());
    expect_rejected<D>(p, m, "index out of range", certify::Rule::index_out_of_range);
  }
  {
    Cells<D> m = t;
    auto& s = m[pick(rng)];
    s[1] = s[0];
    expect_rejected<D>(p, m, "repeated vertex", certify::Rule::repeated_vertex);
  }
  for (int tries = 0;; ++tries) {
    REQUIRE(tries < 1000);
    certify::Simplex_indices<D> s;
    for (auto& v : s) v = point(rng);
    auto sorted = s;
    std::sort(sorted.begin(), sorted.end());
    if (present.count(sorted) || orient<D>(p, s) == kernel::ZERO) continue;
    Cells<D> m = t;
    m.insert(m.begin() + static_cast<long>(pick(rng)), s);
    expect_rejected<D>(p, m, "add an overlapping simplex");
    break;
  }
  {
    const std::uint32_t v = t[pick(rng)][0];
    Cells<D> m;
    for (const auto& s : t)
      if (std::find(s.begin(), s.end(), v) == s.end()) m.push_back(s);
    expect_rejected<D>(p, m, "remove every simplex of point " + std::to_string(v));
  }
  {
    Cells<D> m = t;
    for (auto& s : m) std::swap(s[0], s[1]);  // every row reflected: still the same triangulation
    std::shuffle(m.begin(), m.end(), rng);
    expect_canonical<D>(p, m, "reoriented and shuffled rows");
  }
}

/// dewall's, CGAL's and Qhull's (when `with_qhull`) triangulations are canonical;
/// the mutants of dewall's are rejected.
template <int D>
void accept_and_mutate(const std::vector<Point_d<D>>& p, const std::string& name, std::mt19937_64& rng,
                       bool with_qhull) {
  INFO("point set: " << name << " (" << p.size() << " points, D = " << D << ")");
  const Cells<D> t = dewall_cells<D>(p);
  expect_canonical<D>(p, t, "dewall");
  expect_canonical<D>(p, cgal_cells<D>(p), "CGAL");
  if (with_qhull)
    if (const auto q = qhull_cells<D>(p)) expect_canonical<D>(p, *q, "Qhull qdelaunay Qt i");
  check_mutants<D>(p, t, rng);
}

}  // namespace

TEST_CASE("certify: correct triangulations accepted, mutants rejected", "[certify]") {
  const std::uint64_t seed = 20240611;
  INFO("seed = " << seed);
  std::mt19937_64 rng(seed);
  accept_and_mutate<2>(dewall::test::uniform<2>(300, rng), "uniform", rng, true);
  accept_and_mutate<2>(dewall::test::lattice_samples<2>(200, 8, rng), "lattice samples with duplicates", rng, false);
  accept_and_mutate<2>(dewall::test::cospherical<2>(true), "cocircular with centre", rng, false);
  accept_and_mutate<3>(dewall::test::uniform<3>(200, rng), "uniform", rng, true);
  accept_and_mutate<3>(dewall::test::lattice<3>(64), "lattice", rng, false);
  accept_and_mutate<3>(dewall::test::lattice_samples<3>(120, 4, rng), "lattice samples with duplicates", rng, false);
  accept_and_mutate<3>(dewall::test::cospherical<3>(false), "cospherical", rng, false);
  accept_and_mutate<3>(dewall::test::planes<3>(150, 3, rng), "parallel planes", rng, false);
  accept_and_mutate<4>(dewall::test::uniform<4>(60, rng), "uniform", rng, true);
  accept_and_mutate<4>(dewall::test::lattice<4>(81), "lattice", rng, false);
  accept_and_mutate<4>(dewall::test::cospherical<4>(true), "cospherical with centre", rng, false);
}

TEST_CASE("certify: Qhull on a 2D lattice is Delaunay, not necessarily canonical", "[certify]") {
  // Qhull resolves cocircular squares its own way (Qt triangulates each merged
  // facet); the closed-sphere test accepts any of those choices. (On a 3D grid,
  // `qdelaunay Qt` emits zero-volume tetrahedra, which certify rightly rejects.)
  const auto p = dewall::test::lattice<2>(100);
  if (const auto q = qhull_cells<2>(p)) {
    const auto r = run_certify<2>(p, *q, true);
    INFO(rules_of<2>(r));
    CHECK(r.delaunay);
    CHECK(r.cospherical_facets > 0);
  }
}

TEST_CASE("certify: a later duplicate as vertex, and a missing point", "[certify]") {
  std::vector<Point_d<2>> p{{{0, 0}}, {{1, 0}}, {{0, 1}}, {{1, 1}}, {{1, 0}}};
  const Cells<2> t = dewall_cells<2>(p);
  expect_canonical<2>(p, t, "square with a duplicate");
  Cells<2> m = t;
  for (auto& s : m)
    for (auto& v : s)
      if (v == 1) v = 4;
  expect_rejected<2>(p, m, "later copy used", certify::Rule::duplicate_point_used);
  p.push_back({{0.5, 0.5}});
  expect_rejected<2>(p, t, "centre not a vertex", certify::Rule::point_not_a_vertex);
  p.push_back({{2, 2}});
  p.erase(p.end() - 2);
  // Point 5 outside the hull and unused; no simplex reaches it.
  expect_rejected<2>(p, t, "point outside not a vertex", certify::Rule::point_not_a_vertex);
}

TEST_CASE("certify: non-convex boundary and an empty list", "[certify]") {
  // An L-shaped region triangulated without its hull: locally convex nowhere near the notch.
  std::vector<Point_d<2>> p{{{0, 0}}, {{2, 0}}, {{2, 1}}, {{1, 1}}, {{1, 2}}, {{0, 2}}};
  const Cells<2> l{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  expect_rejected<2>(p, l, "L shape", certify::Rule::boundary_not_convex);
  expect_rejected<2>(p, {}, "no simplices", certify::Rule::point_not_a_vertex);
  std::vector<Point_d<2>> nan{{{0, 0}}, {{1, 0}}, {{0, std::numeric_limits<double>::quiet_NaN()}}};
  expect_rejected<2>(nan, {{0, 1, 2}}, "NaN", certify::Rule::non_finite_point);
  // A degenerate simplex.
  std::vector<Point_d<2>> line{{{0, 0}}, {{1, 1}}, {{2, 2}}, {{0, 1}}};
  expect_rejected<2>(line, {{0, 1, 2}, {0, 2, 3}}, "collinear", certify::Rule::degenerate_simplex);
}

TEST_CASE("certify: non-Delaunay flips rejected, cospherical flips Delaunay but not canonical", "[certify]") {
  const std::uint64_t seed = 99;
  INFO("seed = " << seed);
  std::mt19937_64 rng(seed);
  const auto not_delaunay = certify::Rule::not_locally_delaunay;
  const auto delaunay_not_canonical = [](const auto& p, const auto& m, const std::string& what) {
    constexpr int D = std::decay_t<decltype(p[0])>::dimension;
    INFO(what);
    const auto r = run_certify<D>(p, m, true);
    INFO(rules_of<D>(r));
    CHECK(r.delaunay);
    CHECK_FALSE(r.canonical);
    REQUIRE(r.first_note() != nullptr);
    CHECK(r.first_note()->rule == certify::Rule::not_canonical);
    CHECK(r.cospherical_facets > 0);
  };
  {
    const auto p = dewall::test::uniform<2>(200, rng);
    const auto f = flip_2_2(p, dewall_cells<2>(p), false);
    REQUIRE(f);
    expect_rejected<2>(p, *f, "2-2 flip", not_delaunay);
  }
  {
    const auto p = dewall::test::lattice<2>(49);
    const auto t = dewall_cells<2>(p);
    CHECK(run_certify<2>(p, t).canonical);
    const auto f = flip_2_2(p, t, true);
    REQUIRE(f);
    delaunay_not_canonical(p, *f, "2-2 flip of a lattice square");
  }
  {
    const auto p = dewall::test::uniform<3>(200, rng);
    const auto t = dewall_cells<3>(p);
    const auto f23 = flip_2_3(p, t, false);
    REQUIRE(f23);
    expect_rejected<3>(p, *f23, "2-3 flip", not_delaunay);
    const auto f32 = flip_3_2(p, t, false);
    REQUIRE(f32);
    expect_rejected<3>(p, *f32, "3-2 flip", not_delaunay);
  }
  {
    // Lattices and points on one sphere have no convex cospherical pair of
    // tetrahedra in their canonical triangulation (checked: every adjacent pair is
    // non-convex), so build one: a bipyramid on a sphere of radius 5, the equator
    // triangle abc and the poles d, e. Its two triangulations, {abcd, abce} and
    // {deab, debc, deca}, are both Delaunay; exactly one is canonical.
    const std::vector<Point_d<3>> p{{{5, 0, 0}}, {{-3, 4, 0}}, {{-3, -4, 0}}, {{0, 0, 5}}, {{0, 0, -5}}};
    const auto t = dewall_cells<3>(p);
    expect_canonical<3>(p, t, "bipyramid");
    const auto f = t.size() == 2 ? flip_2_3(p, t, true) : flip_3_2(p, t, true);
    REQUIRE(f);
    delaunay_not_canonical(p, *f, t.size() == 2 ? "cospherical 2-3 flip" : "cospherical 3-2 flip");
    const auto back = f->size() == 2 ? flip_2_3(p, *f, true) : flip_3_2(p, *f, true);
    REQUIRE(back);
    expect_canonical<3>(p, *back, "flipped back");
    // The same flips inside a larger set: the bipyramid with points far outside its sphere.
    std::vector<Point_d<3>> q = p;
    for (const auto& r : dewall::test::uniform<3>(40, rng)) q.push_back({{40 * r[0] + 20, 40 * r[1] + 20, 40 * r[2] + 20}});
    const auto tq = dewall_cells<3>(q);
    expect_canonical<3>(q, tq, "bipyramid and far points");
    const auto fq = t.size() == 2 ? flip_2_3(q, tq, true) : flip_3_2(q, tq, true);
    if (fq) delaunay_not_canonical(q, *fq, "cospherical flip among far points");
  }
}

TEST_CASE("simplex reader: plain, Qhull and TetGen .ele, with errors", "[certify][io]") {
  using dewall::io::Parse_error;
  {
    std::istringstream in("# a comment\n0 1 2\n\n2 1 3  # trailing\n");
    const auto l = dewall::io::read_simplices(in, "t.txt", 2);
    CHECK(l.format == "plain");
    CHECK(l.table.indices == std::vector<std::uint32_t>{0, 1, 2, 2, 1, 3});
    CHECK(l.lines == std::vector<std::size_t>{2, 4});
  }
  {
    std::istringstream in("2\n0 1 2\n2 1 3\n");
    const auto l = dewall::io::read_simplices(in, "q.txt", 2);
    CHECK(l.format == "qhull");
    CHECK(l.table.size() == 2);
  }
  {
    std::istringstream in("2 3 0\n1 1 2 3\n2 3 2 4\n");
    const auto l = dewall::io::read_ele(in, "t.ele", 2, 1);
    CHECK(l.format == "tetgen");
    CHECK(l.table.indices == std::vector<std::uint32_t>{0, 1, 2, 2, 1, 3});
  }
  const auto error = [](const std::string& text, int d, const std::string& needle, bool ele = false) {
    std::istringstream in(text);
    INFO(text);
    try {
      if (ele) dewall::io::read_ele(in, "f", d, 1);
      else dewall::io::read_simplices(in, "f", d);
      FAIL("no Parse_error");
    } catch (const Parse_error& e) {
      CHECK_THAT(e.what(), Catch::Contains(needle));
    }
  };
  error("0 1 2\n0 1 x\n", 2, "f:2: 'x' is not a vertex index");
  error("0 1 2\n0 -1 2\n", 2, "f:2:");
  error("0 1 2\n0 1\n", 2, "f:2: expected 3 vertex indices, found 2");
  error("0 1 2 3\n", 2, "f:1: expected 3");
  error("0 1 99999999999\n", 2, "too large");
  error("3\n0 1 2\n", 2, "announces 3 facets");
  error("1\n0 1 2 3\n", 2, "non-simplicial facet");
  error("1 3 0\n1 0 2 3\n", 2, "below the first point number", true);
  error("2 3 0\n1 1 2 3\n", 2, "truncated", true);
  error("1 4 0\n1 1 2 3 4\n", 2, "vertices per simplex", true);
}

namespace {

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

}  // namespace

TEST_CASE("command line: certify", "[certify][cli]") {
  const dewall::test::Cli_in_directory cli("certify_cli_tmp");
  const auto run_cli = [&](const std::string& args) { return cli(args); };
  const std::string d = std::filesystem::absolute(cli.dir).string() + "/";
  // The 3×3 lattice square: canonical diagonals are dewall's.
  write(d + "grid.txt", "0 0\n1 0\n2 0\n0 1\n1 1\n2 1\n0 2\n1 2\n2 2\n");
  REQUIRE(run_cli("triangulate " + d + "grid.txt -o " + d + "grid.tri").status == 0);
  SECTION("canonical: exit 0, with or without --canonical") {
    auto r = run_cli("certify " + d + "grid.txt " + d + "grid.tri");
    CHECK(r.status == 0);
    CHECK(r.out.rfind("delaunay canonical:", 0) == 0);
    CHECK(run_cli("certify " + d + "grid.txt " + d + "grid.tri --canonical").status == 0);
    r = run_cli("certify " + d + "grid.txt " + d + "grid.tri --json");
    CHECK(r.status == 0);
    CHECK(r.out.find("\"delaunay\":true,\"canonical\":true") != std::string::npos);
  }
  SECTION("the other diagonal of one square: Delaunay, not canonical") {
    std::vector<Point_d<2>> p;
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) p.push_back({{double(x), double(y)}});
    const auto f = flip_2_2(p, dewall_cells<2>(p), true);
    REQUIRE(f);
    std::string text;
    for (const auto& s : *f) text += std::to_string(s[0]) + " " + std::to_string(s[1]) + " " + std::to_string(s[2]) + "\n";
    write(d + "flip.tri", text);
    auto r = run_cli("certify " + d + "grid.txt " + d + "flip.tri");
    CHECK(r.status == 0);
    CHECK(r.out.rfind("delaunay not-canonical:", 0) == 0);
    CHECK(r.out.find("[not_canonical]") != std::string::npos);
    r = run_cli("certify " + d + "grid.txt " + d + "flip.tri --canonical");
    CHECK(r.status == 1);
    r = run_cli("certify " + d + "grid.txt " + d + "flip.tri --json");
    CHECK(r.out.find("\"delaunay\":true,\"canonical\":false") != std::string::npos);
    CHECK(r.out.find("\"rule\":\"not_canonical\"") != std::string::npos);
  }
  SECTION("broken: exit 1 with the first violation and its line; --all lists more") {
    std::string tri = dewall::test::slurp(d + "grid.tri");
    write(d + "broken.tri", "# first line is a comment\n" + tri.substr(tri.find('\n') + 1) + "0 4 8\n");
    auto r = run_cli("certify " + d + "grid.txt " + d + "broken.tri");
    CHECK(r.status == 1);
    CHECK(r.out.rfind("not delaunay:", 0) == 0);
    CHECK(r.out.find("broken.tri:") != std::string::npos);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
    r = run_cli("certify " + d + "grid.txt " + d + "broken.tri --all");
    CHECK(r.status == 1);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') > 2);
    r = run_cli("certify " + d + "grid.txt " + d + "broken.tri --json");
    CHECK(r.status == 1);
    CHECK(r.out.find("\"delaunay\":false") != std::string::npos);
    CHECK(r.out.find("\"line\":") != std::string::npos);
  }
  SECTION("--stream: the same verdicts and witnesses through temporary files") {
    std::string tri = dewall::test::slurp(d + "grid.tri");
    write(d + "broken.tri", tri.substr(tri.find('\n') + 1) + "0 4 8\n");
    for (const std::string file : {"grid.tri", "broken.tri"})
      for (const std::string all : {"", " --all"}) {
        const std::string args = "certify " + d + "grid.txt " + d + file + all;
        const auto in_memory = run_cli(args), streamed = run_cli(args + " --stream --memory 1K");
        INFO(args);
        CHECK(streamed.status == in_memory.status);
        CHECK(streamed.out == in_memory.out);
      }
    REQUIRE(run_cli("generate uniform 3000 --dim 3 --seed 7 -o " + d + "u.dwpt").status == 0);
    REQUIRE(run_cli("triangulate " + d + "u.dwpt -o " + d + "u.dwsx").status == 0);
    const auto r = run_cli("certify --canonical --stream --memory 64K " + d + "u.dwpt " + d + "u.dwsx");
    CHECK(r.status == 0);
    CHECK(r.out.rfind("delaunay canonical:", 0) == 0);
    CHECK(run_cli("certify --stream --memory 0 " + d + "u.dwpt " + d + "u.dwsx").status == 2);
    CHECK(run_cli("certify --stream --memory 12Q " + d + "u.dwpt " + d + "u.dwsx").status == 2);
  }
  SECTION("TetGen .node/.ele numbered from 1") {
    write(d + "sq.node", "4 2 0 0\n1 0 0\n2 1 0\n3 0 1\n4 1 1\n");
    write(d + "sq.ele", "2 3 0\n1 3 1 2\n2 3 2 4\n");
    const auto r = run_cli("certify " + d + "sq.node " + d + "sq.ele");
    CHECK(r.status == 0);
    CHECK(r.out.rfind("delaunay canonical:", 0) == 0);
  }
  SECTION("unreadable input: exit 2 with file and line") {
    write(d + "bad.tri", "0 1 2\n0 1 z\n");
    auto r = run_cli("certify " + d + "grid.txt " + d + "bad.tri");
    CHECK(r.status == 2);
    CHECK(r.err.find("bad.tri:2:") != std::string::npos);
    CHECK(run_cli("certify " + d + "grid.txt /nonexistent.tri").status == 2);
    CHECK(run_cli("certify " + d + "grid.txt").status == 2);
    CHECK(run_cli("certify " + d + "grid.txt " + d + "grid.tri --frobnicate").status == 2);
  }
}

namespace {

/// Every field of two reports, violations in order.
void check_same_report(const certify::Report& a, const certify::Report& b) {
  CHECK(a.delaunay == b.delaunay);
  CHECK(a.canonical == b.canonical);
  CHECK(a.distinct_points == b.distinct_points);
  CHECK(a.interior_facets == b.interior_facets);
  CHECK(a.boundary_facets == b.boundary_facets);
  CHECK(a.cospherical_facets == b.cospherical_facets);
  REQUIRE(a.violations.size() == b.violations.size());
  for (std::size_t i = 0; i < a.violations.size(); ++i) {
    const auto &v = a.violations[i], &w = b.violations[i];
    CHECK((v.rule == w.rule && v.simplex == w.simplex && v.other_simplex == w.other_simplex && v.face == w.face &&
           v.point == w.point));
  }
}

/// certify with 1, 2 and 5 threads, first violation only and all of them: the same reports.
template <int D>
void check_threads_agree(const std::vector<Point_d<D>>& p, const Cells<D>& t) {
  for (bool all : {false, true}) {
    const auto one = certify::certify<dewall::kernel::Filtered_kernel_d<D>>(p, t, {.all = all, .threads = 1});
    for (unsigned threads : {2u, 5u})
      check_same_report(one, certify::certify<dewall::kernel::Filtered_kernel_d<D>>(p, t, {.all = all, .threads = threads}));
  }
}

}  // namespace

TEST_CASE("certify: the same report for every number of threads", "[certify][threads]") {
  // Large enough for several ranges of rows (16384 each) and of facet buckets
  // (4096 points each), with violations in several of them; small enough for
  // the sanitizer build (a minute at -O0 for twice these sizes).
  std::mt19937_64 rng(31);
  const auto points = dewall::test::uniform<3>(10000, rng);
  Cells<3> t = dewall_cells<3>(points);
  check_threads_agree<3>(points, t);
  // A lattice: cospherical facets everywhere, counted and noted alike.
  const auto grid = dewall::test::lattice<3>(9261);  // 21^3
  Cells<3> g = dewall_cells<3>(grid);
  check_threads_agree<3>(grid, g);
  // Mutants spread over the list: rows dropped (holes), a vertex replaced (a
  // facet of three simplices, sides crossed), a row repeated, an index out of range.
  for (std::size_t k = 1; k <= 5; ++k) t.erase(t.begin() + static_cast<std::ptrdiff_t>(k * t.size() / 7));
  t[t.size() / 3][0] = t[2 * t.size() / 3][0];
  t.push_back(t[t.size() / 2]);
  t[t.size() - 10][2] = static_cast<std::uint32_t>(points.size() + 3);
  CHECK(certify::certify<dewall::kernel::Filtered_kernel_d<3>>(points, t, {.all = true}).violations.size() >= 5);
  check_threads_agree<3>(points, t);
  // The lattice's rows in reverse order: the ranges see other rows, the report is the same.
  std::reverse(g.begin(), g.end());
  check_threads_agree<3>(grid, g);
}
