// The search's structures, each on its own: the kd-tree against brute force,
// and the two floating-point pruning tests of a search (a box misses the ball
// of a sphere; a box holds no point on the outer side of a face) against exact
// GMP evaluation, on random, near-degenerate and extreme inputs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "dewall/detail/walls/active_face_list.hpp"
#include "dewall/detail/walls/face_side_filter.hpp"
#include "dewall/detail/walls/kd_tree.hpp"
#include "dewall/detail/walls/point_set.hpp"
#include "dewall/detail/walls/simplex_sphere.hpp"
#include "dewall/io/point_generators.hpp"
#include "support/gmp_reference.hpp"

using namespace dewall;
using detail::Coords;

namespace {

template <int D>
std::vector<Coords<D>> generated(io::Point_kind kind, std::size_t n, std::uint64_t seed) {
  const io::Point_table table = io::generate_points(kind, n, D, seed);
  std::vector<Coords<D>> c(table.coordinates.size() / D);
  for (std::size_t i = 0; i < c.size(); ++i)
    for (int j = 0; j < D; ++j) c[i][j] = table.coordinates[i * D + static_cast<std::size_t>(j)];
  return c;
}

template <int D>
void check_tree(const std::vector<Coords<D>>& coords, std::size_t leaf_size, int quickselect_rounds = -1) {
  INFO("n = " << coords.size() << ", leaf size " << leaf_size << ", quickselect rounds " << quickselect_rounds);
  std::vector<Coords<D>> at = coords;  // by position once the tree is built
  std::vector<detail::Index> order(coords.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<detail::Index>(i);
  const detail::Kd_tree<D> tree(at, order, leaf_size, quickselect_rounds);
  // The ids moved with their coordinates, and are a permutation.
  for (std::size_t p = 0; p < order.size(); ++p) REQUIRE(at[p] == coords[order[p]]);
  std::vector<detail::Index> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i) REQUIRE(sorted[i] == i);
  std::size_t leaves = 0;
  std::vector<int> leaf_hits(coords.size(), 0);
  // The order a node splits in: along its box's widest axis, ties broken by the next axes.
  const auto before = [](const Coords<D>& p, const Coords<D>& q, int axis) {
    for (int k = 0; k < D; ++k) {
      const int j = (axis + k) % D;
      if (p[j] != q[j]) return p[j] < q[j];
    }
    return false;
  };
  for (detail::Index node = 0; node < tree.node_count(); ++node) {
    const auto& n = tree.node(node);
    REQUIRE(n.begin < n.end);
    // The box is the tight bounding box of the node's points.
    Coords<D> lo = at[n.begin], hi = lo;
    for (detail::Index p = n.begin; p < n.end; ++p)
      for (int j = 0; j < D; ++j) {
        lo[j] = std::min(lo[j], at[p][j]);
        hi[j] = std::max(hi[j], at[p][j]);
      }
    CHECK(n.lo == lo);
    CHECK(n.hi == hi);
    if (n.is_leaf()) {
      ++leaves;
      CHECK((n.end - n.begin <= leaf_size || lo == hi));
      for (detail::Index p = n.begin; p < n.end; ++p) {
        ++leaf_hits[p];
        CHECK(tree.leaf_of(p) == node);
      }
    } else {
      // The children split the range in two at its median, and know their parent.
      const auto& a = tree.node(n.first_child);
      const auto& b = tree.node(n.first_child + 1);
      CHECK(a.begin == n.begin);
      CHECK(a.end == b.begin);
      CHECK(b.end == n.end);
      CHECK(a.end == n.begin + (n.end - n.begin) / 2);
      CHECK(a.parent == node);
      CHECK(b.parent == node);
      int axis = 0;
      for (int j = 1; j < D; ++j)
        if (n.hi[j] - n.lo[j] > n.hi[axis] - n.lo[axis]) axis = j;
      detail::Index largest_left = a.begin, smallest_right = b.begin;
      for (detail::Index p = a.begin; p < a.end; ++p)
        if (before(at[largest_left], at[p], axis)) largest_left = p;
      for (detail::Index p = b.begin; p < b.end; ++p)
        if (before(at[p], at[smallest_right], axis)) smallest_right = p;
      CHECK_FALSE(before(at[smallest_right], at[largest_left], axis));
    }
  }
  CHECK(leaves == tree.leaf_count());
  CHECK(std::all_of(leaf_hits.begin(), leaf_hits.end(), [](int h) { return h == 1; }));
}

template <int D>
kernel::Point_d<D> as_point(const Coords<D>& c) {
  kernel::Point_d<D> p;
  for (int j = 0; j < D; ++j) p[j] = c[j];
  return p;
}

/// Points of the box [lo, hi] to check a "nothing in this box" claim on: its
/// corners (all of them, D ≤ 4), random points, and the point of the box
/// nearest to `target` (where a ball would reach first).
template <int D, class Rng>
std::vector<Coords<D>> witnesses(const Coords<D>& lo, const Coords<D>& hi, const Coords<D>& target, Rng& rng) {
  std::vector<Coords<D>> w;
  for (unsigned mask = 0; mask < (1u << D); ++mask) {
    Coords<D> c;
    for (int j = 0; j < D; ++j) c[j] = (mask >> j) & 1 ? hi[j] : lo[j];
    w.push_back(c);
  }
  Coords<D> nearest;
  for (int j = 0; j < D; ++j) nearest[j] = std::clamp(target[j], lo[j], hi[j]);
  w.push_back(nearest);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 8; ++k) {
    Coords<D> c;
    for (int j = 0; j < D; ++j) c[j] = std::clamp(lo[j] + u(rng) * (hi[j] - lo[j]), lo[j], hi[j]);
    w.push_back(c);
  }
  return w;
}

