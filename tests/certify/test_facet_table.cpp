// The certifier's facet matching over compact records (facet_table.hpp) against
// a brute-force matching, and the certifier built on it against the certifier
// it replaced (tests/support/certify_reference.hpp): the same report — rule,
// simplices, facet, point, counts — on dewall's triangulations of uniform,
// lattice, cospherical and duplicated points in 2D–6D and on their mutants.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <random>
#include <span>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "dewall/certify/certify.hpp"
#include "dewall/certify/face_grouping.hpp"
#include "dewall/certify/facet_table.hpp"
#include "dewall/certify/spatial_order.hpp"
#include "dewall/dewall.hpp"
#include "support/certify_mutants.hpp"
#include "support/certify_reference.hpp"
#include "support/dewall_point_sets.hpp"

namespace certify = dewall::certify;
namespace kernel = dewall::kernel;
using certify::detail::Facet_record;

namespace {

template <int D>
using Rows = std::vector<std::array<std::uint32_t, D + 1>>;

// What a row is for these tests: not a proper simplex, or the sign of the
// orientation of its vertices in increasing order.
constexpr std::uint8_t row_invalid = 0, row_sorted_positive = 1;

/// The rows as the certifier stores them (encode_row).
template <int D>
Rows<D> encoded(const Rows<D>& rows, const std::vector<std::uint8_t>& status) {
  Rows<D> e(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    e[r] = status[r] == row_invalid ? certify::detail::invalid_row<D + 1>()
                                    : certify::detail::encode_row(certify::detail::sort_row(rows[r]).v,
                                                                  status[r] == row_sorted_positive);
  return e;
}

/// One facet's members as (row, apex, positive), in row order.
using Members = std::vector<std::tuple<std::size_t, std::uint32_t, bool>>;

/// The facets of the valid rows by brute force: every facet's sorted vertices
/// with its members; `positive` from the parity of (facet…, apex) against the
/// sorted row, counted by inversions.
template <int D>
std::map<std::vector<std::uint32_t>, Members> brute_force(const Rows<D>& rows, const std::vector<std::uint8_t>& status) {
  std::map<std::vector<std::uint32_t>, Members> facets;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (status[r] == row_invalid) continue;
    for (int j = 0; j <= D; ++j) {
      std::vector<std::uint32_t> f;
      for (int i = 0; i <= D; ++i)
        if (i != j) f.push_back(rows[r][static_cast<std::size_t>(i)]);
      std::sort(f.begin(), f.end());
      std::vector<std::uint32_t> tuple = f;
      tuple.push_back(rows[r][static_cast<std::size_t>(j)]);
      int inversions = 0;
      for (std::size_t a = 0; a < tuple.size(); ++a)
        for (std::size_t b = a + 1; b < tuple.size(); ++b) inversions += tuple[a] > tuple[b];
      const bool positive = (status[r] == row_sorted_positive) == (inversions % 2 == 0);
      facets[f].emplace_back(r, rows[r][static_cast<std::size_t>(j)], positive);
    }
  }
  return facets;
}

/// Sorted, the groups come in facet order; unordered (hashed, buckets small
/// enough), in any order: then they are sorted here before the comparison.
template <int D>
void check_matching(const Rows<D>& rows, const std::vector<std::uint8_t>& status, std::size_t vertex_count, bool ordered) {
  const auto expected = brute_force<D>(rows, status);
  std::vector<std::pair<std::vector<std::uint32_t>, Members>> got;
  const Rows<D> e = encoded<D>(rows, status);
  certify::detail::match_facets<D>(
      vertex_count, std::span<const std::array<std::uint32_t, D + 1>>(e),
      [&](std::size_t v, std::span<const Facet_record<D, std::uint64_t>> g) {
        std::vector<std::uint32_t> f{static_cast<std::uint32_t>(v)};
        f.insert(f.end(), g[0].rest.begin(), g[0].rest.end());
        Members m;
        for (const auto& rec : g) {
          CHECK(rec.rest == g[0].rest);
          m.emplace_back(rec.row(), rec.apex, rec.positive());
        }
        got.emplace_back(f, m);
      },
      ordered);
  if (!ordered) std::sort(got.begin(), got.end());
  // The same facets, in increasing order, with the same members in row order.
  REQUIRE(got.size() == expected.size());
  std::size_t i = 0;
  for (const auto& [f, m] : expected) {
    CHECK(got[i].first == f);
    CHECK(got[i].second == m);
    ++i;
  }
}

/// Random rows of D + 1 distinct vertices from a small pool (so facets repeat,
/// some in three rows or more), a fifth of them invalid; buckets of every
/// size, below and above what the hashed matching takes.
template <int D>
void random_matching(std::mt19937_64& rng) {
  for (std::size_t pool : {std::size_t{D + 2}, std::size_t{12}, std::size_t{40}, std::size_t{80}, std::size_t{200}}) {
    Rows<D> rows(500);
    std::vector<std::uint8_t> status(rows.size());
    for (std::size_t r = 0; r < rows.size(); ++r) {
      std::vector<std::uint32_t> v(pool);
      for (std::size_t i = 0; i < pool; ++i) v[i] = static_cast<std::uint32_t>(i);
      std::shuffle(v.begin(), v.end(), rng);
      std::copy(v.begin(), v.begin() + D + 1, rows[r].begin());
      status[r] = static_cast<std::uint8_t>(rng() % 5 == 0 ? 0 : 1 + rng() % 2);
    }
    INFO("D = " << D << ", pool " << pool);
    check_matching<D>(rows, status, pool, true);
    check_matching<D>(rows, status, pool, false);
  }
}

template <int D>
std::string dump(const certify::Report& r) {
  std::string s = "delaunay " + std::to_string(r.delaunay) + " canonical " + std::to_string(r.canonical) + " points " +
                  std::to_string(r.points) + " distinct " + std::to_string(r.distinct_points) + " simplices " +
                  std::to_string(r.simplices) + " interior " + std::to_string(r.interior_facets) + " boundary " +
                  std::to_string(r.boundary_facets) + " cospherical " + std::to_string(r.cospherical_facets) + "\n";
  for (const auto& v : r.violations) s += certify::describe(v) + "\n";
  return s;
}

/// The ways the certifier is run: in the input's numbering and renumbered, in
/// memory with a working memory so small that it takes many ranges, and
/// streaming through temporary files with a working memory so small that it
/// takes many windows; on 1 and 2 threads; each for the first violation and
/// for --all.
constexpr std::size_t certifier_variants = 16;
constexpr std::size_t every_variant = certifier_variants;

/// The certifier and the reference agree: in `variant` (one of the sixteen
/// ways above) or, with every_variant, in all of them.
template <int D>
void same_report(const std::vector<kernel::Point_d<D>>& p, const Rows<D>& t, const std::string& what,
                 std::size_t variant = every_variant) {
  INFO(what << " (D = " << D << ", " << p.size() << " points, " << t.size() << " rows)");
  using K = kernel::Filtered_kernel_d<D>;
  const std::span<const kernel::Point_d<D>> points(p);
  const std::span<const std::array<std::uint32_t, D + 1>> rows(t);
  for (bool all : {false, true}) {
    const auto wanted = [&](std::size_t v) { return variant == every_variant || variant == v + (all ? 8 : 0); };
    if (!wanted(0) && !wanted(1) && !wanted(2) && !wanted(3) && !wanted(4) && !wanted(5) && !wanted(6) && !wanted(7)) continue;
    const std::string expected = dump<D>(dewall::test::certify_reference<K>(points, rows, {.all = all, .threads = 1}));
    for (unsigned threads : {1u, 2u}) {
      const std::size_t first = threads == 1 ? 0 : 4;
      INFO("all " << all << ", threads " << threads);
      for (bool spatial : {false, true}) {
        if (!wanted(first + spatial)) continue;
        INFO("spatial order " << spatial);
        CHECK(dump<D>(certify::certify<K>(points, rows, {.all = all, .threads = threads, .spatial_order = spatial})) == expected);
      }
      if (wanted(first + 2)) {
        INFO("in memory, ranges of a few vertices, in several batches");
        CHECK(dump<D>(certify::certify<K>(points, rows, {.all = all, .threads = threads, .working_memory = 2048})) == expected);
      }
      if (!wanted(first + 3)) continue;
      INFO("streaming");
      CHECK(dump<D>(certify::certify<K>(points, rows, {.all = all, .threads = threads, .stream = true, .working_memory = 2048})) ==
            expected);
    }
  }
}

/// A triangulation and its mutants, each compared with the reference.
/// The triangulation is checked in every variant, each mutant in one of them,
/// in turn from `first_variant` (so that the calls of a test cover them all).
template <int D>
void same_reports_with_mutants(const std::vector<kernel::Point_d<D>>& p, const std::string& what, std::mt19937_64& rng,
                               std::size_t first_variant = 0) {
  const Rows<D> t = dewall::triangulate<D>(p, dewall::Options{.engine = dewall::Engine::dewall}).simplices;
  same_report<D>(p, t, what);
  std::size_t variant = first_variant;
  dewall::test::for_each_mutant<D>(p.size(), t, rng, [&](const std::string& name, const Rows<D>& m) {
    same_report<D>(p, m, what + ", " + name, variant++ % certifier_variants);
  });
}

template <int D>
void same_reports(std::size_t n, std::mt19937_64& rng) {
  // Eleven mutants a set: the four sets together take every variant in turn.
  same_reports_with_mutants<D>(dewall::test::uniform<D>(n, rng), "uniform", rng, 0);
  same_reports_with_mutants<D>(dewall::test::lattice<D>(n), "lattice", rng, 11);
  same_reports_with_mutants<D>(dewall::test::cospherical<D>(true), "cospherical with centre", rng, 22);
  auto dup = dewall::test::uniform<D>(n / 2, rng);
  for (std::size_t i = 0; i < n / 4; ++i) dup.push_back(dup[static_cast<std::size_t>(rng() % dup.size())]);
  same_reports_with_mutants<D>(dup, "with duplicates", rng, 33);
}

}  // namespace

