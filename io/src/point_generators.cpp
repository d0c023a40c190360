#include "dewall/io/point_generators.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <vector>

#include "dewall/io/dimensions.hpp"
#include "dewall/io/progress.hpp"

namespace dewall::io {
namespace {

using Rng = std::mt19937_64;
// Gaussian-integer products in 2D reach 2^100 before they are converted to
// doubles; GCC and Clang's 128-bit integers hold them exactly.
__extension__ typedef __int128 Int128;

constexpr std::array<const char*, 8> kind_names = {"uniform", "ball",           "sphere", "bubbles",
                                                   "grid",    "lattice-sphere", "planes", "torus"};

/// A uniform double in [0, 1): the top 53 bits of one draw, scaled exactly.
double uniform01(Rng& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

/// A standard normal deviate (Marsaglia's polar method: no trigonometry).
double normal(Rng& rng) {
  for (;;) {
    const double u = 2 * uniform01(rng) - 1, v = 2 * uniform01(rng) - 1;
    const double s = u * u + v * v;
    if (s > 0 && s < 1) return u * std::sqrt(-2 * std::log(s) / s);
  }
}

/// Calls `progress` every 2^16 points, cheaply.
void tick(Progress* progress, std::size_t i) {
  if (progress && (i & 0xffff) == 0) progress->advance_to(i);
}

void uniform_cube(Point_table& t, std::size_t n, Rng& rng, Progress* progress) {
  t.coordinates.resize(n * static_cast<std::size_t>(t.dimension));
  for (std::size_t i = 0; i < t.coordinates.size(); ++i) {
    t.coordinates[i] = uniform01(rng);
    tick(progress, i / static_cast<std::size_t>(t.dimension));
  }
}

/// Rejection from the cube [−1, 1]^D: the accepted points satisfy |p|² ≤ 1 as
/// computed in double, a promise a user can check without a tolerance. (At most
/// 1 / 0.08 draws per point, in 6D.)
void ball(Point_table& t, std::size_t n, Rng& rng, Progress* progress) {
  const auto d = static_cast<std::size_t>(t.dimension);
  std::vector<double> p(d);
  for (std::size_t i = 0; i < n; ++i) {
    double s;
    do {
      s = 0;
      for (auto& x : p) x = 2 * uniform01(rng) - 1, s += x * x;
    } while (s > 1);
    t.coordinates.insert(t.coordinates.end(), p.begin(), p.end());
    tick(progress, i);
  }
}

/// A normal vector divided by its length is uniform on the sphere. With noise,
/// the radius is 1 + noise · z (z drawn after the direction, so noise 0 draws
/// nothing more and keeps the points of the noiseless generator).
void sphere(Point_table& t, std::size_t n, double noise, Rng& rng, Progress* progress) {
  const auto d = static_cast<std::size_t>(t.dimension);
  std::vector<double> p(d);
  for (std::size_t i = 0; i < n; ++i) {
    double s;
    do {
      s = 0;
      for (auto& x : p) x = normal(rng), s += x * x;
    } while (s < 1e-12);  // a direction needs a length
    const double r = std::sqrt(s);
    if (noise == 0) {
      for (auto x : p) t.coordinates.push_back(x / r);
    } else {
      const double radius = 1 + noise * normal(rng);
      for (auto x : p) t.coordinates.push_back(x / r * radius);
    }
    tick(progress, i);
  }
}

/// Uniform on the surface of a torus: the points at distance r = 0.3 from the
/// circle of radius R = 1 in the plane of the first two axes (in 3D the usual
/// torus; in 2D two circles). A direction u on the unit sphere of the other
/// D − 1 dimensions (the radial one first) gives the point
/// ((R + r·u_0)·cos θ, (R + r·u_0)·sin θ, r·u_1, …); keeping it with probability
/// (R + r·u_0)/(R + r) makes the density uniform by area. Like a scanned
/// surface, and unlike a sphere, most of its Delaunay balls are small.
/// With noise, the point moves along the normal u: the tube radius becomes
/// r · (1 + noise · z), z drawn after the point is accepted (noise 0 draws
/// nothing more), so the density stays uniform by area on the noiseless torus.
void torus(Point_table& t, std::size_t n, double noise, Rng& rng, Progress* progress) {
  constexpr double R = 1.0, r = 0.3, pi = 3.14159265358979323846;
  const auto d = static_cast<std::size_t>(t.dimension);
  std::vector<double> u(d - 1);
  t.coordinates.reserve(n * d);
  for (std::size_t i = 0; i < n;) {
    double s = 0;
    for (auto& x : u) x = normal(rng), s += x * x;
    if (s < 1e-12) continue;
    const double norm = std::sqrt(s);
    for (auto& x : u) x /= norm;
    if (uniform01(rng) * (R + r) > R + r * u[0]) continue;
    const double theta = 2 * pi * uniform01(rng);
    const double tube = noise == 0 ? r : r * (1 + noise * normal(rng)), radius = R + tube * u[0];
    t.coordinates.push_back(radius * std::cos(theta));
    t.coordinates.push_back(radius * std::sin(theta));
    for (std::size_t j = 1; j + 1 < d; ++j) t.coordinates.push_back(tube * u[j]);
    tick(progress, i++);
  }
}

/// The paper's "bubbles": a few clusters of random centre, size and weight, each
/// a Gaussian about its centre, so the density falls off from the centre. About
/// one cluster per 50 points, at most 10.
void bubbles(Point_table& t, std::size_t n, Rng& rng, Progress* progress) {
  const auto d = static_cast<std::size_t>(t.dimension);
  const std::size_t clusters = std::clamp<std::size_t>(n / 50, 1, 10);
  std::vector<double> centre(clusters * d), sigma(clusters), cumulative(clusters);
  double total = 0;
  for (std::size_t c = 0; c < clusters; ++c) {
    for (std::size_t j = 0; j < d; ++j) centre[c * d + j] = 0.2 + 0.6 * uniform01(rng);
    sigma[c] = 0.02 + 0.06 * uniform01(rng);
    cumulative[c] = total += 0.5 + uniform01(rng);
  }
  t.coordinates.reserve(n * d);
  for (std::size_t i = 0; i < n; ++i) {
    const double w = uniform01(rng) * total;
    const auto c = std::min<std::size_t>(
        clusters - 1, static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), w) -
                                               cumulative.begin()));
    for (std::size_t j = 0; j < d; ++j) t.coordinates.push_back(centre[c * d + j] + sigma[c] * normal(rng));
    tick(progress, i);
  }
}