/// A random simplex of one of several kinds: plain, nearly flat, tiny or huge,
/// far from the origin.
template <int D, class Rng>
std::array<Coords<D>, D + 1> random_simplex(Rng& rng, int kind) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::array<Coords<D>, D + 1> s;
  for (auto& p : s)
    for (double& v : p) v = u(rng);
  if (kind == 1)  // nearly flat: a huge, barely bounded sphere
    for (int i = 0; i <= D; ++i) s[i][D - 1] = 1e-9 * u(rng);
  const double scale = kind == 2 ? 0x1p-40 : kind == 3 ? 0x1p40 : 1.0;
  const double offset = kind == 4 ? 1e6 : 0.0;
  for (auto& p : s)
    for (double& v : p) v = v * scale + offset;
  return s;
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("kd-tree: ranges, tight boxes and leaves against brute force", "[search][tree]", ((int D), D), 2,
                       3, 4) {
  for (const auto kind : {io::Point_kind::uniform, io::Point_kind::bubbles, io::Point_kind::grid,
                          io::Point_kind::sphere, io::Point_kind::planes})
    for (const std::size_t leaf : {std::size_t{1}, std::size_t{3}, std::size_t{8}}) {
      INFO("kind " << io::point_kind_name(kind));
      check_tree<D>(generated<D>(kind, 700, 17), leaf);
    }
  // Equal coordinates: duplicates of approximate coordinates end in one leaf.
  std::vector<Coords<D>> same(40, Coords<D>{});
  same.push_back(Coords<D>{});
  same.back()[0] = 1;
  check_tree<D>(same, 4);
  check_tree<D>(std::vector<Coords<D>>(1, Coords<D>{}), 8);
  // The median selections: presorted, reversed, few distinct values; each
  // also with the quickselect's fallback (std::nth_element on a copy) forced
  // after 0 and 1 rounds.
  std::vector<Coords<D>> sorted(3000), reversed, few(3000);
  for (std::size_t i = 0; i < sorted.size(); ++i)
    for (int j = 0; j < D; ++j) {
      sorted[i][j] = static_cast<double>(i) * (j + 1);
      few[i][j] = static_cast<double>((i * 7 + static_cast<std::size_t>(j)) % 5);
    }
  reversed.assign(sorted.rbegin(), sorted.rend());
  for (const auto* points : {&sorted, &reversed, &few})
    for (const int rounds : {-1, 0, 1}) check_tree<D>(*points, 8, rounds);
  check_tree<D>(generated<D>(io::Point_kind::uniform, 700, 18), 3, 0);
}