TEST_CASE("certify facet table: the matching, sorted and hashed, equals a brute-force one, 2D-6D", "[certify][facet_table]") {
  std::mt19937_64 rng(61);
  random_matching<2>(rng);
  random_matching<3>(rng);
  random_matching<4>(rng);
  random_matching<5>(rng);
  random_matching<6>(rng);
}

TEST_CASE("certify facet table: sorting a row keeps its parity", "[certify][facet_table]") {
  std::array<std::uint32_t, 5> row{4, 1, 3, 0, 2};
  std::array<std::uint32_t, 5> sorted{0, 1, 2, 3, 4};
  std::mt19937_64 rng(5);
  for (int k = 0; k < 100; ++k) {
    std::shuffle(row.begin(), row.end(), rng);
    int inversions = 0;
    for (std::size_t a = 0; a < 5; ++a)
      for (std::size_t b = a + 1; b < 5; ++b) inversions += row[a] > row[b];
    const auto s = certify::detail::sort_row(row);
    CHECK(s.v == sorted);
    CHECK(s.odd == (inversions % 2 == 1));
  }
}

TEST_CASE("certify facet table: the same reports as the former certifier, 2D and 3D, mutants", "[certify][facet_table]") {
  std::mt19937_64 rng(6161);
  same_reports<2>(1000, rng);
  same_reports<3>(500, rng);
}