void grid(Point_table& t, std::size_t n) {
  const int d = t.dimension;
  const auto k = std::max<std::size_t>(
      2, static_cast<std::size_t>(std::llround(std::pow(static_cast<double>(n), 1.0 / d))));
  std::vector<std::size_t> c(static_cast<std::size_t>(d), 0);
  for (;;) {
    for (auto v : c) t.coordinates.push_back(static_cast<double>(v));
    std::size_t j = 0;
    while (j < c.size() && ++c[j] == k) c[j++] = 0;
    if (j == c.size()) break;
  }
}

/// n points on p hyperplanes x_{D−1} = h_0 < … < h_{p−1} in [0, 1] (p = `count`,
/// or when that is 0 about log2(n) / 2, 2 … 8); the
/// height of a plane is one double shared by all its points, so each plane is
/// exactly a hyperplane; the other coordinates are uniform in [0, 1). Point i
/// lies on plane i mod p, so every plane gets its share.
void planes(Point_table& t, std::size_t n, int count, Rng& rng, Progress* progress) {
  const auto d = static_cast<std::size_t>(t.dimension);
  const auto p = count != 0 ? static_cast<std::size_t>(count)
                            : static_cast<std::size_t>(std::clamp(std::lround(std::log2(static_cast<double>(n)) / 2), 2L, 8L));
  t.coordinates.reserve(n * d);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j + 1 < d; ++j) t.coordinates.push_back(uniform01(rng));
    t.coordinates.push_back(static_cast<double>(i % p) / static_cast<double>(p - 1));
    tick(progress, i);
  }
}