TEMPLATE_TEST_CASE_SIG("the ball test never drops a box that meets the closed ball (GMP)", "[search][gmp][heavy]", ((int D), D),
                       2, 3, 4) {
  std::mt19937_64 rng(20261123 + D);
  std::uniform_real_distribution<double> u(-1, 1);
  std::size_t pruned = 0, checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int kind = trial % 5;
    auto s = random_simplex<D>(rng, kind);
    std::array<kernel::Point_d<D>, D + 1> p;
    for (int i = 0; i <= D; ++i) p[i] = as_point<D>(s[i]);
    if (test::gmp_orientation<D>(p) == kernel::NEGATIVE) {
      std::swap(s[0], s[1]);
      std::swap(p[0], p[1]);
    }
    std::array<const Coords<D>*, D + 1> refs;
    for (int i = 0; i <= D; ++i) refs[i] = &s[i];
    const detail::Simplex_sphere<D> sphere(refs);
    const auto& ball = sphere.enclosing_box();
    if (!ball.bounded) continue;
    Coords<D> centre;
    for (int j = 0; j < D; ++j) centre[j] = 0.5 * (ball.centre_lo[j] + ball.centre_hi[j]);
    const double radius = 0.5 * (ball.hi[0] - ball.lo[0]);
    for (int b = 0; b < 6; ++b) {
      // Boxes about the sphere: some inside, some just outside, some far.
      Coords<D> lo, hi;
      const double reach = radius * (b < 3 ? 1.0 + 0.05 * b : 0.5 + b);
      for (int j = 0; j < D; ++j) {
        const double a = centre[j] + reach * u(rng), w = radius * 0.3 * std::fabs(u(rng));
        lo[j] = a;
        hi[j] = a + w;
      }
      if (ball.may_meet(lo, hi)) continue;
      ++pruned;
      for (const auto& x : witnesses<D>(lo, hi, centre, rng)) {
        ++checked;
        // Strictly outside the closed ball: the unperturbed exact predicate.
        REQUIRE(test::gmp_side_of_oriented_sphere<D>(p, as_point<D>(x)) == kernel::ON_NEGATIVE_SIDE);
      }
    }
  }
  CHECK(pruned > 1000);  // the test prunes, so it is tested
  CHECK(checked > 10 * pruned);
}

TEMPLATE_TEST_CASE_SIG("the outer-side test never drops a box holding an outer point (GMP)", "[search][gmp]",
                       ((int D), D), 2, 3, 4) {
  std::mt19937_64 rng(20261124 + D);
  std::uniform_real_distribution<double> u(-1, 1);
  std::size_t pruned = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int kind = trial % 5;
    const auto s = random_simplex<D>(rng, kind);
    std::array<const Coords<D>*, D> face;
    for (int i = 0; i < D; ++i) face[i] = &s[i];
    // The region of all queries: the simplex's bounding box, widened.
    Coords<D> lo = s[0], hi = s[0];
    for (const auto& x : s)
      for (int j = 0; j < D; ++j) {
        lo[j] = std::min(lo[j], x[j]);
        hi[j] = std::max(hi[j], x[j]);
      }
    for (int j = 0; j < D; ++j) {
      const double w = hi[j] - lo[j];
      lo[j] -= w;
      hi[j] += w;
    }
    const detail::Face_side_filter<D> filter(face, lo, hi);
    for (int b = 0; b < 8; ++b) {
      // A sub-box of the region; some thin ones lying on the face's hyperplane's
      // neighbourhood (a face vertex as a corner).
      Coords<D> blo, bhi;
      std::uniform_real_distribution<double> t(0, 1);
      for (int j = 0; j < D; ++j) {
        double a = lo[j] + t(rng) * (hi[j] - lo[j]), c = lo[j] + t(rng) * (hi[j] - lo[j]);
        if (b == 0) a = c = s[0][j];
        blo[j] = std::min(a, c);
        bhi[j] = std::max(a, c);
      }
      if (filter.box_may_hold_outer(blo, bhi)) continue;
      ++pruned;
      for (const auto& x : witnesses<D>(blo, bhi, s[D], rng)) {
        std::array<kernel::Point_d<D>, D + 1> p;
        for (int i = 0; i < D; ++i) p[i] = as_point<D>(s[i]);
        p[D] = as_point<D>(x);
        REQUIRE(test::gmp_orientation<D>(p) != kernel::POSITIVE);
      }
    }
  }
  CHECK(pruned > 1000);
}