TEST_CASE("certify facet table: the same reports as the former certifier, 4D-6D, mutants", "[certify][facet_table]") {
  std::mt19937_64 rng(6162);
  same_reports<4>(120, rng);
  same_reports<5>(60, rng);
  same_reports<6>(30, rng);
}

TEST_CASE("certify facet table: the same reports over several ranges of rows and vertices", "[certify][facet_table][heavy]") {
  std::mt19937_64 rng(6163);
  // Ranges of 16384 rows and of 4096 vertices, merged in order: the
  // triangulation, then a violation in a late range, found first.
  const auto p = dewall::test::uniform<3>(10000, rng);
  Rows<3> t = dewall::triangulate<3>(p, dewall::Options{.engine = dewall::Engine::dewall}).simplices;
  same_report<3>(p, t, "uniform, several ranges");
  t.erase(t.begin() + static_cast<std::ptrdiff_t>(t.size() - 100));
  std::swap(t[t.size() - 50][0], t[t.size() - 50][1]);
  for (std::size_t variant : {0, 6, 7, 11, 13}) same_report<3>(p, t, "uniform, several ranges, a late row dropped", variant);
}

TEST_CASE("certify spatial order: a permutation, for points at the ends of the double range", "[certify][spatial_order]") {
  // Boxes whose extent overflows a double, or is a few subnormals wide: the
  // cell of every point is computed without overflow or NaN (UBSan checks the
  // conversions), and the order is a permutation that puts the points that are
  // not finite first.
  const double big = 1.7e308, tiny = 0x1p-1073;
  const std::vector<std::vector<std::array<double, 3>>> sets = {
      {{-big, 0, big}, {big, -big, 0}, {0, big, -big}, {big, big, big}, {-big, -big, -big}},
      {{0, 0, 0}, {tiny, 0, -tiny}, {-tiny, tiny, 0}, {2 * tiny, -tiny, tiny}},
      {{-big, tiny, 1}, {big, -tiny, 1}, {0, 0, 1}, {INFINITY, 0, 1}, {1, NAN, 1}},
  };
  for (const auto& set : sets) {
    const auto order = certify::detail::z_order<3>(
        std::span<const std::array<double, 3>>(set), [](const std::array<double, 3>& x) -> const std::array<double, 3>& { return x; },
        [&](std::size_t i) { return std::isfinite(set[i][0]) && std::isfinite(set[i][1]) && std::isfinite(set[i][2]); });
    std::vector<std::uint32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < sorted.size(); ++i) CHECK(sorted[i] == i);
  }
}

