// Random and degenerate point generators shared by the kernel and triangulator tests.
//
// Every generator takes the engine explicitly (std::mt19937_64, seeded by the
// test, whose seed the test prints with Catch2's INFO); none keeps state. The
// degenerate families are *exactly* degenerate in double: integer coordinates
// (exact below 2^53), signed permutations of one integer vector (all on one
// sphere), integer points of a lower-dimensional integer flat. The transforms
// below keep that exactness where stated (scaling by a power of two, translation
// by a representable offset), and `nudge_ulps` breaks it by the smallest amount.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "dewall/io/point_generators.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/point_array.hpp"

namespace dewall::test {

using Rng = std::mt19937_64;
template <int D>
using Point = kernel::Point_d<D>;

/// The seed a test should use: DEWALL_TEST_SEED from the environment when set
/// (to reproduce a failure printed by INFO), otherwise `fallback`.
inline std::uint64_t test_seed(std::uint64_t fallback) {
  if (const char* s = std::getenv("DEWALL_TEST_SEED")) return std::stoull(s, nullptr, 0);
  return fallback;
}

/// A uniform integer in [lo, hi].
inline long uniform_int(Rng& rng, long lo, long hi) {
  return std::uniform_int_distribution<long>(lo, hi)(rng);
}

// ---------------------------------------------------------------- random doubles

/// A point uniform in the box [lo, hi]^D.
template <int D>
Point<D> uniform_point(Rng& rng, double lo = -1, double hi = 1) {
  std::uniform_real_distribution<double> u(lo, hi);
  Point<D> p;
  for (int j = 0; j < D; ++j) p[j] = u(rng);
  return p;
}

template <int D>
std::vector<Point<D>> uniform_points(Rng& rng, std::size_t n, double lo = -1, double hi = 1) {
  std::vector<Point<D>> v(n);
  for (auto& p : v) p = uniform_point<D>(rng, lo, hi);
  return v;
}

/// A double of random sign with a random 53-bit significand and binary exponent
/// uniform in [emin, emax]: m·2^e, 2^52 ≤ m < 2^53. Exponents below −1074 + 52
/// give subnormals (the low bits are then rounded away); emax ≤ 970.
inline double random_double_with_exponent(Rng& rng, int emin, int emax) {
  const auto m = static_cast<double>((rng() >> 11) | (std::uint64_t{1} << 52));
  const int e = static_cast<int>(uniform_int(rng, emin, emax));
  const double v = std::ldexp(m, e - 52);
  return (rng() & 1) ? v : -v;
}

/// A point whose coordinates each have an independent random exponent in
/// [emin, emax]: mixed scales within one point.
template <int D>
Point<D> wide_range_point(Rng& rng, int emin, int emax) {
  Point<D> p;
  for (int j = 0; j < D; ++j) p[j] = random_double_with_exponent(rng, emin, emax);
  return p;
}

// ---------------------------------------------------------------- exactly degenerate

/// A point with integer coordinates uniform in [lo, hi].
template <int D>
Point<D> lattice_point(Rng& rng, long lo, long hi) {
  Point<D> p;
  for (int j = 0; j < D; ++j) p[j] = static_cast<double>(uniform_int(rng, lo, hi));
  return p;
}

template <int D>
std::vector<Point<D>> lattice_points(Rng& rng, std::size_t n, long lo, long hi) {
  std::vector<Point<D>> v(n);
  for (auto& p : v) p = lattice_point<D>(rng, lo, hi);
  return v;
}

/// Every point of the grid {0, …, k−1}^D (k^D points): the library's `grid`
/// generator (`dewall generate grid`), first coordinate fastest. With k = 2
/// these are the cube's vertices: all on one sphere.
template <int D>
std::vector<Point<D>> grid_points(int k) {
  std::size_t n = 1;
  for (int j = 0; j < D; ++j) n *= static_cast<std::size_t>(k);
  return kernel::points_from_coordinates<D>(io::generate_points(io::Point_kind::grid, n, D, 0).coordinates);
}

/// centre + a random signed permutation of v: every such point lies on the
/// sphere of squared radius |v|² around centre (exactly, for integer inputs).
template <int D>
Point<D> random_signed_permutation(Rng& rng, const std::array<long, D>& v, const Point<D>& centre) {
  std::array<long, D> w = v;
  std::shuffle(w.begin(), w.end(), rng);
  Point<D> p;
  for (int j = 0; j < D; ++j) {
    const long c = (rng() & 1) ? w[static_cast<std::size_t>(j)] : -w[static_cast<std::size_t>(j)];
    p[j] = centre[j] + static_cast<double>(c);
  }
  return p;
}

/// n distinct integer points on one sphere: signed permutations of a random
/// integer vector with entries in [1, max_entry] (pairwise distinct when
/// possible, so that there are enough of them) around an integer centre in
/// [−centre_range, centre_range]^D. Returns fewer than n points when the vector
/// has fewer distinct signed permutations (at least 2^D ≥ D + 2 of them; up to 2^D·D!).
template <int D>
std::vector<Point<D>> cospherical_integer_points(Rng& rng, std::size_t n, long max_entry = 2 * D,
                                                 long centre_range = 3) {
  std::array<long, D> v;
  for (auto& e : v) e = uniform_int(rng, 1, max_entry);
  const Point<D> centre = lattice_point<D>(rng, -centre_range, centre_range);
  std::vector<Point<D>> out;
  for (int attempts = 0; out.size() < n && attempts < 1000 * static_cast<int>(n); ++attempts) {
    const Point<D> p = random_signed_permutation<D>(rng, v, centre);
    if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  }
  return out;
}

/// n integer points on a random k-dimensional integer flat (k < D gives
/// coplanar, k = 1 collinear points): o + Σ_{t<k} c_t·b_t with o, b_t integer
/// (entries in [−range, range]) and integer c_t in [−range, range].
template <int D>
std::vector<Point<D>> flat_integer_points(Rng& rng, std::size_t n, int k, long range = 4) {
  const Point<D> origin = lattice_point<D>(rng, -range, range);
  std::vector<Point<D>> basis(static_cast<std::size_t>(k));
  for (auto& b : basis) b = lattice_point<D>(rng, -range, range);
  std::vector<Point<D>> out(n);
  for (auto& p : out) {
    p = origin;
    for (const auto& b : basis) {
      const double c = static_cast<double>(uniform_int(rng, -range, range));
      for (int j = 0; j < D; ++j) p[j] += c * b[j];
    }
  }
  return out;
}

// ---------------------------------------------------------------- transforms

/// Multiplies every coordinate by 2^e. Exact (keeps every degeneracy) as long as
/// no result overflows or loses bits as a subnormal.
template <int D>
void scale_by_power_of_two(std::vector<Point<D>>& points, int e) {
  for (auto& p : points)
    for (int j = 0; j < D; ++j) p[j] = std::ldexp(p[j], e);
}

/// Multiplies coordinate j by 2^e[j]: an affine map, so it keeps orientation
/// degeneracies (collinear, coplanar) exactly, but not cosphericity.
template <int D>
void scale_axes_by_powers_of_two(std::vector<Point<D>>& points, const std::array<int, D>& e) {
  for (auto& p : points)
    for (int j = 0; j < D; ++j) p[j] = std::ldexp(p[j], e[static_cast<std::size_t>(j)]);
}

/// Adds `offset` to every point. Exact (keeps every degeneracy) when the sums
/// are representable, e.g. integer points moved by an integer offset below 2^53.
template <int D>
void translate(std::vector<Point<D>>& points, const Point<D>& offset) {
  for (auto& p : points)
    for (int j = 0; j < D; ++j) p[j] += offset[j];
}

/// Moves `count` randomly chosen coordinates (of randomly chosen points) by one
/// ulp up or down: the smallest change that can break an exact degeneracy.
template <int D>
void nudge_ulps(Rng& rng, std::vector<Point<D>>& points, int count = 1) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (int t = 0; t < count; ++t) {
    auto& p = points[static_cast<std::size_t>(uniform_int(rng, 0, static_cast<long>(points.size()) - 1))];
    const int j = static_cast<int>(uniform_int(rng, 0, D - 1));
    p[j] = std::nextafter(p[j], (rng() & 1) ? inf : -inf);
  }
}