TEMPLATE_TEST_CASE_SIG("clipping to the outer side keeps every outer point, and nothing for a lattice's side (GMP)",
                       "[search][gmp]", ((int D), D), 2, 3, 4) {
  std::mt19937_64 rng(20261125 + D);
  const Coords<D> lo{}, hi = [] {
    Coords<D> h;
    h.fill(1.0);
    return h;
  }();
  std::uniform_real_distribution<double> u(0, 1);
  // Random faces, some axis-aligned with integer-like coordinates, some nearly so.
  std::size_t outer_points = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::array<Coords<D>, D> s;
    const int kind = trial % 3;
    for (auto& p : s)
      for (int j = 0; j < D; ++j) p[j] = kind == 0 ? u(rng) : std::floor(u(rng) * 8) / 8;
    if (kind > 0)
      for (auto& p : s) p[D - 1] = kind == 1 ? 0.25 : 0.25 + 1e-17 * u(rng);  // on (or next to) a lattice plane
    std::array<const Coords<D>*, D> face;
    for (int i = 0; i < D; ++i) face[i] = &s[i];
    const detail::Face_side_filter<D> filter(face, lo, hi);
    Coords<D> clo = lo, chi = hi;
    const bool any = filter.clip_to_outer_side(clo, chi);
    for (int k = 0; k < 40; ++k) {
      Coords<D> x;
      for (int j = 0; j < D; ++j) x[j] = kind == 0 ? u(rng) : std::floor(u(rng) * 8) / 8;
      if (k == 0) x = s[0], x[D - 1] = 0.25;  // a point on the face's plane
      std::array<kernel::Point_d<D>, D + 1> p;
      for (int i = 0; i < D; ++i) p[i] = as_point<D>(s[i]);
      p[D] = as_point<D>(x);
      if (test::gmp_orientation<D>(p) != kernel::POSITIVE) continue;
      ++outer_points;
      REQUIRE(any);
      for (int j = 0; j < D; ++j) REQUIRE((clo[j] <= x[j] && x[j] <= chi[j]));
    }
  }
  CHECK(outer_points > 10000);

  // A face in the plane x_{D-1} = 0 (the box's side), outer side below it: nothing to scan.
  std::array<Coords<D>, D> side{};
  for (int i = 1; i < D; ++i) side[i][i - 1] = 1.0 / 8;
  std::array<const Coords<D>*, D> face;
  for (int i = 0; i < D; ++i) face[i] = &side[i];
  for (const bool flip : {false, true}) {
    if (flip) std::swap(face[0], face[1]);
    const detail::Face_side_filter<D> filter(face, lo, hi);
    std::array<kernel::Point_d<D>, D + 1> p;
    for (int i = 0; i < D; ++i) p[i] = as_point<D>(*face[i]);
    p[D] = as_point<D>(hi);
    const bool inside_is_outer = test::gmp_orientation<D>(p) == kernel::POSITIVE;
    Coords<D> clo = lo, chi = hi;
    CHECK(filter.clip_to_outer_side(clo, chi) == inside_is_outer);
  }
}

