// Point generators for `dewall generate`, benchmarks and tests: random sets
// (uniform in a cube, in a ball, on a sphere, the paper's "bubbles") and exactly
// degenerate ones (an integer grid, integer points on one sphere, points on
// parallel planes), in E^2 … E^6, and in 3D simulated sensor data (a range
// scan, a depth-camera frame, an airborne laser scan, a repeated indoor scan).
//
// Randomness: one std::mt19937_64 seeded by the caller. The engine's sequence
// is fixed by the C++ standard; the standard *distributions* are not, so the
// conversions to doubles are written here (53 random bits per uniform double,
// Marsaglia's polar method for normal deviates). The same seed therefore gives
// the same points with any standard library; only std::log and std::sqrt in the
// normal deviates could, in principle, differ in the last bit between C libraries.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "dewall/io/point_reader.hpp"

namespace dewall::io {

class Progress;

/// The kinds of point sets `generate_points` makes.
enum class Point_kind {
  uniform,         ///< uniform in the unit cube [0, 1)^D
  ball,            ///< uniform in the unit ball about the origin (|p|² ≤ 1 in double arithmetic)
  sphere,          ///< uniform on the unit sphere (|p| = 1 up to rounding)
  bubbles,         ///< Gaussian clusters in the unit cube: density falls off from each centre
  grid,            ///< the integer lattice {0 … k−1}^D, k^D ≈ N (every point ties)
  lattice_sphere,  ///< all integer points with |p|² = m, m chosen for about N points (exactly cospherical)
  planes,          ///< points on a few hyperplanes x_{D−1} = const (exactly coplanar per plane)
  torus,           ///< uniform on a torus surface (R = 1, r = 0.3), like a scanned object's surface
  scan,            ///< a simulated range scan of objects on a table (3D only): scan lines, a 2^-16 grid
  depth,           ///< a depth-camera frame (3D only): a few hundred planes z = c, each a near-regular grid
  lidar,           ///< an airborne laser scan tile in UTM coordinates (3D only): a 0.5 m grid, 4 % repeats
  indoor,          ///< the `scan` points each repeated 2 … 4 times (3D only)
};

/// Options of a generator beyond kind, size, dimension and seed.
struct Generator_options {
  /// Normal noise off the surface, for `sphere` and `torus` only: each point
  /// moves along the surface normal by noise · r · z, z a standard normal
  /// deviate and r the surface's radius (sphere: 1; torus: the tube radius
  /// 0.3). So the distance to the centre (sphere) or to the core circle (torus)
  /// is r · (1 + noise · z): a shell of standard deviation noise · r, the same
  /// shape at every n (relative to the radius, not to the point spacing). 0, the
  /// default, gives exactly the points of the overload without options.
  /// \pre 0 ≤ noise ≤ 1, finite.
  double noise = 0;
  /// The number of hyperplanes of kind `planes`; 0, the default, chooses
  /// about log2(n) / 2 of them (2 … 8). 2 is the paper's Figure 7.
  /// \pre 0 or 2 … 1000; 0 for every other kind.
  int planes = 0;
};

/// The kind named `name` ("uniform", "ball", "sphere", "bubbles", "grid",
/// "lattice-sphere", "planes", "torus", "scan", "depth", "lidar", "indoor"), or nothing.
std::optional<Point_kind> parse_point_kind(std::string_view name);
/// The name of `kind`, as parse_point_kind accepts it.
const char* point_kind_name(Point_kind kind);
/// Whether `kind` is made in 3D only (scan, depth, lidar, indoor).
bool is_3d_only(Point_kind kind);
/// "uniform, ball, …": every name, for messages.
std::string point_kind_names();

/// A point set of `kind` in E^`dimension` (2 … 6) with about `n` points (exactly
/// n for the random kinds), from an engine seeded with `seed`. The deterministic
/// kinds (grid, lattice-sphere) ignore the seed.
/// `progress`, when given, receives the number of points made so far.
/// \throws std::invalid_argument for a dimension outside 2 … 6 (the 3D-only
/// kinds: other than 3) or n < dimension + 1 (indoor: n < 8).
Point_table generate_points(Point_kind kind, std::size_t n, int dimension, std::uint64_t seed,
                            Progress* progress = nullptr);
/// As above, with `options` (Generator_options::noise).
/// \throws std::invalid_argument also for a noise outside [0, 1], a non-zero
/// noise for a kind other than sphere and torus, or a plane count other than 0
/// or 2 … 1000 (non-zero for kind planes only).
Point_table generate_points(Point_kind kind, std::size_t n, int dimension, std::uint64_t seed,
                            const Generator_options& options, Progress* progress = nullptr);

}  // namespace dewall::io
