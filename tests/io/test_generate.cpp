// The point generators behind `dewall generate`: reproducible from a seed, and
// each kind keeps its promise exactly (integer grids, exactly cospherical lattice
// points, exactly coplanar planes, radius bounds), in every dimension 2 … 6.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <span>
#include <vector>

#include "dewall/dewall.hpp"
#include "dewall/io/point_generators.hpp"

using dewall::io::generate_points;
using dewall::io::Point_kind;
using dewall::io::Point_table;

namespace {

constexpr Point_kind all_kinds[] = {Point_kind::uniform, Point_kind::ball,  Point_kind::sphere, Point_kind::bubbles,
                                    Point_kind::grid,    Point_kind::lattice_sphere, Point_kind::planes,
                                    Point_kind::torus,   Point_kind::scan,  Point_kind::depth,  Point_kind::lidar,
                                    Point_kind::indoor};
constexpr Point_kind random_kinds[] = {Point_kind::uniform, Point_kind::ball,  Point_kind::sphere, Point_kind::bubbles,
                                       Point_kind::planes,  Point_kind::torus, Point_kind::scan,   Point_kind::depth,
                                       Point_kind::lidar,   Point_kind::indoor};

/// Whether `kind` is made in dimension d (the sensor kinds are 3D only).
bool made_in(Point_kind kind, int d) { return !dewall::io::is_3d_only(kind) || d == 3; }

double coordinate(const Point_table& t, std::size_t i, int j) {
  return t.coordinates[i * static_cast<std::size_t>(t.dimension) + static_cast<std::size_t>(j)];
}

bool is_integer(double v) { return std::isfinite(v) && v == std::floor(v) && std::abs(v) < 0x1p53; }

template <int D>
std::size_t triangulated_simplices(const Point_table& t) {
  std::vector<dewall::kernel::Point_d<D>> p(t.size());
  for (std::size_t i = 0; i < t.size(); ++i)
    for (int j = 0; j < D; ++j) p[i][j] = coordinate(t, i, j);
  return dewall::triangulate<D>(p).simplices.size();
}

}  // namespace

TEST_CASE("generators: names round-trip", "[generate]") {
  for (auto kind : all_kinds) CHECK(dewall::io::parse_point_kind(dewall::io::point_kind_name(kind)) == kind);
  CHECK(!dewall::io::parse_point_kind("cube"));
  CHECK(dewall::io::point_kind_names().find("lattice-sphere") != std::string::npos);
}

TEST_CASE("generators: reproducible from the seed, different for another seed", "[generate]") {
  for (int d = 2; d <= 6; ++d)
    for (auto kind : all_kinds) {
      if (!made_in(kind, d)) continue;
      INFO("kind " << dewall::io::point_kind_name(kind) << ", dimension " << d);
      const auto a = generate_points(kind, 200, d, 12345);
      const auto b = generate_points(kind, 200, d, 12345);
      REQUIRE(a.dimension == d);
      REQUIRE(a.coordinates.size() == b.coordinates.size());
      CHECK(std::memcmp(a.coordinates.data(), b.coordinates.data(), a.coordinates.size() * sizeof(double)) == 0);
      for (double v : a.coordinates) REQUIRE(std::isfinite(v));
      if (std::find(std::begin(random_kinds), std::end(random_kinds), kind) != std::end(random_kinds)) {
        CHECK(a.size() == 200);
        CHECK(generate_points(kind, 200, d, 12346).coordinates != a.coordinates);
      }
    }
}

TEST_CASE("generators: uniform, ball and sphere bounds", "[generate]") {
  for (int d = 2; d <= 6; ++d) {
    INFO("dimension " << d);
    const auto u = generate_points(Point_kind::uniform, 500, d, 1);
    for (double v : u.coordinates) REQUIRE((v >= 0 && v < 1));
    const auto b = generate_points(Point_kind::ball, 500, d, 2);
    const auto s = generate_points(Point_kind::sphere, 500, d, 3);
    for (std::size_t i = 0; i < 500; ++i) {
      double nb = 0, ns = 0;
      for (int j = 0; j < d; ++j) nb += coordinate(b, i, j) * coordinate(b, i, j), ns += coordinate(s, i, j) * coordinate(s, i, j);
      REQUIRE(nb <= 1.0);  // promised in double arithmetic, no tolerance
      REQUIRE(std::abs(std::sqrt(ns) - 1) <= 1e-14);
    }
  }
}

