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

constexpr std::array<const char*, 12> kind_names = {"uniform", "ball",           "sphere", "bubbles", "grid",
                                                    "lattice-sphere", "planes", "torus", "scan", "depth",
                                                    "lidar",   "indoor"};

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

/// A simulated range scan, what a scanned surface looks like to a
/// triangulator (3D only). The scene: a table top (the box [−1.2, 1.2]² ×
/// [−0.1, 0]), on it a ball (radius 0.5), a smaller one (0.25), a box and an
/// upright cylinder. Six scanners around it (radius 3, height 1.2, the first
/// at a random angle) each shoot a regular grid of rays (azimuth × elevation:
/// scan lines; density uneven over the surfaces, high where a surface is seen
/// at a grazing angle); a ray's first hit is a point, moved along the ray by
/// range noise (σ = 0.0005) and rounded to multiples of 2^-16, a scanner's
/// resolution: the table's points lie on a few hundred exactly parallel
/// planes, as a scanned floor's do. The grids are sized from a pilot grid so that they hit
/// more than n times; n of the hits are kept at random.
void scan(Point_table& t, std::size_t n, Rng& rng, Progress* progress) {
  using V = std::array<double, 3>;
  constexpr double pi = 3.14159265358979323846, eps = 1e-9;
  auto sub = [](const V& a, const V& b) { return V{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
  auto dot = [](const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  struct Ball { V c; double r; };
  struct Box { V lo, hi; };
  struct Cylinder { double x, y, r, z0, z1; };
  const Ball balls[] = {{{0.35, 0.3, 0.5}, 0.5}, {{-0.55, 0.55, 0.25}, 0.25}};
  const Box boxes[] = {{{-1.2, -1.2, -0.1}, {1.2, 1.2, 0}}, {{-0.8, -0.75, 0}, {-0.3, -0.45, 0.4}}};
  const Cylinder cylinder{0.55, -0.55, 0.2, 0, 0.8};
  // The nearest hit at t > eps of the ray o + t·w (w of unit length), or infinity.
  auto first_hit = [&](const V& o, const V& w) {
    double best = HUGE_VAL;
    for (const Ball& b : balls) {
      const V oc = sub(o, b.c);
      const double half_b = dot(w, oc), disc = half_b * half_b - (dot(oc, oc) - b.r * b.r);
      if (disc < 0) continue;
      const double root = std::sqrt(disc);
      for (const double h : {-half_b - root, -half_b + root})
        if (h > eps) { best = std::min(best, h); break; }
    }
    for (const Box& b : boxes) {  // slabs
      double enter = -HUGE_VAL, leave = HUGE_VAL;
      for (int j = 0; j < 3; ++j) {
        if (w[j] == 0) {
          if (o[j] < b.lo[j] || o[j] > b.hi[j]) enter = HUGE_VAL;
          continue;
        }
        const double a = (b.lo[j] - o[j]) / w[j], c = (b.hi[j] - o[j]) / w[j];
        enter = std::max(enter, std::min(a, c));
        leave = std::min(leave, std::max(a, c));
      }
      if (enter <= leave && enter > eps) best = std::min(best, enter);
    }
    {  // the cylinder's side, then its top
      const double dx = o[0] - cylinder.x, dy = o[1] - cylinder.y, a = w[0] * w[0] + w[1] * w[1];
      const double half_b = dx * w[0] + dy * w[1], disc = half_b * half_b - a * (dx * dx + dy * dy - cylinder.r * cylinder.r);
      if (a > 0 && disc >= 0) {
        const double h = (-half_b - std::sqrt(disc)) / a, z = o[2] + h * w[2];
        if (h > eps && z >= cylinder.z0 && z <= cylinder.z1) best = std::min(best, h);
      }
      if (w[2] != 0) {
        const double h = (cylinder.z1 - o[2]) / w[2], x = o[0] + h * w[0] - cylinder.x, y = o[1] + h * w[1] - cylinder.y;
        if (h > eps && x * x + y * y <= cylinder.r * cylinder.r) best = std::min(best, h);
      }
    }
    return best;
  };
  constexpr int scanners = 6;
  constexpr double half_width = 0.62;  // the grid's half-angle: the table's corners seen from 3 away
  const double first = 2 * pi * uniform01(rng);
  // Each scanner's rays on a side × side grid; `hit(o, w, h)` for every hit.
  auto sweep = [&](int side, auto&& hit) {
    for (int s = 0; s < scanners; ++s) {
      const double phi = first + 2 * pi * s / scanners;
      const V o{3 * std::cos(phi), 3 * std::sin(phi), 1.2};
      const double azimuth0 = phi + pi, elevation0 = std::atan2(0.3 - 1.2, 3.0);
      for (int i = 0; i < side; ++i) {
        const double e = elevation0 + half_width * (2.0 * (i + 0.5) / side - 1);
        for (int j = 0; j < side; ++j) {
          const double a = azimuth0 + half_width * (2.0 * (j + 0.5) / side - 1);
          const V w{std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
          const double h = first_hit(o, w);
          if (h != HUGE_VAL) hit(o, w, h);
        }
      }
    }
  };
  constexpr int pilot = 64;
  std::size_t pilot_hits = 0;
  sweep(pilot, [&](const V&, const V&, double) { ++pilot_hits; });
  const double per_ray = std::max(1.0, static_cast<double>(pilot_hits)) / (scanners * pilot * pilot);
  std::vector<V> hits;
  hits.reserve(static_cast<std::size_t>(1.2 * static_cast<double>(n)) + 16);
  for (int side = static_cast<int>(std::ceil(std::sqrt(1.1 * static_cast<double>(n) / (scanners * per_ray)))) + 1;
       hits.size() < n; side += side / 8 + 1) {  // (a finer grid in the rare case the pilot misjudged)
    hits.clear();
    sweep(side, [&](const V& o, const V& w, double h) {
      const double range = h + 0.0005 * normal(rng);
      V p;
      for (int j = 0; j < 3; ++j) p[j] = std::nearbyint((o[j] + range * w[j]) * 0x1p16) * 0x1p-16;
      hits.push_back(p);
      tick(progress, std::min(hits.size(), n - 1));
    });
  }
  // n of the hits at random, in the order they were scanned.
  std::vector<std::size_t> pick(hits.size());
  for (std::size_t i = 0; i < pick.size(); ++i) pick[i] = i;
  for (std::size_t i = 0; i < n; ++i) std::swap(pick[i], pick[i + static_cast<std::size_t>(uniform01(rng) * static_cast<double>(pick.size() - i))]);
  std::sort(pick.begin(), pick.begin() + static_cast<std::ptrdiff_t>(n));
  t.coordinates.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i) t.coordinates.insert(t.coordinates.end(), hits[pick[i]].begin(), hits[pick[i]].end());
}

/// Indices of `count` of the first `total` integers, chosen at random, in
/// increasing order (a partial Fisher–Yates shuffle). \pre count ≤ total.
std::vector<std::size_t> random_subset(std::size_t total, std::size_t count, Rng& rng) {
  std::vector<std::size_t> pick(total);
  for (std::size_t i = 0; i < total; ++i) pick[i] = i;
  for (std::size_t i = 0; i < count; ++i)
    std::swap(pick[i], pick[i + std::min(total - i - 1, static_cast<std::size_t>(uniform01(rng) * static_cast<double>(total - i)))]);
  pick.resize(count);
  std::sort(pick.begin(), pick.end());
  return pick;
}

/// One depth-camera frame (3D only), as a structured-light or time-of-flight
/// camera gives it: a W × H pixel grid (aspect 4:3, focal length 0.83 W,
/// principal point at the centre) looking along +z into a room (floor,
/// ceiling, side walls, a tilted back wall 3.4–4 m away) holding two balls and
/// a box placed at random. A pixel's depth is the first hit along its ray
/// plus noise growing with the square of the depth, quantised as a camera's
/// disparity is (d = round(800 / z), z = 800 / d, then whole millimetres):
/// a few hundred depth levels. The point is ((u − c_x) z / f, (v − c_y) z / f, z):
/// each level a plane z = c whose points share their rows' y and their
/// columns' x exactly — a near-regular grid, coplanar, collinear and
/// cocircular everywhere. Of the W·H ≥ n / 0.95 pixels, n are kept at random
/// (the holes of a real frame), in the frame's row order.
void depth(Point_table& t, std::size_t n, Rng& rng, Progress* progress) {
  using V = std::array<double, 3>;
  const double pixels = static_cast<double>(n) / 0.95;
  const auto w = static_cast<std::size_t>(std::ceil(std::sqrt(pixels * 4 / 3)));
  const auto h = static_cast<std::size_t>(std::ceil(pixels / static_cast<double>(w)));
  const double f = 0.83 * static_cast<double>(w), cx = (static_cast<double>(w) - 1) / 2, cy = (static_cast<double>(h) - 1) / 2;
  struct Ball { V c; double r; };
  // Camera at the origin, y pointing down: floor y = 1.1, ceiling y = −1.4.
  Ball balls[2];
  for (auto& b : balls) {
    b.r = 0.2 + 0.3 * uniform01(rng);
    b.c = {-1.2 + 2.4 * uniform01(rng), 1.1 - b.r, 1.2 + 1.8 * uniform01(rng)};
  }
  const double box_x = -1.0 + 1.5 * uniform01(rng), box_z = 1.5 + 1.5 * uniform01(rng);
  const V box_lo{box_x, 0.4, box_z}, box_hi{box_x + 0.5, 1.1, box_z + 0.4};
  const double tilt = 0.15 * (2 * uniform01(rng) - 1);  // back wall z = 3.7 + tilt·x
  // The depth z of the first hit of the ray (a, b, 1), or infinity.
  auto first_hit = [&](double a, double b) {
    double best = HUGE_VAL;
    auto plane = [&](double denominator, double numerator) {  // n·(t·dir) = c: t = c / (n·dir)
      if (denominator != 0) {
        const double z = numerator / denominator;
        if (z > 0.3) best = std::min(best, z);
      }
    };
    plane(b, 1.1), plane(b, -1.4), plane(a, 2.0), plane(a, -2.0), plane(1 - tilt * a, 3.7);
    const V dir{a, b, 1};
    for (const Ball& ball : balls) {
      const double dd = a * a + b * b + 1, dc = a * ball.c[0] + b * ball.c[1] + ball.c[2];
      const double cc = ball.c[0] * ball.c[0] + ball.c[1] * ball.c[1] + ball.c[2] * ball.c[2];
      const double disc = dc * dc - dd * (cc - ball.r * ball.r);
      if (disc >= 0) {
        const double z = (dc - std::sqrt(disc)) / dd;
        if (z > 0.3) best = std::min(best, z);
      }
    }
    double enter = 0.3, leave = HUGE_VAL;  // the box: slabs
    for (int j = 0; j < 3; ++j) {
      if (dir[j] == 0) {  // parallel to the slab: inside it or never in the box
        if (box_lo[j] > 0 || box_hi[j] < 0) enter = HUGE_VAL;
        continue;
      }
      const double p = box_lo[j] / dir[j], q = box_hi[j] / dir[j];
      enter = std::max(enter, std::min(p, q));
      leave = std::min(leave, std::max(p, q));
    }
    if (enter <= leave) best = std::min(best, enter);
    return best;
  };
  const auto keep = random_subset(w * h, n, rng);
  t.coordinates.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double u = static_cast<double>(keep[i] % w), v = static_cast<double>(keep[i] / w);
    double z = first_hit((u - cx) / f, (v - cy) / f);
    if (z == HUGE_VAL) z = 4.0;  // (not reached: the room is closed)
    z += (0.0012 + 0.0019 * (z - 0.4) * (z - 0.4)) * normal(rng);
    const double disparity = std::clamp(std::nearbyint(800 / z), 150.0, 2000.0);
    z = std::nearbyint(1000 * (800 / disparity)) / 1000;
    t.coordinates.push_back((u - cx) * z / f);
    t.coordinates.push_back((v - cy) * z / f);
    t.coordinates.push_back(z);
    tick(progress, i);
  }
}

/// An airborne laser scan tile in UTM coordinates (3D only): x ≈ 5·10^5,
/// y ≈ 5·10^6 (metres; the tile's corner a random multiple of 1 km), the
/// returns on a 0.5 m grid (85 % of the cells of a square tile, at random),
/// z a gently rolling terrain about 250 m high (three random waves, a few
/// metres) with flat-roofed buildings (one per 2,500 m², roofs 5–15 m up),
/// plus noise (σ = 2 cm), stored as a LAS file stores it: whole centimetres.
/// Then 4 % of the points (round(0.04 n)) are exact repeats of earlier ones
/// (overlapping flight strips), after the others. Points in flight order:
/// lines of the grid, alternately forwards and backwards.
void lidar(Point_table& t, std::size_t n, Rng& rng, Progress* progress) {
  constexpr double pi = 3.14159265358979323846, spacing = 0.5;
  const auto repeats = static_cast<std::size_t>(std::llround(0.04 * static_cast<double>(n)));
  const std::size_t distinct = n - repeats;
  const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(distinct) / 0.85)));
  const double x0 = 500000 + 1000 * std::floor(100 * uniform01(rng) - 50);
  const double y0 = 5000000 + 1000 * std::floor(100 * uniform01(rng) - 50);
  struct Wave { double kx, ky, phase, amplitude; };
  Wave waves[3];
  for (auto& wave : waves) {
    const double length = 60 + 240 * uniform01(rng), angle = 2 * pi * uniform01(rng);
    wave = {2 * pi / length * std::cos(angle), 2 * pi / length * std::sin(angle), 2 * pi * uniform01(rng),
            0.5 + 2.5 * uniform01(rng)};
  }
  auto ground = [&](double x, double y) {  // x, y from the tile's corner
    double z = 250;
    for (const Wave& wave : waves) z += wave.amplitude * std::sin(wave.kx * x + wave.ky * y + wave.phase);
    return z;
  };
  struct Building { double x, y, dx, dy, roof; };
  const double extent = spacing * static_cast<double>(side);
  std::vector<Building> buildings(static_cast<std::size_t>(extent * extent / 2500));
  for (auto& b : buildings) {
    b.dx = 8 + 22 * uniform01(rng), b.dy = 8 + 22 * uniform01(rng);
    b.x = (extent - b.dx) * uniform01(rng), b.y = (extent - b.dy) * uniform01(rng);
    b.roof = ground(b.x + b.dx / 2, b.y + b.dy / 2) + 5 + 10 * uniform01(rng);
  }
  const auto cells = random_subset(side * side, distinct, rng);
  t.coordinates.reserve(3 * n);
  for (std::size_t i = 0; i < distinct; ++i) {
    const std::size_t row = cells[i] / side, along = cells[i] % side;
    const double x = spacing * static_cast<double>(along), y = spacing * static_cast<double>(row);
    double z = ground(x, y);
    for (const Building& b : buildings)
      if (x >= b.x && x <= b.x + b.dx && y >= b.y && y <= b.y + b.dy) z = std::max(z, b.roof);
    z = std::nearbyint(100 * (z + 0.02 * normal(rng))) / 100;
    t.coordinates.push_back(x0 + x);
    t.coordinates.push_back(y0 + y);
    t.coordinates.push_back(z);
    tick(progress, i);
  }
  // Backwards rows: reverse each odd row's run of points (cells are sorted by row, then column).
  for (std::size_t begin = 0; begin < distinct;) {
    std::size_t end = begin;
    while (end < distinct && cells[end] / side == cells[begin] / side) ++end;
    if ((cells[begin] / side) % 2 == 1)
      for (std::size_t a = begin, b = end - 1; a < b; ++a, --b)
        for (std::size_t j = 0; j < 3; ++j) std::swap(t.coordinates[3 * a + j], t.coordinates[3 * b + j]);
    begin = end;
  }
  for (std::size_t i = 0; i < repeats; ++i) {
    const auto k = std::min(distinct - 1, static_cast<std::size_t>(uniform01(rng) * static_cast<double>(distinct)));
    for (std::size_t j = 0; j < 3; ++j) t.coordinates.push_back(t.coordinates[3 * k + j]);
    tick(progress, distinct + i);
  }
}

