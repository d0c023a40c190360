// certify_share and merge_shares: the reports of a certification split into
// 1 to 4 shares, merged (in any order), equal certify()'s report, on dewall's
// triangulations and their mutants, for the first violation and for --all, in
// the certifier's numbering and the input's, in memory and streaming.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "dewall/certify/certify.hpp"
#include "dewall/dewall.hpp"
#include "support/certify_mutants.hpp"
#include "support/dewall_point_sets.hpp"

namespace certify = dewall::certify;
namespace kernel = dewall::kernel;

namespace {

template <int D>
using Rows = std::vector<std::array<std::uint32_t, D + 1>>;

/// What a report says; its counts too when the walk went through every
/// facet (Delaunay, or --all): else they count as far as the walk went.
std::string dump(const certify::Report& r, bool all) {
  std::string s = "delaunay " + std::to_string(r.delaunay) + " canonical " + std::to_string(r.canonical) + " points " +
                  std::to_string(r.points) + " distinct " + std::to_string(r.distinct_points) + " simplices " +
                  std::to_string(r.simplices) + "\n";
  if (r.delaunay || all)
    s += "interior " + std::to_string(r.interior_facets) + " boundary " + std::to_string(r.boundary_facets) +
         " cospherical " + std::to_string(r.cospherical_facets) + "\n";
  for (const auto& v : r.violations) s += certify::describe(v) + "\n";
  return s;
}

/// certify() and the merged shares agree, for 1 to 4 shares.
template <int D>
void same_merged_report(const std::vector<kernel::Point_d<D>>& p, const Rows<D>& t, const std::string& what,
                        std::mt19937_64& rng) {
  using K = kernel::Filtered_kernel_d<D>;
  const std::span<const kernel::Point_d<D>> points(p);
  const std::span<const std::array<std::uint32_t, D + 1>> rows(t);
  const std::vector<certify::Options> variants = {
      {.threads = 1},
      {.threads = 1, .spatial_order = false},
      {.threads = 2, .working_memory = 2048},
      {.threads = 1, .stream = true, .working_memory = 2048},
  };
  for (bool all : {false, true})
    for (std::size_t k = 0; k < variants.size(); ++k) {
      certify::Options options = variants[k];
      options.all = all;
      INFO(what << " (D = " << D << ", " << p.size() << " points, " << t.size() << " rows), all " << all << ", variant " << k);
      const std::string expected = dump(certify::certify<K>(points, rows, options), all);
      for (std::size_t parts = 1; parts <= 4; ++parts) {
        INFO(parts << " shares");
        std::vector<certify::Share_report<D>> shares;
        for (std::size_t part = 0; part < parts; ++part) {
          certify::Span_source<D> source(rows);
          shares.push_back(certify::certify_share<K>(points, source, {part, parts}, options));
        }
        std::shuffle(shares.begin(), shares.end(), rng);
        CHECK(dump(certify::merge_shares<K>(points, std::span<const certify::Share_report<D>>(shares), options), all) == expected);
      }
    }
}

template <int D>
void same_merged_reports_with_mutants(const std::vector<kernel::Point_d<D>>& p, const std::string& what, std::mt19937_64& rng) {
  const Rows<D> t = dewall::triangulate<D>(p, dewall::Options{.engine = dewall::Engine::dewall}).simplices;
  same_merged_report<D>(p, t, what, rng);
  dewall::test::for_each_mutant<D>(p.size(), t, rng, [&](const std::string& name, const Rows<D>& m) {
    same_merged_report<D>(p, m, what + ", " + name, rng);
  });
  // Points that are not finite, in two shares' parts, and a later duplicate used.
  std::vector<kernel::Point_d<D>> q = p;
  q[p.size() / 3][0] = NAN;
  q[p.size() / 2][D - 1] = INFINITY;
  same_merged_report<D>(q, t, what + ", two points not finite", rng);
  q = p;
  q.push_back(q[t[t.size() / 2][0]]);
  Rows<D> u = t;
  u[t.size() / 2][0] = static_cast<std::uint32_t>(p.size());
  same_merged_report<D>(q, u, what + ", a later duplicate used", rng);
}

/// A k × k grid of unit squares, each cut along a random diagonal: Delaunay,
/// with many cospherical facets resolved against the perturbation (notes).
std::pair<std::vector<kernel::Point_d<2>>, Rows<2>> random_diagonals(std::uint32_t k, std::mt19937_64& rng) {
  std::vector<kernel::Point_d<2>> p;
  for (std::uint32_t i = 0; i <= k; ++i)
    for (std::uint32_t j = 0; j <= k; ++j) p.push_back({double(i), double(j)});
  Rows<2> t;
  for (std::uint32_t i = 0; i < k; ++i)
    for (std::uint32_t j = 0; j < k; ++j) {
      const std::uint32_t a = i * (k + 1) + j, b = a + k + 1, c = a + 1, d = b + 1;
      if (rng() % 2) t.insert(t.end(), {{a, b, d}, {a, d, c}});
      else t.insert(t.end(), {{a, b, c}, {b, d, c}});
    }
  std::shuffle(t.begin(), t.end(), rng);
  return {p, t};
}

}  // namespace

