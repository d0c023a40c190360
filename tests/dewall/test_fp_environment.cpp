// The caller's floating-point environment cannot change an answer: with
// flush-to-zero and denormals-are-zero on (what linking with -ffast-math or
// -Ofast does to a whole process, through crtfastmath.o) and rounding upward,
// the predicates still give GMP's sign, triangulate still gives CGAL's cells,
// certify still says canonical, and the caller gets its environment back
// (kernel/include/dewall/kernel/floating_point.hpp). The compile-flag side is
// tested through the installed package by the fp_flags_* tests (examples/).
#include <catch2/catch.hpp>

#include <cfenv>
#include <cmath>
#include <vector>

#include "dewall/certify/certify.hpp"
#include "dewall/dewall.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/side_of_sphere.hpp"
#include "support/cgal_reference.hpp"
#include "support/gmp_reference.hpp"

#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace {

using dewall::kernel::Point_d;

/// Sets FTZ and DAZ (x86-64) and upward rounding for its lifetime.
class Hostile_environment {
 public:
  Hostile_environment() {
#if defined(__x86_64__)
    saved_csr_ = _mm_getcsr();
    _mm_setcsr(saved_csr_ | 0x8040u);  // FTZ (bit 15) and DAZ (bit 6)
#endif
    saved_rounding_ = std::fegetround();
    std::fesetround(FE_UPWARD);
  }
  ~Hostile_environment() {
    std::fesetround(saved_rounding_);
#if defined(__x86_64__)
    _mm_setcsr(saved_csr_);
#endif
  }
  /// True while the environment is still the hostile one (the library put it back).
  static bool in_force() {
    bool ok = std::fegetround() == FE_UPWARD;
#if defined(__x86_64__)
    ok = ok && (_mm_getcsr() & 0x8040u) == 0x8040u;
#endif
    return ok;
  }

 private:
  unsigned saved_csr_ = 0;
  int saved_rounding_ = FE_TONEAREST;
};

/// An n^D lattice in which every fifth point has one coordinate moved up by one
/// ulp: 0 becomes 2^-1074, the smallest subnormal, which DAZ reads as 0.
template <int D>
std::vector<Point_d<D>> nudged_lattice(int n) {
  std::vector<Point_d<D>> points;
  std::array<int, D> c{};
  for (int k = 0;; ++k) {
    Point_d<D> p;
    for (int j = 0; j < D; ++j) p[j] = c[j];
    if (k % 5 == 0) p[k % D] = std::nextafter(p[k % D], 1e300);
    points.push_back(p);
    int j = 0;
    for (; j < D && ++c[j] == n; ++j) c[j] = 0;
    if (j == D) return points;
  }
}

}  // namespace

TEST_CASE("predicates are exact under flush-to-zero and upward rounding", "[kernel][fp-environment]") {
  using P = Point_d<3>;
  const P o{{0, 0, 0}}, x{{0x1p-1074, 0, 0}}, y{{0, 1, 0}}, z{{0, 0, 1}}, q{{0x1p-1074, 0x1p-1074, 0}};
  const std::array<P, 4> simplex{o, x, y, z};
  // The references first: GMP's conversion from double is floating-point code too.
  const auto orientation = dewall::test::gmp_orientation<3>(simplex);
  const auto side = dewall::test::gmp_side_of_oriented_sphere<3>(simplex, q);
  REQUIRE(orientation == dewall::kernel::POSITIVE);
  const Hostile_environment hostile;
  // Under DAZ the subnormal difference reads as 0 and the answer would be ZERO.
  CHECK(dewall::kernel::orientation_d<3>(o, x, y, z) == orientation);
  CHECK(dewall::kernel::orientation_d_exact<3>({&o, &x, &y, &z}) == orientation);
  CHECK(dewall::kernel::side_of_oriented_sphere_d<3>(o, x, y, z, q) == side);
  CHECK(Hostile_environment::in_force());  // the caller's environment is back
}

TEMPLATE_TEST_CASE_SIG("triangulate and certify are exact under flush-to-zero and upward rounding",
                       "[dewall][fp-environment]", ((int D), D), 2, 3) {
  const auto points = nudged_lattice<D>(D == 2 ? 12 : 6);
  const auto expected = dewall::test::cgal_delaunay<D>(points);  // in the default environment
  const Hostile_environment hostile;
  for (int depth : {0, 6}) {  // serial, and parallel (worker threads have their own environment)
    const auto t = dewall::triangulate<D>(points, dewall::Options{.parallel_depth = depth});
    CHECK(dewall::test::as_set<D>(t.simplices) == expected);
    const auto report = dewall::certify::certify<dewall::kernel::Filtered_kernel_d<D>>(points, t.simplices);
    CHECK(report.canonical);
  }
  CHECK(Hostile_environment::in_force());
}