// ---- lattice-sphere ---------------------------------------------------------

std::uint64_t isqrt(std::uint64_t v) {
  auto r = static_cast<std::uint64_t>(std::sqrt(static_cast<double>(v)));
  while (r * r > v) --r;
  while ((r + 1) * (r + 1) <= v) ++r;
  return r;
}

/// Calls `emit(a)` for every a_0 ≥ a_1 ≥ … ≥ a_{D−1} ≥ 0 with Σ a_i² = m. The
/// first of the remaining k entries is the largest, so a_i² ≥ rest / k: this
/// lower bound keeps the search near the solutions (≈ m^{(D−1)/2} / (D−1)! steps).
void sorted_representations(std::uint64_t m, int d, const std::function<void(const std::array<std::uint64_t, 6>&)>& emit) {
  std::array<std::uint64_t, 6> a{};
  std::function<void(int, std::uint64_t, std::uint64_t)> rec = [&](int i, std::uint64_t rest, std::uint64_t bound) {
    if (i == d - 1) {
      const auto r = isqrt(rest);
      if (r * r == rest && r <= bound) a[static_cast<std::size_t>(i)] = r, emit(a);
      return;
    }
    const auto k = static_cast<std::uint64_t>(d - i);
    const auto high = std::min(bound, isqrt(rest));
    auto low = isqrt(rest / k);
    while (low * low * k < rest) ++low;  // ceil(sqrt(rest / k))
    if (low > high) return;
    for (auto v = high;; --v) {
      a[static_cast<std::size_t>(i)] = v;
      rec(i + 1, rest - v * v, v);
      if (v == low) break;
    }
  };
  rec(0, m, isqrt(m));
}

/// Number of points with |p|² = m: each sorted tuple stands for its distinct
/// permutations times a sign per non-zero entry.
std::size_t lattice_sphere_count(std::uint64_t m, int d) {
  std::size_t count = 0;
  sorted_representations(m, d, [&](const std::array<std::uint64_t, 6>& a) {
    std::size_t perms = 1;
    for (int i = 2; i <= d; ++i) perms *= static_cast<std::size_t>(i);
    std::size_t run = 1, signs = 1;
    for (int i = 0; i < d; ++i) {
      if (a[static_cast<std::size_t>(i)] != 0) signs *= 2;
      if (i > 0 && a[static_cast<std::size_t>(i)] == a[static_cast<std::size_t>(i - 1)]) perms /= ++run;
      else run = 1;
    }
    count += perms * signs;
  });
  return count;
}

double log_distance(std::size_t count, std::size_t n) {
  return count == 0 ? 1e300 : std::abs(std::log(static_cast<double>(count) / static_cast<double>(n)));
}

/// D ≥ 3: the points on |p|² = m number about (S_D / 2) m^{D/2 − 1} (the
/// derivative of the ball volume V_D m^{D/2}; S_D = D V_D is the area of the unit
/// sphere). Start from the m this predicts, correct once by the actual count,
/// then try the neighbours when that is cheap.
/// In 3D, m ≡ 7 (mod 8) has no points and m ≡ 0 (mod 4) only those of m / 4
/// (Legendre's three-square theorem): skip both.
std::uint64_t choose_squared_radius(std::size_t n, int d) {
  const double area = 2 * std::pow(M_PI, d / 2.0) / std::tgamma(d / 2.0);
  const double exponent = 2.0 / (d - 2);
  auto admissible = [&](double x) {
    auto m = static_cast<std::uint64_t>(std::max(1.0, std::round(x)));
    if (d == 3)
      while (m % 4 == 0 || m % 8 == 7) ++m;
    return m;
  };
  const auto m0 = admissible(std::pow(2.0 * static_cast<double>(n) / area, exponent));
  const auto c0 = lattice_sphere_count(m0, d);
  const auto m1 = admissible(static_cast<double>(m0) *
                             std::pow(static_cast<double>(n) / static_cast<double>(std::max<std::size_t>(c0, 1)), exponent));
  const auto c1 = m1 == m0 ? c0 : lattice_sphere_count(m1, d);
  auto best = log_distance(c1, n) < log_distance(c0, n) ? std::pair{m1, c1} : std::pair{m0, c0};
  // The count jumps between neighbouring m (it follows the divisors of m);
  // when counting is cheap, look at the neighbours for a closer one.
  const double steps = std::pow(static_cast<double>(best.first), (d - 1) / 2.0);
  if (steps * 33 < 3e7) {
    const auto centre = best.first;
    for (auto m = centre > 16 ? centre - 16 : 1; m <= centre + 16; ++m) {
      if (m != admissible(static_cast<double>(m))) continue;
      const auto c = lattice_sphere_count(m, d);
      if (log_distance(c, n) < log_distance(best.second, n)) best = {m, c};
    }
  }
  return best.first;
}