TEST_CASE("certify shares: merged, the report of certify, with notes, mutants", "[certify][shares]") {
  std::mt19937_64 rng(6166);
  for (int round = 0; round < 3; ++round) {
    const auto [p, t] = random_diagonals(12, rng);
    same_merged_report<2>(p, t, "random diagonals", rng);
    dewall::test::for_each_mutant<2>(p.size(), t, rng, [&](const std::string& name, const Rows<2>& m) {
      same_merged_report<2>(p, m, "random diagonals, " + name, rng);
    });
  }
}

TEST_CASE("certify shares: merged, the report of certify, 2D, mutants", "[certify][shares]") {
  std::mt19937_64 rng(6164);
  same_merged_reports_with_mutants<2>(dewall::test::uniform<2>(300, rng), "uniform", rng);
  same_merged_reports_with_mutants<2>(dewall::test::lattice<2>(200), "lattice", rng);
}

TEST_CASE("certify shares: merged, the report of certify, 3D, mutants", "[certify][shares]") {
  std::mt19937_64 rng(6167);
  same_merged_reports_with_mutants<3>(dewall::test::uniform<3>(200, rng), "uniform", rng);
  same_merged_reports_with_mutants<3>(dewall::test::cospherical<3>(true), "cospherical with centre", rng);
  auto dup = dewall::test::uniform<3>(120, rng);
  for (std::size_t i = 0; i < 40; ++i) dup.push_back(dup[static_cast<std::size_t>(rng() % dup.size())]);
  same_merged_reports_with_mutants<3>(dup, "with duplicates", rng);
}

TEST_CASE("certify shares: merged, the report of certify, 4D, mutants", "[certify][shares]") {
  std::mt19937_64 rng(6165);
  same_merged_reports_with_mutants<4>(dewall::test::lattice<4>(81), "lattice", rng);
  same_merged_reports_with_mutants<4>(dewall::test::uniform<4>(80, rng), "uniform", rng);
}

TEST_CASE("certify shares: a share out of range is refused", "[certify][shares]") {
  const std::vector<kernel::Point_d<2>> p = {{0, 0}, {1, 0}, {0, 1}};
  const Rows<2> t = {{0, 1, 2}};
  certify::Span_source<2> source{std::span<const std::array<std::uint32_t, 3>>(t)};
  CHECK_THROWS_AS(certify::certify_share<kernel::Filtered_kernel_d<2>>(std::span<const kernel::Point_d<2>>(p), source, {2, 2}),
                  std::invalid_argument);
  CHECK_THROWS_AS(certify::merge_shares<kernel::Filtered_kernel_d<2>>(std::span<const kernel::Point_d<2>>(p), {}),
                  std::invalid_argument);
}

