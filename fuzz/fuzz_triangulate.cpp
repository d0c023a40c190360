// fuzz_triangulate: dewall::triangulate on small, mostly degenerate point sets
// (D = 2, 3, 4) against CGAL's Delaunay triangulation and a brute-force
// empty-sphere check.
//
// Input: [dimension] [point count] [family] [family parameters] [coordinate
// style header] [transform], then per point one byte (one in eight: a copy of an
// earlier point) and the point's bytes. Families, all chosen to be degenerate
// in exact arithmetic, because that is where the perturbation must agree with
// CGAL's to the last simplex:
//   lattice      integer grid {0 … m−1}^D (cocircular/cospherical everywhere);
//   cospherical  signed permutations of one small integer vector (all points on
//                one sphere around the origin);
//   layers       the last coordinate from {0, 1, 2} (coplanar layers), the
//                others from the coordinate styles of fuzz_common.hpp;
//   free         every coordinate from the coordinate styles (extreme, subnormal,
//                nudged, raw doubles).
// The transform translates by an integer and scales by 2^e, e ∈ [-1074, 1000]
// (exact on lattices unless the result is subnormal; overflow to infinity is
// legal input that must be rejected as Invalid_input).
//
// Properties:
//  1. non-finite input → Invalid_input; otherwise Invalid_input exactly when
//     CGAL finds no finite full cell (fewer than D + 1 distinct points, or the
//     points do not span E^D);
//  2. the simplices, as sorted index tuples, are the finite cells of CGAL's
//     triangulation; no simplex repeats; every simplex is positively oriented
//     and uses first occurrences of duplicate points only;
//  3. empty spheres, by brute force: no distinct input point lies inside any
//     simplex's circumsphere under the kernel's perturbed predicate
//     (tests/support/brute_force_delaunay.hpp); and the certifier finds the
//     triangulation Delaunay and canonical;
//  4. the output is a function of the point set and not of the threads: the
//     serial run (parallel_depth = 0) gives the same list in the same order, and
//     the reversed input gives the same simplices (mapped through coordinates);
//  5. Engine::hybrid with regions of 6 and of 25 points (so that the walls,
//     the regions' filter and the finishing gift-wrap all run) gives CGAL's
//     simplices, the same list on one thread, with the regions built by either
//     incremental construction;
//  6. Engine::incremental (the project's own Bowyer–Watson) gives CGAL's
//     simplices, positively oriented, each once;
//  7. its zoned (parallel) insertion, from the first D + 1 points on: CGAL's
//     cells, and the same cells and neighbours in the same slots on two
//     threads as on one.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "dewall/certify/certify.hpp"
#include "dewall/detail/incremental/incremental_delaunay.hpp"
#include "dewall/dewall.hpp"
#include "dewall/kernel/orientation.hpp"
#include "fuzz_common.hpp"
#include "support/brute_force_delaunay.hpp"
#include "support/cgal_reference.hpp"

#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Epick_d.h>

namespace {

using namespace dewall::kernel;
using dewall::fuzz::Byte_source;
using dewall::fuzz::Coordinate_decoder;

enum class Family : int { lattice, cospherical, layers, free };
constexpr int family_count = 4;

// Small enough that one execution stays in the milliseconds under ASan.
constexpr int max_points(int d) { return d == 2 ? 64 : d == 3 ? 40 : 20; }

template <int D>
std::vector<Point_d<D>> read_points(Byte_source& in) {
  const int n = in.integer(1, max_points(D));
  const auto family = static_cast<Family>(in.integer(0, family_count - 1));
  const int lattice_size = in.integer(2, 6);
  std::array<int, D> sphere_vector;
  for (auto& v : sphere_vector) v = in.integer(0, 4);
  const Coordinate_decoder decoder = Coordinate_decoder::read(in);
  // Most inputs keep their natural scale; one in four moves to an extreme one.
  const std::uint8_t transform = in.byte();
  const int exponent = transform % 4 == 0 ? in.integer(-1074, 1000) : 0;
  const double offset = transform % 8 == 4 ? in.integer(-(1 << 15), 1 << 15) * 1024.0 : 0;

  std::vector<Point_d<D>> points;
  for (int i = 0; i < n; ++i) {
    const std::uint8_t b = in.byte();
    if (!points.empty() && b % 8 == 7) {
      points.push_back(points[b / 8 % points.size()]);
      continue;
    }
    Point_d<D> p;
    switch (family) {
      case Family::lattice:
        for (int j = 0; j < D; ++j) p[j] = in.integer(0, lattice_size - 1);
        break;
      case Family::cospherical: {
        // A signed permutation of sphere_vector: |p| is the same for every point.
        std::array<int, D> v = sphere_vector;
        for (int j = 0; j < D - 1; ++j) std::swap(v[j], v[in.integer(j, D - 1)]);
        const std::uint8_t signs = in.byte();
        for (int j = 0; j < D; ++j) p[j] = (signs >> j & 1) ? -v[j] : v[j];
        break;
      }
      case Family::layers:
        for (int j = 0; j < D - 1; ++j) p[j] = decoder.coordinate(in);
        p[D - 1] = in.integer(0, 2);
        break;
      case Family::free:
        p = dewall::fuzz::read_point<D>(in, decoder);
        break;
    }
    points.push_back(p);
  }
  for (auto& p : points)
    for (int j = 0; j < D; ++j) p[j] = std::ldexp(p[j] + offset, exponent);
  return points;
}

/// Whether CGAL finds that the points span E^D. Asked separately in dD because
/// cgal_delaunay's dD branch reads D + 1 vertices per cell, which lower-
/// dimensional cells do not have (2D and 3D just report no finite cell).
template <int D>
bool cgal_spans(const std::vector<Point_d<D>>& points) {
  using K = CGAL::Epick_d<CGAL::Dimension_tag<D>>;
  CGAL::Delaunay_triangulation<K> dt(D);
  std::vector<typename K::Point_d> p;
  for (const auto& q : points) p.emplace_back(q.x.begin(), q.x.end());
  dt.insert(p.begin(), p.end());
  return dt.current_dimension() == D;
}

template <int D>
struct Checker {
  const std::vector<Point_d<D>>& points;

