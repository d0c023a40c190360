// dewall::mpi::triangulate against CGAL and the single-machine library, run by
// ctest under mpiexec with 1, 2, 3, 4 and 7 ranks (tests/CMakeLists.txt).
//
// Every rank makes the same point set (fixed seeds; 2D and 3D: eight kinds,
// 4D: two, 5D and 6D: a few uniform points), passes its share (uneven shares,
// and some ranks none; some cases again with each block built in regions,
// Options::region_points), and rank 0 gathers the simplices and checks:
//  * no simplex twice, each positively oriented (exact orientation), in the
//    canonical form of Global_simplex;
//  * the set equals CGAL's (tests/support/cgal_reference.hpp);
//  * the set equals dewall::triangulate's on one machine;
//  * the certifier (certify/, independent of dewall/) finds it Delaunay and canonical.
// Error cases: a NaN on one rank, points not spanning E^D, too few distinct
// points: every rank throws Invalid_input with the same message.
// Not Catch2: its main knows nothing of MPI; each check prints what failed,
// and the exit status (the same on every rank) is the number of failures.
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "dewall/certify/certify.hpp"
#include "dewall/dewall.hpp"
#include "dewall/io/point_generators.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/point_array.hpp"
#include "dewall/mpi/triangulate.hpp"
#include "support/cgal_reference.hpp"
#include "support/point_generators.hpp"