TEST_CASE("certify shares: a missing, repeated or differently made share is refused", "[certify][shares]") {
  // A share missing could hide the only violation (a flipped edge here): the
  // merge must refuse anything but every part once, made the same way.
  using K = kernel::Filtered_kernel_d<2>;
  std::mt19937_64 rng(6164);
  const auto p = dewall::test::uniform<2>(200, rng);
  const Rows<2> t = dewall::triangulate<2>(p).simplices;
  const std::span<const kernel::Point_d<2>> points(p);
  const auto share = [&](std::size_t part, std::size_t parts, bool stream) {
    certify::Span_source<2> source{std::span<const std::array<std::uint32_t, 3>>(t)};
    return certify::certify_share<K>(points, source, {part, parts}, {.stream = stream, .working_memory = stream ? std::size_t{4096} : std::size_t{0}});
  };
  using Shares = std::vector<certify::Share_report<2>>;
  const auto merged = [&](const Shares& s) { return certify::merge_shares<K>(points, std::span<const certify::Share_report<2>>(s)); };
  CHECK(merged(Shares{share(0, 3, false), share(2, 3, false), share(1, 3, false)}).delaunay);
  CHECK_THROWS_AS(merged(Shares{share(0, 3, false), share(1, 3, false)}), std::invalid_argument);
  CHECK_THROWS_AS(merged(Shares{share(0, 2, false), share(0, 2, false)}), std::invalid_argument);
  CHECK_THROWS_AS(merged(Shares{share(0, 2, false), share(1, 3, false)}), std::invalid_argument);
  // One share streaming (vertices in input numbers), the other in Z order.
  CHECK_THROWS_AS(merged(Shares{share(0, 2, true), share(1, 2, false)}), std::invalid_argument);
  CHECK(merged(Shares{share(0, 2, true), share(1, 2, true)}).delaunay);
}

TEST_CASE("certify shares: the rows' screen keeps what the plain test keeps", "[certify][shares]") {
  // Random rows, some with indices out of range, against the plain test of
  // each row: a vertex in the set, or an index out of range in a row the share reports.
  std::mt19937_64 rng(6168);
  for (int round = 0; round < 200; ++round) {
    const std::size_t n = 1 + rng() % 300, parts = 1 + rng() % 4, part = rng() % parts, r0 = rng() % 1000;
    std::vector<bool> plain(n);
    dewall::certify::detail::Vertex_set mine(n);
    const std::uint64_t density = rng() % 5;  // of 4: none to all
    for (std::size_t v = 0; v < n; ++v)
      if (rng() % 4 < density) plain[v] = true, mine.insert(v);
    for (std::size_t v = 0; v < n + 70; ++v) REQUIRE(mine.contains(v) == (v < n && plain[v]));
    std::vector<std::array<std::uint32_t, 4>> rows(rng() % 200);
    for (auto& c : rows)
      for (auto& v : c) v = rng() % 16 == 0 ? static_cast<std::uint32_t>(n + rng() % 3 * 1000) : static_cast<std::uint32_t>(rng() % n);
    if (!rows.empty() && round % 2) rows[rng() % rows.size()][rng() % 4] = ~std::uint32_t{0};
    const std::size_t a = rows.empty() ? 0 : rng() % rows.size(), b = a + (rows.size() > a ? rng() % (rows.size() - a + 1) : 0);
    std::vector<std::uint32_t> expected = {7}, screened = {7};  // appended after what is there
    for (std::size_t i = a; i < b; ++i) {
      const bool outside = std::any_of(rows[i].begin(), rows[i].end(), [&](std::uint32_t v) { return v >= n; });
      const bool any = std::any_of(rows[i].begin(), rows[i].end(), [&](std::uint32_t v) { return v < n && plain[v]; });
      if (outside ? (r0 + i) % parts == part : any) expected.push_back(static_cast<std::uint32_t>(i));
    }
    dewall::certify::detail::screen_rows<4>(std::span<const std::array<std::uint32_t, 4>>(rows), a, b, r0, mine, part, parts, screened);
    INFO("round " << round << ", " << n << " points, rows " << a << " to " << b);
    CHECK(screened == expected);
  }
}