TEMPLATE_TEST_CASE_SIG("Active_face_list: the paper's Update and pop against a map", "[afl]", ((int D), D), 2, 3, 6) {
  // Faces over a small vertex pool, so that faces recur (in any vertex order,
  // as the two simplices on a face give it), through several rehashes.
  std::mt19937_64 rng(20261125 + D);
  std::uniform_int_distribution<detail::Index> vertex(0, 3 * D + 2);
  std::uniform_int_distribution<int> action(0, 3);
  detail::Active_face_list<D> afl;
  std::map<detail::Face<D>, detail::Face<D>> model;  // key (sorted) -> the face as first inserted
  const auto random_face = [&] {
    detail::Face<D> f;
    for (int i = 0; i < D; ++i) {
      do f[i] = vertex(rng);
      while (std::find(f.begin(), f.begin() + i, f[i]) != f.begin() + i);
    }
    return f;
  };
  for (int step = 0; step < 20000; ++step) {
    if (action(rng) == 0 && !model.empty()) {
      REQUIRE(!afl.empty());
      const detail::Face<D> f = afl.pop();
      const auto it = model.find(detail::face_key<D>(f));
      REQUIRE(it != model.end());
      CHECK(it->second == f);  // the orientation it was inserted with
      model.erase(it);
    } else {
      const detail::Face<D> f = random_face();
      afl.update(f);
      if (model.find(detail::face_key<D>(f)) == model.end()) model.emplace(detail::face_key<D>(f), f);
      else model.erase(detail::face_key<D>(f));
    }
    REQUIRE(afl.empty() == model.empty());
    if (step % 97 == 0) {  // a copy drained: exactly the model's faces, each once, as first inserted
      detail::Active_face_list<D> copy = afl;
      std::map<detail::Face<D>, detail::Face<D>> drained;
      while (!copy.empty()) {
        const detail::Face<D> f = copy.pop();
        REQUIRE(drained.emplace(detail::face_key<D>(f), f).second);
      }
      REQUIRE(drained == model);
    }
  }
  while (!model.empty()) {  // every face left comes out once
    const detail::Face<D> f = afl.pop();
    REQUIRE(model.erase(detail::face_key<D>(f)) == 1);
  }
  CHECK(afl.empty());
}

TEST_CASE("Point_set: the project's kernel reads its own scaled copies and gives the input back bit for bit",
          "[search][point-set]") {
  // Coordinates of every magnitude the scaling keeps exact (subnormal
  // products included), negative zeros, and a duplicate: the point set
  // scales them by one power of two; restore_input must give each distinct
  // point back exactly, the duplicate (not in the distinct list) as NaN.
  using K = dewall::kernel::Filtered_kernel_d<3>;
  static_assert(!dewall::detail::Point_set<K>::reads_input);
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (const double scale : {1.0, 3.0, 0x1.8p-601, 0x1p-1030, 0x1.4p700}) {
    std::vector<dewall::kernel::Point_d<3>> points(300);
    for (auto& p : points)
      for (double& x : p.x) x = unit(rng) * scale;
    points[7].x = {-0.0, 0.0, -0.0};
    points.push_back(points[11]);  // a duplicate, left out of the distinct list
    std::vector<dewall::detail::Index> distinct(points.size() - 1);
    for (std::size_t i = 0; i < distinct.size(); ++i) distinct[i] = static_cast<dewall::detail::Index>(i);
    const dewall::detail::Point_set<K> ps(K{}, points, distinct, 8);
    INFO("scale " << scale << ", scale_exponent " << ps.scale_exponent);
    const auto restored = ps.restore_input();
    REQUIRE(restored.size() == points.size());
    for (std::size_t i = 0; i < distinct.size(); ++i)
      for (std::size_t j = 0; j < 3; ++j)
        CHECK(std::bit_cast<std::uint64_t>(restored[i].x[j]) == std::bit_cast<std::uint64_t>(points[i].x[j]));
    CHECK(std::isnan(restored.back().x[0]));
    if (scale != 1.0) CHECK(ps.scale_exponent != 0);  // the copies really are scaled
  }
}