  void check(bool ok, const char* what) const {
    if (ok) return;
    dewall::fuzz::print_points<D>("input", points);
    dewall::fuzz::fail(what);
  }
};
#define CHECK_ON(checker, expr) (checker).check((expr), #expr)

template <int D>
void run(Byte_source& in) {
  const std::vector<Point_d<D>> points = read_points<D>(in);
  const Checker<D> checker{points};
  bool finite = true;
  for (const auto& p : points) finite = finite && is_finite(p);

  dewall::Triangulation<D> t;
  bool rejected = false;
  try {
    t = dewall::triangulate<D>(points, dewall::Options{.engine = dewall::Engine::dewall});
  } catch (const dewall::Invalid_input&) {
    rejected = true;
  }
  if (!finite) {
    CHECK_ON(checker, rejected);
    return;
  }
  // Property 1 and 2: CGAL decides what the answer is.
  if constexpr (D >= 4) {
    const bool spans = cgal_spans<D>(points);
    CHECK_ON(checker, rejected == !spans);
    if (rejected) return;
  }
  const auto expected = dewall::test::cgal_delaunay<D>(points);
  CHECK_ON(checker, rejected == expected.empty());
  if (rejected) return;
  const auto got = dewall::test::as_set<D>(t.simplices);
  CHECK_ON(checker, got.size() == t.simplices.size());
  CHECK_ON(checker, got == expected);

  std::map<std::array<double, D>, std::uint32_t> first;
  for (std::size_t i = points.size(); i-- > 0;) first[points[i].x] = static_cast<std::uint32_t>(i);
  for (const auto& s : t.simplices) {
    Orientation_points<D> o;
    for (int i = 0; i <= D; ++i) {
      CHECK_ON(checker, s[i] < points.size() && first.at(points[s[i]].x) == s[i]);
      o[static_cast<std::size_t>(i)] = &points[s[i]];
    }
    CHECK_ON(checker, orientation_d<D>(o) == POSITIVE);
  }

  // Property 3: empty spheres, every simplex against every distinct point, by
  // brute force (independent of the certifier); and the certifier's verdict.
  CHECK_ON(checker, !dewall::test::brute_force_violation<D>(points, t.simplices));
  const auto report = dewall::certify::certify<dewall::kernel::Filtered_kernel_d<D>>(points, t.simplices);
  CHECK_ON(checker, report.delaunay && report.canonical);

  // Property 4: threads and input order change nothing.
  const auto serial = dewall::triangulate<D>(points, dewall::Options{.parallel_depth = 0, .engine = dewall::Engine::dewall});
  CHECK_ON(checker, serial.simplices == t.simplices);
  const std::vector<Point_d<D>> reversed(points.rbegin(), points.rend());
  std::vector<dewall::Simplex<D>> mapped;
  for (auto s : dewall::triangulate<D>(reversed, dewall::Options{.engine = dewall::Engine::dewall}).simplices) {
    for (auto& v : s) v = first.at(reversed[v].x);
    mapped.push_back(s);
  }
  CHECK_ON(checker, dewall::test::as_set<D>(mapped) == expected);

  // Property 5: the hybrid engine (walls, then regions by CGAL's incremental
  // construction), with regions small enough that most inputs have several.
  for (std::size_t region : {std::size_t{6}, std::size_t{25}}) {
    const auto h = dewall::triangulate<D>(points, dewall::Options{.engine = dewall::Engine::hybrid, .region_points = region});
    CHECK_ON(checker, h.simplices.size() == expected.size());
    CHECK_ON(checker, dewall::test::as_set<D>(h.simplices) == expected);
    const auto h_serial = dewall::triangulate<D>(
        points, dewall::Options{.parallel_depth = 0, .engine = dewall::Engine::hybrid, .region_points = region});
    CHECK_ON(checker, h_serial.simplices == h.simplices);
    for (const dewall::Engine regions : {dewall::Engine::incremental, dewall::Engine::cgal}) {
      const auto other = dewall::triangulate<D>(
          points, dewall::Options{.engine = dewall::Engine::hybrid, .incremental_engine = regions, .region_points = region});
      CHECK_ON(checker, other.simplices.size() == expected.size());
      CHECK_ON(checker, dewall::test::as_set<D>(other.simplices) == expected);
    }
  }

  // Property 6: the project's own incremental engine.
  const auto own = dewall::triangulate<D>(points, dewall::Options{.engine = dewall::Engine::incremental});
  CHECK_ON(checker, own.simplices.size() == expected.size());
  CHECK_ON(checker, dewall::test::as_set<D>(own.simplices) == expected);
  for (const auto& s : own.simplices) {
    std::array<const Point_d<D>*, D + 1> refs;
    for (int i = 0; i <= D; ++i) refs[static_cast<std::size_t>(i)] = &points[s[static_cast<std::size_t>(i)]];
    CHECK_ON(checker, dewall::kernel::orientation_d<D>(refs) == dewall::kernel::POSITIVE);
  }

  // Property 7: zoned insertion (Zoned_insertion, zoned_insertion.hpp, which
  // the library uses from 2^16 points on), every point after the first
  // 256th (the BRIO sample's own sample) in zones: CGAL's cells, and on two threads the same cells in the same
  // slots as on one; zones that run out of slots or give up early, or try
  // the points beside the cut too, or glue every star through the ridge table
  // with colliding keys (same_ridge alone tells ridges apart), by the input's size.
  std::vector<Point_d<D>> distinct;
  std::vector<std::uint32_t> input_of;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (first.at(points[i].x) == i) distinct.push_back(points[i]), input_of.push_back(static_cast<std::uint32_t>(i));
  dewall::detail::Incremental_tuning tuning;
  tuning.zoned_insertion_threshold = 0;
  tuning.zone_slots_scale = points.size() % 2 ? 1 : 0.25;
  tuning.zone_probe = points.size() % 3 ? 2048 : 4;
  tuning.near_cut_spacings = points.size() % 5 ? 2.0 : 0.0;
  tuning.ridge_table_only = tuning.colliding_ridge_keys = points.size() % 7 == 0;
  std::array<dewall::detail::Incremental_delaunay<D>, 2> zoned{dewall::detail::Incremental_delaunay<D>(tuning),
                                                               dewall::detail::Incremental_delaunay<D>(tuning)};
  for (int threads = 1; threads <= 2; ++threads) {
    auto& dt = zoned[static_cast<std::size_t>(threads - 1)];
    tbb::task_arena(threads).execute([&] { CHECK_ON(checker, dt.build(std::span<const Point_d<D>>(distinct))); });
  }
  std::vector<dewall::Simplex<D>> cells;
  CHECK_ON(checker, zoned[0].slots() == zoned[1].slots());
  for (std::size_t c = 0; c < zoned[0].slots(); ++c) {
    CHECK_ON(checker, zoned[0].is_free(c) == zoned[1].is_free(c));
    if (zoned[0].is_free(c)) continue;
    CHECK_ON(checker, zoned[0].cell(c) == zoned[1].cell(c));
    for (int i = 0; i <= D; ++i) CHECK_ON(checker, zoned[0].neighbor(c, i) == zoned[1].neighbor(c, i));
    if (zoned[0].is_infinite(c)) continue;
    dewall::Simplex<D> s;
    for (int i = 0; i <= D; ++i) s[static_cast<std::size_t>(i)] = input_of[zoned[0].input_index(zoned[0].cell(c)[static_cast<std::size_t>(i)])];
    cells.push_back(s);
  }
  CHECK_ON(checker, zoned[0].is_valid());
  CHECK_ON(checker, dewall::test::as_set<D>(cells) == expected);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Byte_source in(data, size);
  // Mostly 2D and 3D (CGAL's specialised triangulations); 4D through CGAL's dD one.
  const std::uint8_t d = in.byte();
  const int dimension = d % 8 < 4 ? 2 : d % 8 < 7 ? 3 : 4;
  if (dimension == 2) run<2>(in);
  else if (dimension == 3) run<3>(in);
  else run<4>(in);
  return 0;
}