TEST_CASE("certify face grouping: the same groups as a brute force, among few vertices or many", "[certify][facet_table]") {
  // Rows over a small pool of vertices spread over [0, vertex_count): with
  // many more vertices than faces the buckets are the faces' own smallest
  // vertices (the boundary of a large triangulation), else one per vertex.
  std::mt19937_64 rng(62);
  for (std::size_t spread : {std::size_t{1}, std::size_t{7919}}) {
    constexpr std::size_t K = 3, pool = 40;
    const std::size_t vertex_count = pool * spread;
    std::vector<std::array<std::uint32_t, K>> rows(60);
    for (auto& r : rows) {
      std::vector<std::uint32_t> v(pool);
      for (std::size_t i = 0; i < pool; ++i) v[i] = static_cast<std::uint32_t>(i * spread);
      std::shuffle(v.begin(), v.end(), rng);
      std::copy_n(v.begin(), K, r.begin());
    }
    std::map<std::vector<std::uint32_t>, std::vector<std::pair<std::size_t, int>>> expected, found;
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int p = 0; p < static_cast<int>(K); ++p) {
        std::vector<std::uint32_t> face;
        for (int j = 0; j < static_cast<int>(K); ++j)
          if (j != p) face.push_back(rows[r][static_cast<std::size_t>(j)]);
        std::sort(face.begin(), face.end());
        expected[face].emplace_back(r, p);
      }
    std::size_t groups = 0;
    const auto collect = [&](std::span<const certify::detail::Face_ref> g) {
      ++groups;
      std::vector<std::uint32_t> face;
      for (int j = 0; j < static_cast<int>(K); ++j)
        if (j != g[0].position) face.push_back(rows[g[0].row][static_cast<std::size_t>(j)]);
      std::sort(face.begin(), face.end());
      for (const auto& f : g) found[face].emplace_back(f.row, f.position);
    };
    INFO("vertex count " << vertex_count);
    certify::detail::group_faces<K>(vertex_count, std::span<const std::array<std::uint32_t, K>>(rows), collect);
    CHECK(found == expected);
    CHECK(groups == expected.size());
    // In blocks of vertices, as the progress overload walks them.
    found.clear();
    groups = 0;
    certify::detail::group_faces<K>(vertex_count, std::span<const std::array<std::uint32_t, K>>(rows), collect, [](double) {});
    CHECK(found == expected);
    CHECK(groups == expected.size());
  }
}