void lattice_sphere_high(Point_table& t, std::size_t n) {
  const int d = t.dimension;
  const auto m = choose_squared_radius(n, d);
  sorted_representations(m, d, [&](const std::array<std::uint64_t, 6>& a) {
    std::vector<std::int64_t> p(a.begin(), a.begin() + d);
    std::sort(p.begin(), p.end());
    do {
      std::vector<std::size_t> nonzero;
      for (std::size_t i = 0; i < p.size(); ++i)
        if (p[i] != 0) nonzero.push_back(i);
      for (std::size_t mask = 0; mask < (std::size_t{1} << nonzero.size()); ++mask)
        for (std::size_t i = 0; i < p.size(); ++i) {
          const auto bit = std::find(nonzero.begin(), nonzero.end(), i) - nonzero.begin();
          const bool negate = p[i] != 0 && ((mask >> bit) & 1);
          t.coordinates.push_back(static_cast<double>(negate ? -p[i] : p[i]));
        }
    } while (std::next_permutation(p.begin(), p.end()));
  });
}

/// D = 2: the number of representations m = x² + y² is 4 ∏ (e_i + 1) over the
/// primes p_i ≡ 1 (mod 4) dividing m to the power e_i (Jacobi; m without other
/// odd prime factors). Counts near n come from m = 5^e · 13 · 17 · 29 · …, and
/// the points themselves from Gaussian integers: with p = π π̄ in Z[i], the
/// solutions are u · ∏ π_i^j π̄_i^(e_i − j), u a unit — all distinct by unique
/// factorisation. No search: this scales to 10^5 points and more.
void lattice_sphere_2(Point_table& t, std::size_t n) {
  struct Gaussian {
    Int128 re, im;
    Gaussian operator*(const Gaussian& o) const { return {re * o.re - im * o.im, re * o.im + im * o.re}; }
  };
  std::vector<Gaussian> primes;  // π = a + bi with a² + b² = p, p ≡ 1 (mod 4)
  for (std::int64_t p = 5; primes.size() < 40; p += 4) {
    bool prime = true;
    for (std::int64_t q = 2; q * q <= p && prime; ++q) prime = p % q != 0;
    if (!prime) continue;
    for (std::int64_t a = 1; a * a < p; ++a) {
      const auto b = static_cast<std::int64_t>(isqrt(static_cast<std::uint64_t>(p - a * a)));
      if (b * b == p - a * a) {
        primes.push_back({a, b});
        break;
      }
    }
  }
  // Candidates: k primes to the first power (4 · 2^k points), or the first one
  // squared (6 · 2^k points). Coordinates stay below 2^50 (exact doubles).
  std::size_t best_k = 0;
  bool best_squared = false;
  double best = log_distance(4, n);
  double log2_m = 0;
  for (std::size_t k = 1; k <= primes.size(); ++k) {
    const auto& q = primes[k - 1];
    log2_m += std::log2(static_cast<double>(q.re * q.re + q.im * q.im));
    if (log2_m + std::log2(5.0) > 100) break;
    for (bool squared : {false, true}) {
      const std::size_t count = (squared ? 6 : 4) * (std::size_t{1} << k);
      if (log_distance(count, n) < best) best = log_distance(count, n), best_k = k, best_squared = squared;
    }
  }
  std::vector<Gaussian> z{{1, 0}};
  for (std::size_t i = 0; i < best_k; ++i) {
    const Gaussian pi = primes[i], bar{primes[i].re, -primes[i].im};
    const std::vector<Gaussian> factors = best_squared && i == 0 ? std::vector<Gaussian>{pi * pi, pi * bar, bar * bar}
                                                                 : std::vector<Gaussian>{pi, bar};
    std::vector<Gaussian> next;
    for (const auto& x : z)
      for (const auto& f : factors) next.push_back(x * f);
    z = std::move(next);
  }
  for (const auto& x : z)
    for (const Gaussian u : {Gaussian{1, 0}, Gaussian{0, 1}, Gaussian{-1, 0}, Gaussian{0, -1}}) {
      const auto p = x * u;
      t.coordinates.push_back(static_cast<double>(p.re));
      t.coordinates.push_back(static_cast<double>(p.im));
    }
}

}  // namespace