/// An indoor scan seen several times (3D only): the points of kind `scan`
/// (about n / 3 of them), each repeated 2, 3 or 4 times exactly, as when
/// registered sweeps snap to the same scanner grid. The output is the sweeps
/// one after the other: every point, then the points seen a second time,
/// a third, a fourth; n points in all.
void indoor(Point_table& t, std::size_t n, Rng& rng, Progress* progress) {
  const std::size_t distinct = std::max<std::size_t>(4, (n + 2) / 3);
  scan(t, distinct, rng, nullptr);
  std::vector<int> times(distinct);
  std::size_t total = 0;
  for (auto& k : times) total += static_cast<std::size_t>(k = 2 + static_cast<int>(uniform01(rng) * 3));
  // Bring the total to n, one point at a time (n ≥ 2·distinct and 4·distinct ≥ n hold for n ≥ 8).
  while (total != n) {
    auto& k = times[std::min(distinct - 1, static_cast<std::size_t>(uniform01(rng) * static_cast<double>(distinct)))];
    if (total > n && k > 2) --k, --total;
    else if (total < n && k < 4) ++k, ++total;
  }
  const std::vector<double> base = t.coordinates;
  t.coordinates.reserve(3 * n);
  for (int sweep = 2; sweep <= 4; ++sweep)
    for (std::size_t i = 0; i < distinct; ++i)
      if (times[i] >= sweep) {
        t.coordinates.insert(t.coordinates.end(), base.begin() + static_cast<std::ptrdiff_t>(3 * i),
                             base.begin() + static_cast<std::ptrdiff_t>(3 * i + 3));
        tick(progress, t.coordinates.size() / 3);
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

bool is_3d_only(Point_kind kind) {
  return kind == Point_kind::scan || kind == Point_kind::depth || kind == Point_kind::lidar || kind == Point_kind::indoor;
}

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
  if (is_3d_only(kind) && dimension != 3)
    throw std::invalid_argument(std::string("kind ") + point_kind_name(kind) + " is 3D only, not dimension " +
                                std::to_string(dimension));
  if (kind == Point_kind::indoor && n < 8)
    throw std::invalid_argument("kind indoor needs at least 8 points (each of them repeated), asked for " +
                                std::to_string(n));
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
    case Point_kind::scan: scan(t, n, rng, progress); break;
    case Point_kind::depth: depth(t, n, rng, progress); break;
    case Point_kind::lidar: lidar(t, n, rng, progress); break;
    case Point_kind::indoor: indoor(t, n, rng, progress); break;
  }
  if (progress) progress->finish();
  return t;
}

}  // namespace dewall::io