TEST_CASE("certify spatial order: the same order on one thread or several", "[certify][spatial_order]") {
  // Enough points for the ranges to be keyed and counted apart, half of them
  // on a coarse lattice so that many share a cell (their input order must stay),
  // and a few that are not finite.
  std::mt19937_64 rng(63);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::array<double, 3>> p(200000);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (double& c : p[i]) c = i % 2 ? u(rng) : std::floor(4 * u(rng));
  p[7][1] = NAN;
  p[150001][2] = INFINITY;
  const auto coords = [](const std::array<double, 3>& x) -> const std::array<double, 3>& { return x; };
  const auto finite = [&](std::size_t i) { return std::isfinite(p[i][0]) && std::isfinite(p[i][1]) && std::isfinite(p[i][2]); };
  const auto serial = certify::detail::z_order<3>(std::span<const std::array<double, 3>>(p), coords, finite);
  for (std::size_t parts : {2u, 3u}) {
    const auto threads = [](std::size_t count, auto&& f) {
      std::vector<std::thread> pool;
      for (std::size_t i = 0; i < count; ++i) pool.emplace_back([&f, i] { f(i, static_cast<unsigned>(i)); });
      for (auto& t : pool) t.join();
    };
    INFO("parts " << parts);
    CHECK(certify::detail::z_order<3>(std::span<const std::array<double, 3>>(p), coords, finite, threads, parts) == serial);
  }
  std::vector<std::uint32_t> sorted = serial, every(p.size());
  std::sort(sorted.begin(), sorted.end());
  std::iota(every.begin(), every.end(), 0u);
  CHECK(sorted == every);
}