namespace {

using namespace dewall;

int rank = 0, size = 1;
int failures = 0;

void fail(const std::string& what) {
  ++failures;
  std::fprintf(stderr, "FAILED (rank %d of %d): %s\n", rank, size, what.c_str());
}

/// How the points are shared out: rank r gets [first(r), first(r + 1)).
enum class Shares { even, growing, gaps };
std::uint64_t first_of(Shares s, std::uint64_t n, int r) {
  const auto R = static_cast<std::uint64_t>(size), q = static_cast<std::uint64_t>(r);
  switch (s) {
    case Shares::even: return n * q / R;
    case Shares::growing: return n * q * q / (R * R);  // rank 0 few, the last many
    case Shares::gaps: return q == R ? n : n * (q / 2 * 2) / R;  // every odd rank none
  }
  return 0;
}

/// Regions (Options::region_points) in a case: none, or about five per rank.
enum class Regions { none, some };

template <int D>
void check_case(const std::string& name, const std::vector<kernel::Point_d<D>>& points, Shares shares,
                Regions regions = Regions::none) {
  const std::uint64_t n = points.size();
  const std::uint64_t b = first_of(shares, n, rank), e = rank + 1 == size ? n : first_of(shares, n, rank + 1);
  std::span<const kernel::Point_d<D>> local(points.data() + b, e - b);
  mpi::Options options;
  if (regions == Regions::some) options.region_points = std::max<std::uint64_t>(20, n / (5 * static_cast<std::uint64_t>(size)));
  mpi::Result<D> r;
  try {
    r = mpi::triangulate<D>(MPI_COMM_WORLD, local, b, options);
  } catch (const std::exception& x) {
    fail(name + ": threw " + x.what());
    return;
  }
  // The count the sink was told first (Simplex_sink::start) is the count it got.
  if (r.statistics.simplices != r.simplices.size()) fail(name + ": the announced count differs from the simplices");
  // Gather on rank 0.
  using S = mpi::Global_simplex<D>;
  const int bytes = static_cast<int>(r.simplices.size() * sizeof(S));
  std::vector<int> counts(size), displs(size);
  MPI_Gather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<S> all;
  if (rank == 0) {
    int total = 0;
    for (int q = 0; q < size; ++q) {
      displs[q] = total;
      total += counts[q];
    }
    all.resize(static_cast<std::size_t>(total) / sizeof(S));
  }
  MPI_Gatherv(r.simplices.data(), bytes, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, 0,
              MPI_COMM_WORLD);
  std::uint64_t rounds = r.statistics.rounds, max_rounds = 0, halo = r.statistics.halo_points, halo_total = 0;
  MPI_Reduce(&rounds, &max_rounds, 1, MPI_UINT64_T, MPI_MAX, 0, MPI_COMM_WORLD);
  if (regions == Regions::some && r.statistics.regions < 2 && n > 200) fail(name + ": built in one region");
  MPI_Reduce(&halo, &halo_total, 1, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
  if (rank != 0) return;

  const std::string label = name + (regions == Regions::some ? ", in regions" : "") + " (" + std::to_string(D) +
                            "D, " + std::to_string(n) + " points, " + std::to_string(size) + " ranks)";
  test::Simplex_set<D> got;
  std::vector<certify::Simplex_indices<D>> rows;
  bool oriented = true, canonical = true;
  for (const S& s : all) {
    std::array<std::uint32_t, D + 1> t;
    kernel::Orientation_points<D> refs;
    for (int i = 0; i <= D; ++i) {
      t[i] = static_cast<std::uint32_t>(s[i]);
      refs[i] = &points[s[i]];
    }
    oriented &= kernel::orientation_d<D>(refs) == kernel::POSITIVE;
    S sorted = s;
    std::sort(sorted.begin(), sorted.end());
    canonical &= std::equal(s.begin(), s.end() - 2, sorted.begin()) &&
                 ((s[D - 1] == sorted[D - 1] && s[D] == sorted[D]) || (s[D - 1] == sorted[D] && s[D] == sorted[D - 1]));
    rows.push_back(t);
    std::sort(t.begin(), t.end());
    got.insert(t);
  }
  const certify::Report report = certify::certify<kernel::Filtered_kernel_d<D>>(points, rows);
  if (!report.delaunay || !report.canonical) fail(label + ": the certifier rejects it");
  if (got.size() != all.size()) fail(label + ": " + std::to_string(all.size() - got.size()) + " simplices more than once");
  if (!oriented) fail(label + ": a simplex is not positively oriented");
  if (!canonical) fail(label + ": a simplex is not in canonical form");
  const test::Simplex_set<D> cgal = test::cgal_delaunay<D>(points);
  if (got != cgal)
    fail(label + ": differs from CGAL (" + std::to_string(got.size()) + " simplices, CGAL " +
         std::to_string(cgal.size()) + ")");
  const auto single = dewall::triangulate<D>(points);
  if (got != test::as_set<D>(single.simplices)) fail(label + ": differs from dewall::triangulate on one machine");
  std::printf("%-44s %7zu simplices, rounds %llu, halo %.1f%% of the points\n", label.c_str(), got.size(),
              static_cast<unsigned long long>(max_rounds), 100.0 * static_cast<double>(halo_total) / static_cast<double>(n));
}

/// Every rank must throw Invalid_input with `expected` as its message.
template <int D>
void check_error(const std::string& name, const std::vector<kernel::Point_d<D>>& points, const std::string& expected) {
  const std::uint64_t n = points.size();
  const std::uint64_t b = n * static_cast<std::uint64_t>(rank) / static_cast<std::uint64_t>(size);
  const std::uint64_t e = n * static_cast<std::uint64_t>(rank + 1) / static_cast<std::uint64_t>(size);
  std::string message = "(nothing thrown)";
  try {
    mpi::triangulate<D>(MPI_COMM_WORLD, std::span<const kernel::Point_d<D>>(points.data() + b, e - b), b);
  } catch (const Invalid_input& x) {
    message = x.what();
  } catch (const std::exception& x) {
    message = std::string("(not Invalid_input) ") + x.what();
  }
  if (message != expected) fail(name + ": expected \"" + expected + "\", got \"" + message + "\"");
  else if (rank == 0) std::printf("%-44s every rank: %s\n", (name + " (" + std::to_string(size) + " ranks)").c_str(), message.c_str());
}

template <int D>
std::vector<kernel::Point_d<D>> generated(io::Point_kind kind, std::size_t n, std::uint64_t seed, int planes = 0) {
  io::Generator_options o;
  o.planes = planes;
  const io::Point_table t = io::generate_points(kind, n, D, seed, o);
  return kernel::points_from_coordinates<D>(t.coordinates);
}

/// `n` uniform points, then copies of random ones, all shuffled: copies in other ranks' shares.
template <int D>
std::vector<kernel::Point_d<D>> with_duplicates(std::size_t n, std::uint64_t seed) {
  test::Rng rng(seed);
  std::vector<kernel::Point_d<D>> v = generated<D>(io::Point_kind::uniform, n, seed);
  for (std::size_t k = 0; k < n / 2; ++k) v.push_back(v[std::uniform_int_distribution<std::size_t>(0, n - 1)(rng)]);
  std::shuffle(v.begin(), v.end(), rng);
  return v;
}

/// A lattice through the origin and copies of its points with every zero
/// coordinate written −0, shuffled: −0 and +0 are one point (the
/// single-machine rule), wherever the copies land and whichever is first.
template <int D>
std::vector<kernel::Point_d<D>> signed_zeros(std::size_t n, std::uint64_t seed) {
  std::vector<kernel::Point_d<D>> v = generated<D>(io::Point_kind::grid, n, 0);
  for (auto& p : v)
    for (int j = 0; j < D; ++j) p[j] -= 3;  // the lattice straddles every axis
  const std::size_t m = v.size();
  for (std::size_t i = 0; i < m; ++i) {
    kernel::Point_d<D> q = v[i];
    bool zero = false;
    for (int j = 0; j < D; ++j)
      if (q[j] == 0) q[j] = -0.0, zero = true;
    if (zero) v.push_back(q);
  }
  test::Rng rng(seed);
  std::shuffle(v.begin(), v.end(), rng);
  return v;
}

template <int D>
void cases(std::size_t n) {
  using io::Point_kind;
  check_case<D>("uniform", generated<D>(Point_kind::uniform, n, 1), Shares::even);
  // Regions: each rank's block built region after region (a few kinds; the rest is the same code).
  check_case<D>("uniform", generated<D>(Point_kind::uniform, n, 1), Shares::growing, Regions::some);
  check_case<D>("bubbles", generated<D>(Point_kind::bubbles, n, 3), Shares::even, Regions::some);
  check_case<D>("lattice (every point ties)", generated<D>(Point_kind::grid, n, 0), Shares::gaps, Regions::some);
  check_case<D>("cospherical (lattice sphere)", generated<D>(Point_kind::lattice_sphere, n / 2, 0), Shares::even,
                Regions::some);
  check_case<D>("duplicates across ranks", with_duplicates<D>(n, 6), Shares::even, Regions::some);
  check_case<D>("uniform, uneven shares", generated<D>(Point_kind::uniform, n, 2), Shares::growing);
  check_case<D>("bubbles", generated<D>(Point_kind::bubbles, n, 3), Shares::even);
  check_case<D>("lattice (every point ties)", generated<D>(Point_kind::grid, n, 0), Shares::gaps);
  check_case<D>("cospherical (lattice sphere)", generated<D>(Point_kind::lattice_sphere, n, 0), Shares::even);
  check_case<D>("two layers", generated<D>(Point_kind::planes, n, 5, 2), Shares::growing);
  check_case<D>("duplicates across ranks", with_duplicates<D>(n, 6), Shares::even);
  test::Rng rng(7);
  check_case<D>("random lattice, many duplicates", test::lattice_points<D>(rng, n / 2, -6, 6), Shares::gaps);
  check_case<D>("-0 and +0 copies across ranks", signed_zeros<D>(n / 2, 8), Shares::even);
}

template <int D>
void error_cases() {
  auto points = generated<D>(io::Point_kind::uniform, 200, 9);
  points[190][D - 1] = std::numeric_limits<double>::quiet_NaN();  // in the last rank's share
  check_error<D>("a NaN on one rank", points, "point 190 has a non-finite coordinate (NaN or infinity)");
  auto flat = generated<D>(io::Point_kind::uniform, 200, 10);
  for (auto& p : flat) p[D - 1] = 0.5;
  check_error<D>("points in one hyperplane", flat,
                 "the points do not span E^" + std::to_string(D) + ": all 200 distinct points are " +
                     (D == 2 ? std::string("collinear") : std::string("coplanar")) + " (affine dimension " +
                     std::to_string(D - 1) + ")");
  std::vector<kernel::Point_d<D>> same(50, flat[0]);
  same[20] = flat[1];
  check_error<D>("two distinct points", same,
                 "need at least " + std::to_string(D + 1) + " distinct points in dimension " + std::to_string(D) +
                     ", got 2");
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  cases<2>(3000);
  cases<3>(2500);
  check_case<4>("uniform", generated<4>(io::Point_kind::uniform, 600, 11), Shares::even);
  check_case<4>("uniform", generated<4>(io::Point_kind::uniform, 600, 11), Shares::even, Regions::some);
  check_case<4>("lattice (every point ties)", generated<4>(io::Point_kind::grid, 600, 0), Shares::even);
  check_case<5>("uniform", generated<5>(io::Point_kind::uniform, 150, 12), Shares::growing);
  check_case<6>("uniform", generated<6>(io::Point_kind::uniform, 60, 13), Shares::even);
  error_cases<2>();
  error_cases<3>();
  int total = 0;
  MPI_Allreduce(&failures, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0) std::printf("%s: %d failure(s) on %d rank(s)\n", total ? "FAILED" : "passed", total, size);
  MPI_Finalize();
  return total == 0 ? 0 : 1;
}