/// k distinct elements of `points` in random order. \pre k ≤ points.size().
template <int D>
std::vector<Point<D>> random_subset(Rng& rng, const std::vector<Point<D>>& points, std::size_t k) {
  std::vector<std::size_t> index(points.size());
  std::iota(index.begin(), index.end(), std::size_t{0});
  std::vector<Point<D>> out(k);
  for (std::size_t i = 0; i < k; ++i) {
    std::swap(index[i], index[static_cast<std::size_t>(
                            uniform_int(rng, static_cast<long>(i), static_cast<long>(index.size()) - 1))]);
    out[i] = points[index[i]];
  }
  return out;
}

/// Points in hexadecimal floating point, one per line: exact, and ready to
/// paste into a regression test.
template <int D>
std::string format_points(const std::vector<Point<D>>& points) {
  std::ostringstream out;
  out << std::hexfloat;
  for (const auto& p : points) {
    out << "{{";
    for (int j = 0; j < D; ++j) out << (j ? ", " : "") << p[j];
    out << "}}\n";
  }
  return out.str();
}

// ---------------------------------------------------------------- named families

/// What a family guarantees exactly, so that tests can check the generator
/// does what its name says.
enum class Degeneracy {
  none,
  cospherical,      // all points on one sphere (or flat): every sphere test is 0
  flat,             // all points on one hyperplane: every orientation and sphere test is 0
  flat_but_last,    // all points but the last on one hyperplane
};