namespace {

/// The Z order's keys as bits interleaved one at a time (the definition), sorted with their indices.
template <int D>
std::vector<std::uint64_t> z_keys_by_bits(const std::vector<std::array<double, D>>& p) {
  std::array<double, D> lo, hi;
  lo.fill(INFINITY);
  hi.fill(-INFINITY);
  for (const auto& x : p)
    for (int j = 0; j < D; ++j) lo[j] = std::min(lo[j], x[j]), hi[j] = std::max(hi[j], x[j]);
  constexpr int bits = 32 / D;
  constexpr double cells = double(1u << bits);
  std::vector<std::uint64_t> keys;
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::array<std::uint32_t, D> q;
    for (int j = 0; j < D; ++j) {
      const double extent = hi[j] * 0.5 - lo[j] * 0.5;
      const double t = extent > 0 ? (p[i][j] * 0.5 - lo[j] * 0.5) / extent : 0.0;
      q[j] = static_cast<std::uint32_t>(std::min(t * cells, cells - 1));
    }
    std::uint64_t key = 0;
    for (int bit = bits - 1; bit >= 0; --bit)
      for (int j = 0; j < D; ++j) key = (key << 1) | ((q[j] >> bit) & 1u);
    keys.push_back((key << 32) | i);
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

/// Points drawn from a few, so many repeat, with −0 for +0 now and then, a
/// far point that crowds the others into a few cells when `crowded`, and
/// some not finite.
template <int D>
std::vector<std::array<double, D>> repeating_points(std::size_t n, bool crowded, std::mt19937_64& rng) {
  std::vector<std::array<double, D>> pool(1 + n / 4);
  for (auto& x : pool)
    for (auto& c : x) c = rng() % 3 == 0 ? 0.0 : double(rng() % 1000) / 1000;
  std::vector<std::array<double, D>> p;
  for (std::size_t i = 0; i < n; ++i) {
    auto x = pool[rng() % pool.size()];
    for (auto& c : x)
      if (c == 0 && rng() % 2) c = -0.0;
    if (rng() % 50 == 0) x[rng() % D] = rng() % 2 ? NAN : -INFINITY;
    p.push_back(x);
  }
  if (crowded) p.push_back({}), p.back().fill(1e12);
  return p;
}

}  // namespace

TEST_CASE("certify spatial order: keys by spread bits, and duplicates found in cells as by hashing", "[certify][spatial_order]") {
  // The keys equal the interleaving bit by bit; the first occurrences found
  // in the cells of the Z order equal kernel::first_occurrences (a hash table),
  // for sparse and crowded cells (the latter sorted), −0 and +0, excluded points.
  std::mt19937_64 rng(6169);
  const auto run = [&]<int D>(std::integral_constant<int, D>) {
    for (int round = 0; round < 20; ++round) {
      const bool crowded = round % 2;
      const auto p = repeating_points<D>(10 + rng() % 400, crowded, rng);
      const auto coords = [](const std::array<double, D>& x) -> const std::array<double, D>& { return x; };
      const auto finite = [&](std::size_t i) { return std::all_of(p[i].begin(), p[i].end(), [](double c) { return std::isfinite(c); }); };
      const auto excluded = [&](std::size_t i) { return !finite(i); };
      const auto sorted = certify::detail::z_order_keys<D>(std::span<const std::array<double, D>>(p), coords, finite);
      std::vector<std::array<double, D>> finite_points;  // the keys of the finite points, as the definition has them
      std::vector<std::uint64_t> expected_keys;
      {
        std::vector<std::size_t> index;
        for (std::size_t i = 0; i < p.size(); ++i)
          if (finite(i)) finite_points.push_back(p[i]), index.push_back(i);
        for (std::uint64_t k : z_keys_by_bits<D>(finite_points)) expected_keys.push_back((k >> 32 << 32) | index[k & 0xffffffffu]);
        for (std::size_t i = 0; i < p.size(); ++i)
          if (!finite(i)) expected_keys.push_back(i);  // key 0
        std::sort(expected_keys.begin(), expected_keys.end());
      }
      INFO("D = " << D << ", round " << round << ", " << p.size() << " points");
      CHECK(std::vector<std::uint64_t>(sorted.begin(), sorted.end()) == expected_keys);
      const auto compare = [](const std::array<double, D>& a, const std::array<double, D>& b) {
        for (int j = 0; j < D; ++j)
          if (a[j] != b[j]) return a[j] < b[j] ? kernel::SMALLER : kernel::LARGER;
        return kernel::EQUAL;
      };
      const auto by_cells = certify::detail::first_occurrences_in_z_order(std::span<const std::array<double, D>>(p),
                                                                          std::span<const std::uint64_t>(sorted), compare, excluded);
      const auto by_hash = kernel::first_occurrences(std::span<const std::array<double, D>>(p), compare, coords, excluded);
      CHECK(by_cells == by_hash);
      CHECK(std::count_if(by_cells.begin(), by_cells.end(), [&, i = std::size_t{0}](std::uint32_t f) mutable { return f != i++; }) > 0);
    }
  };
  run(std::integral_constant<int, 2>{});
  run(std::integral_constant<int, 3>{});
  run(std::integral_constant<int, 4>{});
}