TEST_CASE("generators: grid is the integer lattice", "[generate]") {
  for (int d = 2; d <= 6; ++d) {
    const auto g = generate_points(Point_kind::grid, 1000, d, 0);
    const auto k = static_cast<std::size_t>(std::llround(std::pow(1000.0, 1.0 / d)));
    INFO("dimension " << d << ", side " << k);
    CHECK(g.size() == static_cast<std::size_t>(std::llround(std::pow(double(k), d))));
    std::set<std::vector<double>> distinct;
    for (std::size_t i = 0; i < g.size(); ++i) {
      std::vector<double> p;
      for (int j = 0; j < d; ++j) {
        const double v = coordinate(g, i, j);
        REQUIRE(is_integer(v));
        REQUIRE((v >= 0 && v < double(k)));
        p.push_back(v);
      }
      distinct.insert(p);
    }
    CHECK(distinct.size() == g.size());
  }
}

TEST_CASE("generators: lattice-sphere points are exactly cospherical integers", "[generate]") {
  struct Case {
    int d;
    std::size_t n;
  };
  for (auto [d, n] : {Case{2, 10}, Case{2, 1000}, Case{2, 100000}, Case{3, 10}, Case{3, 2000}, Case{4, 300},
                      Case{4, 5000}, Case{5, 1000}, Case{6, 3000}}) {
    INFO("dimension " << d << ", about " << n << " points");
    const auto t = generate_points(Point_kind::lattice_sphere, n, d, 0);
    // "About n": within a factor 2 (the count follows the divisors of |p|²).
    CHECK(t.size() * 2 >= n);
    CHECK(t.size() <= 2 * n);
    __extension__ typedef __int128 Int128;  // squared norms reach 2^100 in 2D
    Int128 norm = -1;
    std::set<std::vector<double>> distinct;
    for (std::size_t i = 0; i < t.size(); ++i) {
      Int128 s = 0;
      std::vector<double> p;
      for (int j = 0; j < d; ++j) {
        const double v = coordinate(t, i, j);
        REQUIRE(is_integer(v));
        s += static_cast<Int128>(v) * static_cast<Int128>(v);
        p.push_back(v);
      }
      if (norm < 0) norm = s;
      REQUIRE(s == norm);
      distinct.insert(p);
    }
    CHECK(distinct.size() == t.size());
  }
}

TEST_CASE("generators: planes are exactly coplanar, a few of them", "[generate]") {
  for (int d = 2; d <= 6; ++d) {
    INFO("dimension " << d);
    const auto t = generate_points(Point_kind::planes, 1000, d, 9);
    std::map<double, std::size_t> per_plane;  // the last coordinate is the plane
    for (std::size_t i = 0; i < t.size(); ++i) ++per_plane[coordinate(t, i, d - 1)];
    CHECK(per_plane.size() >= 2);
    CHECK(per_plane.size() <= 8);
    for (auto [height, count] : per_plane) CHECK(count >= 1000 / per_plane.size());
  }
}

TEST_CASE("generators: bubbles are clustered", "[generate]") {
  // Density falls off from the centres: most points are much closer to their
  // nearest neighbour than uniform points would be.
  const auto b = generate_points(Point_kind::bubbles, 1000, 2, 4);
  const auto u = generate_points(Point_kind::uniform, 1000, 2, 4);
  auto mean_nearest = [](const Point_table& t) {
    double sum = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      double best = 1e300;
      for (std::size_t k = 0; k < t.size(); ++k)
        if (k != i)
          best = std::min(best, std::hypot(coordinate(t, i, 0) - coordinate(t, k, 0), coordinate(t, i, 1) - coordinate(t, k, 1)));
      sum += best;
    }
    return sum / double(t.size());
  };
  CHECK(mean_nearest(b) < 0.7 * mean_nearest(u));
}

TEST_CASE("generators: every kind triangulates", "[generate]") {
  for (auto kind : all_kinds) {
    INFO("kind " << dewall::io::point_kind_name(kind));
    if (made_in(kind, 2)) CHECK(triangulated_simplices<2>(generate_points(kind, 300, 2, 5)) > 0);
    CHECK(triangulated_simplices<3>(generate_points(kind, 150, 3, 5)) > 0);
  }
}