std::optional<Point_kind> parse_point_kind(std::string_view name) {
  for (std::size_t i = 0; i < kind_names.size(); ++i)
    if (name == kind_names[i]) return static_cast<Point_kind>(i);
  return std::nullopt;
}

const char* point_kind_name(Point_kind kind) { return kind_names[static_cast<std::size_t>(kind)]; }

std::string point_kind_names() {
  std::string s;
  for (const char* name : kind_names) s += (s.empty() ? "" : ", ") + std::string(name);
  return s;
}

Point_table generate_points(Point_kind kind, std::size_t n, int dimension, std::uint64_t seed, Progress* progress) {
  return generate_points(kind, n, dimension, seed, Generator_options{}, progress);
}

Point_table generate_points(Point_kind kind, std::size_t n, int dimension, std::uint64_t seed,
                            const Generator_options& options, Progress* progress) {
  const double noise = options.noise;
  if (!(noise >= 0 && noise <= 1))  // also rejects NaN
    throw std::invalid_argument("noise " + std::to_string(noise) + " is outside [0, 1]");
  if (noise != 0 && kind != Point_kind::sphere && kind != Point_kind::torus)
    throw std::invalid_argument(std::string("noise applies to sphere and torus only, not ") + point_kind_name(kind));
  if (options.planes != 0 && (options.planes < 2 || options.planes > 1000))
    throw std::invalid_argument("plane count " + std::to_string(options.planes) + " is outside 2 … 1000");
  if (options.planes != 0 && kind != Point_kind::planes)
    throw std::invalid_argument(std::string("a plane count applies to kind planes only, not ") + point_kind_name(kind));
  if (!is_supported_dimension(dimension))
    throw std::invalid_argument("dimension " + std::to_string(dimension) + " is not supported (" + dimension_range() + ")");
  if (n < static_cast<std::size_t>(dimension) + 1)
    throw std::invalid_argument("need at least " + std::to_string(dimension + 1) + " points in dimension " +
                                std::to_string(dimension) + ", asked for " + std::to_string(n));
  Point_table t;
  t.dimension = dimension;
  Rng rng(seed);
  if (progress) progress->phase(std::string("generating ") + point_kind_name(kind), n);
  switch (kind) {
    case Point_kind::uniform: uniform_cube(t, n, rng, progress); break;
    case Point_kind::ball: ball(t, n, rng, progress); break;
    case Point_kind::sphere: sphere(t, n, noise, rng, progress); break;
    case Point_kind::bubbles: bubbles(t, n, rng, progress); break;
    case Point_kind::grid: grid(t, n); break;
    case Point_kind::lattice_sphere: dimension == 2 ? lattice_sphere_2(t, n) : lattice_sphere_high(t, n); break;
    case Point_kind::planes: planes(t, n, options.planes, rng, progress); break;
    case Point_kind::torus: torus(t, n, noise, rng, progress); break;
  }
  if (progress) progress->finish();
  return t;
}

}  // namespace dewall::io