/// A named way of drawing n points. Families drawn from a finite set return
/// fewer when it runs out: "cube vertices" at most 2^D, "grid 3^D" at most 3^D,
/// the cospherical ones at least D + 2 and usually 2^D·D!.
template <int D>
struct Point_set_family {
  std::string name;
  Degeneracy degeneracy;
  std::function<std::vector<Point<D>>(Rng&, std::size_t)> make;
};

/// Random, exactly degenerate, near-degenerate (one or two ulps off), extreme
/// magnitudes (subnormals to 2^500, mixed scales) and large-offset point sets.
template <int D>
std::vector<Point_set_family<D>> point_set_families() {
  using V = std::vector<Point<D>>;
  using std::size_t;
  auto shifted = [](V v, double offset) {
    Point<D> o;
    for (int j = 0; j < D; ++j) o[j] = offset;
    translate<D>(v, o);
    return v;
  };
  auto scaled = [](V v, int e) {
    scale_by_power_of_two<D>(v, e);
    return v;
  };
  auto nudged = [](Rng& rng, V v, int count) {
    nudge_ulps<D>(rng, v, count);
    return v;
  };
  auto exponents = [](int emin, int emax) {
    return [=](Rng& rng, size_t n) {
      V v(n);
      for (auto& p : v) p = wide_range_point<D>(rng, emin, emax);
      return v;
    };
  };
  auto uniform = [](Rng& rng, size_t n) { return uniform_points<D>(rng, n); };
  auto lattice = [](Rng& rng, size_t n) { return lattice_points<D>(rng, n, -2, 2); };
  auto cospherical = [](Rng& rng, size_t n) { return cospherical_integer_points<D>(rng, n); };
  auto hyperplane = [](Rng& rng, size_t n) { return flat_integer_points<D>(rng, n, D - 1); };
  auto collinear = [](Rng& rng, size_t n) { return flat_integer_points<D>(rng, n, 1); };
  auto cube = [](Rng& rng, size_t n) {
    static const V vertices = grid_points<D>(2);
    return random_subset<D>(rng, vertices, std::min(n, vertices.size()));
  };
  auto grid3 = [](Rng& rng, size_t n) {
    static const V grid = grid_points<D>(3);
    return random_subset<D>(rng, grid, std::min(n, grid.size()));
  };
  auto hyperplane_but_last = [=](Rng& rng, size_t n) {
    V v = hyperplane(rng, n);
    v.back() = lattice_point<D>(rng, -4, 4);
    return v;
  };
  // Applies a transform to another family's output.
  auto then = [](auto family, auto transform) {
    return [=](Rng& rng, size_t n) { return transform(rng, family(rng, n)); };
  };
  auto scale = [=](int e) { return [=](Rng&, V v) { return scaled(std::move(v), e); }; };
  auto shift = [=](double o) { return [=](Rng&, V v) { return shifted(std::move(v), o); }; };
  auto nudge = [=](int count) { return [=](Rng& rng, V v) { return nudged(rng, std::move(v), count); }; };

  const auto none = Degeneracy::none;
  const auto sphere = Degeneracy::cospherical;
  const auto flat = Degeneracy::flat;
  return {
      // Random.
      {"uniform [-1,1]", none, uniform},
      {"uniform [0,1e-3]", none, [](Rng& rng, size_t n) { return uniform_points<D>(rng, n, 0, 1e-3); }},
      // Exactly degenerate.
      {"lattice [-2,2]", none, lattice},
      {"cube vertices", sphere, cube},
      {"grid 3^D", none, grid3},
      {"cospherical integer", sphere, cospherical},
      {"hyperplane", flat, hyperplane},
      {"collinear", flat, collinear},
      {"hyperplane but the last point", Degeneracy::flat_but_last, hyperplane_but_last},
      // Near-degenerate.
      {"lattice + 1 ulp", none, then(lattice, nudge(1))},
      {"cube + 1 ulp", none, then(cube, nudge(1))},
      {"cospherical + 1 ulp", none, then(cospherical, nudge(1))},
      {"cospherical + 2 ulps", none, then(cospherical, nudge(2))},
      {"hyperplane + 1 ulp", none, then(hyperplane, nudge(1))},
      {"collinear + 1 ulp", none, then(collinear, nudge(1))},
      // Extreme magnitudes.
      {"lattice * 2^-1074 (subnormal)", none, then(lattice, scale(-1074))},
      {"cospherical * 2^-1074 (subnormal)", sphere, then(cospherical, scale(-1074))},
      {"hyperplane * 2^-1060 (subnormal)", flat, then(hyperplane, scale(-1060))},
      {"uniform * 2^-1050 (subnormal)", none, then(uniform, scale(-1050))},
      {"cospherical * 2^-1000", sphere, then(cospherical, scale(-1000))},
      {"cospherical * 2^-1000 + 1 ulp", none, then(then(cospherical, scale(-1000)), nudge(1))},
      {"cospherical * 2^-520", sphere, then(cospherical, scale(-520))},
      {"hyperplane * 2^-300 + 1 ulp", none, then(then(hyperplane, scale(-300)), nudge(1))},
      {"cospherical * 2^300", sphere, then(cospherical, scale(300))},
      {"cospherical * 2^500", sphere, then(cospherical, scale(500))},
      {"cospherical * 2^500 + 1 ulp", none, then(then(cospherical, scale(500)), nudge(1))},
      {"hyperplane * 2^500", flat, then(hyperplane, scale(500))},
      {"exponents [-1022,-1000]", none, exponents(-1022, -1000)},
      {"exponents [-1000,500] per coordinate", none, exponents(-1000, 500)},
      {"exponents [-40,40] per coordinate", none, exponents(-40, 40)},
      {"hyperplane, axes scaled by 2^[-500,500]", flat,
       then(hyperplane,
            [](Rng& rng, V v) {
              std::array<int, D> e;
              for (auto& x : e) x = static_cast<int>(uniform_int(rng, -500, 500));
              scale_axes_by_powers_of_two<D>(v, e);
              return v;
            })},
      {"lattice, one point * 2^400", none,
       then(lattice,
            [](Rng& rng, V v) {
              auto& p = v[static_cast<size_t>(uniform_int(rng, 0, static_cast<long>(v.size()) - 1))];
              for (int j = 0; j < D; ++j) p[j] *= 0x1p400;
              return v;
            })},
      {"tiny points * 2^-500, last one huge", none,
       then(then(uniform, scale(-500)),
            [](Rng& rng, V v) {
              v.back() = uniform_point<D>(rng, -0x1p500, 0x1p500);
              return v;
            })},
      // Large offsets, tiny differences.
      {"lattice + 2^30", none, then(lattice, shift(0x1p30))},
      {"cospherical + 2^30", sphere, then(cospherical, shift(0x1p30))},
      {"cospherical + 2^30 + 1 ulp", none, then(then(cospherical, shift(0x1p30)), nudge(1))},
      {"cospherical * 2^-22 + 2^30", sphere, then(then(cospherical, scale(-22)), shift(0x1p30))},
      {"uniform [-1,1] + 2^30", none, then(uniform, shift(0x1p30))},
      {"cospherical + 2^52", sphere, then(cospherical, shift(0x1p52))},
      {"cospherical + 2^52 + 1 ulp", none, then(then(cospherical, shift(0x1p52)), nudge(1))},
      {"hyperplane + 2^52", flat, then(hyperplane, shift(0x1p52))},
      {"hyperplane + 2^52 + 1 ulp", none, then(then(hyperplane, shift(0x1p52)), nudge(1))},
      {"uniform [0,64] + 2^52", none,
       then([](Rng& rng, size_t n) { return uniform_points<D>(rng, n, 0, 64); }, shift(0x1p52))},
  };
}

}  // namespace dewall::test