TEST_CASE("generators: bad arguments", "[generate]") {
  CHECK_THROWS_AS(generate_points(Point_kind::uniform, 100, 7, 0), std::invalid_argument);
  CHECK_THROWS_AS(generate_points(Point_kind::uniform, 100, 1, 0), std::invalid_argument);
  CHECK_THROWS_WITH(generate_points(Point_kind::ball, 3, 3, 0), Catch::Contains("at least 4 points"));
}

TEST_CASE("generators: torus points lie on the torus surface", "[generate]") {
  for (int d = 2; d <= 6; ++d) {
    INFO("dimension " << d);
    const auto t = generate_points(Point_kind::torus, 500, d, 11);
    REQUIRE(t.size() == 500);
    double lowest = 1e300, highest = -1e300;  // x_0 over the set: the torus spans [−1.3, 1.3]
    for (std::size_t i = 0; i < t.size(); ++i) {
      // Distance to the circle of radius 1 in the plane of the first two axes.
      const double rho = std::hypot(coordinate(t, i, 0), coordinate(t, i, 1)) - 1.0;
      double s = rho * rho;
      for (int j = 2; j < d; ++j) s += coordinate(t, i, j) * coordinate(t, i, j);
      CHECK(std::abs(std::sqrt(s) - 0.3) < 1e-12);
      lowest = std::min(lowest, coordinate(t, i, 0));
      highest = std::max(highest, coordinate(t, i, 0));
    }
    CHECK(lowest < -1.2);
    CHECK(highest > 1.2);
  }
}

TEST_CASE("generators: noise 0 is the noiseless generator, bit for bit", "[generate]") {
  for (int d = 2; d <= 6; ++d)
    for (auto kind : all_kinds) {
      if (!made_in(kind, d)) continue;
      INFO("kind " << dewall::io::point_kind_name(kind) << ", dimension " << d);
      const auto a = generate_points(kind, 300, d, 77);
      const auto b = generate_points(kind, 300, d, 77, dewall::io::Generator_options{.noise = 0});
      REQUIRE(a.coordinates.size() == b.coordinates.size());
      CHECK(std::memcmp(a.coordinates.data(), b.coordinates.data(), a.coordinates.size() * sizeof(double)) == 0);
    }
}

TEST_CASE("generators: noisy torus and sphere points lie in the expected shell", "[generate]") {
  // Distance to the core (torus: the circle of radius 1; sphere: the centre)
  // is radius · (1 + noise · z), z standard normal: its relative offsets have
  // mean 0 and standard deviation `noise`, and none is beyond 6 σ (chance
  // about 2e-9 per point).
  constexpr double noise = 0.05;
  for (int d = 2; d <= 6; ++d)
    for (auto kind : {Point_kind::torus, Point_kind::sphere}) {
      INFO("kind " << dewall::io::point_kind_name(kind) << ", dimension " << d);
      const std::size_t n = 4000;
      const auto t = generate_points(kind, n, d, 19, dewall::io::Generator_options{.noise = noise});
      REQUIRE(t.size() == n);
      const double radius = kind == Point_kind::torus ? 0.3 : 1.0;
      double sum = 0, sum2 = 0;
      for (std::size_t i = 0; i < n; ++i) {
        double s = 0;
        if (kind == Point_kind::torus) {
          const double rho = std::hypot(coordinate(t, i, 0), coordinate(t, i, 1)) - 1.0;
          s = rho * rho;
          for (int j = 2; j < d; ++j) s += coordinate(t, i, j) * coordinate(t, i, j);
        } else {
          for (int j = 0; j < d; ++j) s += coordinate(t, i, j) * coordinate(t, i, j);
        }
        const double offset = std::sqrt(s) / radius - 1;  // noise · z
        REQUIRE(std::abs(offset) <= 6 * noise);
        sum += offset, sum2 += offset * offset;
      }
      const double mean = sum / double(n), sigma = std::sqrt(sum2 / double(n) - mean * mean);
      // Standard errors at n = 4000: the mean 0.05 / 63 ≈ 8e-4, σ about 1.1 %.
      CHECK(std::abs(mean) < 0.004);
      CHECK(std::abs(sigma - noise) < 0.1 * noise);
    }
}

TEST_CASE("generators: noise is checked", "[generate]") {
  using dewall::io::Generator_options;
  CHECK_THROWS_WITH(generate_points(Point_kind::uniform, 100, 3, 0, Generator_options{.noise = 0.1}),
                    Catch::Contains("sphere and torus only"));
  CHECK_THROWS_AS(generate_points(Point_kind::torus, 100, 3, 0, Generator_options{.noise = -0.1}), std::invalid_argument);
  CHECK_THROWS_AS(generate_points(Point_kind::torus, 100, 3, 0, Generator_options{.noise = 1.5}), std::invalid_argument);
  CHECK_THROWS_AS(generate_points(Point_kind::sphere, 100, 3, 0, Generator_options{.noise = std::nan("")}),
                  std::invalid_argument);
}

TEST_CASE("generators: planes with a chosen count", "[generate]") {
  for (int d = 2; d <= 6; ++d)
    for (int count : {2, 3, 20}) {
      INFO("dimension " << d << ", " << count << " planes");
      const auto t = generate_points(Point_kind::planes, 1000, d, 9, dewall::io::Generator_options{.planes = count});
      std::set<double> heights;
      for (std::size_t i = 0; i < t.size(); ++i) heights.insert(coordinate(t, i, d - 1));
      CHECK(heights.size() == static_cast<std::size_t>(count));
      CHECK(*heights.begin() == 0.0);
      CHECK(*heights.rbegin() == 1.0);
    }
  using dewall::io::Generator_options;
  CHECK_THROWS_AS(generate_points(Point_kind::planes, 100, 3, 0, Generator_options{.planes = 1}), std::invalid_argument);
  CHECK_THROWS_AS(generate_points(Point_kind::planes, 100, 3, 0, Generator_options{.planes = 1001}), std::invalid_argument);
  CHECK_THROWS_WITH(generate_points(Point_kind::uniform, 100, 3, 0, Generator_options{.planes = 2}),
                    Catch::Contains("kind planes only"));
}

TEST_CASE("generators: a scan's points lie on the scene, on the scanner's grid, the table's on shared planes",
          "[generate]") {
  CHECK_THROWS_WITH(generate_points(Point_kind::scan, 100, 2, 0), Catch::Contains("3D only"));
  CHECK_THROWS_WITH(generate_points(Point_kind::scan, 100, 4, 0), Catch::Contains("3D only"));
  for (const std::size_t n : {std::size_t{4}, std::size_t{3000}}) {
    const auto t = generate_points(Point_kind::scan, n, 3, 21);
    REQUIRE(t.size() == n);
    std::map<double, std::size_t> heights;  // z → points
    for (std::size_t i = 0; i < n; ++i) {
      for (int j = 0; j < 3; ++j) CHECK(is_integer(coordinate(t, i, j) * 0x1p16));  // the 2^-16 grid
      // In the scene's box (the table [−1.2, 1.2]² × [−0.1, 0], the cylinder up to 0.8),
      // give or take the range noise (σ = 0.0005).
      CHECK(std::abs(coordinate(t, i, 0)) <= 1.21);
      CHECK(std::abs(coordinate(t, i, 1)) <= 1.21);
      CHECK((coordinate(t, i, 2) >= -0.11 && coordinate(t, i, 2) <= 1.01));
      ++heights[coordinate(t, i, 2)];
    }
    if (n < 1000) continue;
    // Most rays hit the table top (z = 0 up to the noise): many points share a height exactly.
    std::size_t near_table = 0, largest_plane = 0;
    for (const auto& [z, count] : heights) {
      if (std::abs(z) < 0.005) near_table += count;
      largest_plane = std::max(largest_plane, count);
    }
    CHECK(near_table > n / 4);
    CHECK(largest_plane >= 10);
    // Above the table: the objects were seen (points up to the balls' and the cylinder's tops).
    CHECK(heights.rbegin()->first > 0.7);
  }
}

namespace {

using Xyz = std::array<double, 3>;

Xyz point3(const Point_table& t, std::size_t i) { return {coordinate(t, i, 0), coordinate(t, i, 1), coordinate(t, i, 2)}; }

/// How many times each distinct point occurs.
std::map<Xyz, std::size_t> multiplicities(const Point_table& t) {
  std::map<Xyz, std::size_t> m;
  for (std::size_t i = 0; i < t.size(); ++i) ++m[point3(t, i)];
  return m;
}

}  // namespace

TEST_CASE("generators: the sensor kinds are 3D only", "[generate]") {
  for (auto kind : {Point_kind::depth, Point_kind::lidar, Point_kind::indoor}) {
    INFO("kind " << dewall::io::point_kind_name(kind));
    CHECK(dewall::io::is_3d_only(kind));
    CHECK_THROWS_WITH(generate_points(kind, 100, 2, 0), Catch::Contains("3D only"));
    CHECK_THROWS_WITH(generate_points(kind, 100, 4, 0), Catch::Contains("3D only"));
  }
  CHECK_THROWS_WITH(generate_points(Point_kind::indoor, 7, 3, 0), Catch::Contains("at least 8"));
  CHECK(generate_points(Point_kind::indoor, 8, 3, 0).size() == 8);
}

TEST_CASE("generators: a depth frame is a few hundred exactly parallel planes of near-regular grids", "[generate]") {
  const std::size_t n = 4000;
  const auto t = generate_points(Point_kind::depth, n, 3, 31);
  REQUIRE(t.size() == n);
  std::map<double, std::vector<std::size_t>> planes;  // z → points
  for (std::size_t i = 0; i < n; ++i) {
    const double z = coordinate(t, i, 2);
    CHECK((z >= 0.4 && z <= 5));
    CHECK(std::nearbyint(z * 1000) / 1000 == z);  // whole millimetres
    planes[z].push_back(i);
  }
  // Disparity levels 800 / d: far fewer planes than points, at most a few hundred.
  CHECK(planes.size() >= 20);
  CHECK(planes.size() <= 400);
  CHECK(multiplicities(t).size() == n);  // one point per pixel
  // On the most populated plane: the points share rows (y) and columns (x)
  // exactly, many of them three or more to a row (collinear), and some four
  // form an axis-parallel rectangle (cocircular: every sphere through them ties).
  const auto& largest = std::max_element(planes.begin(), planes.end(), [](const auto& a, const auto& b) {
                          return a.second.size() < b.second.size();
                        })->second;
  REQUIRE(largest.size() >= 50);
  std::map<double, std::set<double>> rows;  // y → the x of its points
  for (auto i : largest) rows[coordinate(t, i, 1)].insert(coordinate(t, i, 0));
  std::size_t collinear_rows = 0;
  for (const auto& [y, xs] : rows) collinear_rows += xs.size() >= 3;
  CHECK(collinear_rows >= 3);
  bool rectangle = false;
  for (auto a = rows.begin(); a != rows.end() && !rectangle; ++a)
    for (auto b = std::next(a); b != rows.end() && !rectangle; ++b) {
      std::size_t shared = 0;
      for (double x : a->second) shared += b->second.count(x);
      rectangle = shared >= 2;
    }
  CHECK(rectangle);
}

TEST_CASE("generators: a lidar tile is a 0.5 m grid in UTM coordinates with 4 % exact repeats", "[generate]") {
  const std::size_t n = 5000;
  const auto t = generate_points(Point_kind::lidar, n, 3, 41);
  REQUIRE(t.size() == n);
  double x0 = 1e300, y0 = 1e300;
  for (std::size_t i = 0; i < n; ++i) x0 = std::min(x0, coordinate(t, i, 0)), y0 = std::min(y0, coordinate(t, i, 1));
  for (std::size_t i = 0; i < n; ++i) {
    const double x = coordinate(t, i, 0), y = coordinate(t, i, 1), z = coordinate(t, i, 2);
    CHECK((x >= 4.4e5 && x <= 5.6e5));
    CHECK((y >= 4.94e6 && y <= 5.06e6));
    CHECK(is_integer(2 * x));  // the 0.5 m grid, exactly
    CHECK(is_integer(2 * y));
    CHECK(std::nearbyint(z * 100) / 100 == z);  // whole centimetres
    CHECK((z >= 235 && z <= 280));
  }
  const auto m = multiplicities(t);
  CHECK(m.size() == n - 200);  // round(0.04 n) repeats of other points
  std::size_t repeated = 0;
  for (const auto& [p, k] : m) repeated += k > 1;
  CHECK(repeated > 150);
}

TEST_CASE("generators: indoor repeats every scan point 2 to 4 times", "[generate]") {
  for (const std::size_t n : {std::size_t{8}, std::size_t{1001}, std::size_t{3000}}) {
    INFO("n = " << n);
    const auto t = generate_points(Point_kind::indoor, n, 3, 51);
    REQUIRE(t.size() == n);
    const auto m = multiplicities(t);
    CHECK(m.size() >= 4);
    std::set<std::size_t> seen;
    for (const auto& [p, k] : m) {
      CHECK((k >= 2 && k <= 4));
      seen.insert(k);
      for (double v : p) CHECK(is_integer(v * 0x1p16));  // the scan's 2^-16 grid
    }
    if (n >= 1000) CHECK(seen.size() == 3);
  }
}
