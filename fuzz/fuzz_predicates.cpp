// fuzz_predicates: every stage of both predicates against a plain GMP rational
// evaluation, and the perturbed sphere test against CGAL's, in D = 2 … 6.
//
// Input: [dimension] [coordinate style header] [query count] then D + 1 simplex
// points and 1 … 4 query points, each either decoded afresh or (one byte says)
// a copy of an earlier point, because duplicate points are the inputs where the
// predicates' preconditions and the perturbation's tie-breaking meet.
//
// Properties checked, for each query q:
//  1. orientation_d of the simplex: the filter, the interval and the
//     running-error stages, when they answer, the exact stage and the filtered
//     predicate all equal GMP.
//  2. side_of_oriented_sphere_d (unperturbed): the same, against GMP.
//  3. With the simplex made positive (swap two vertices when negative) and q
//     distinct from its vertices:
//       - the _sos answer is never ON_ORIENTED_BOUNDARY, equals the plain
//         answer when that is non-zero, and is invariant under an even
//         permutation of the simplex (the perturbation depends on the point
//         set, not on the order);
//       - in 2D and 3D it equals CGAL's perturbed predicate
//         (Triangulation_2::side_of_oriented_circle(…, true),
//         Delaunay_triangulation_3::side_of_oriented_sphere(…, true)).
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/side_of_sphere.hpp"
#include "fuzz_common.hpp"
#include "support/gmp_reference.hpp"

namespace {

using namespace dewall::kernel;
using dewall::fuzz::Byte_source;
using dewall::fuzz::Coordinate_decoder;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

// CGAL's 3D perturbed predicate is protected; a derived class reaches it.
struct Delaunay_3 : CGAL::Delaunay_triangulation_3<Epick> {
  using CGAL::Delaunay_triangulation_3<Epick>::side_of_oriented_sphere;
};

template <int D>
Oriented_side cgal_perturbed(const std::array<Point_d<D>, D + 1>& s, const Point_d<D>& q) {
  if constexpr (D == 2) {
    static const CGAL::Delaunay_triangulation_2<Epick> t;
    auto P = [](const Point_d<2>& p) { return Epick::Point_2(p[0], p[1]); };
    return static_cast<Oriented_side>(t.side_of_oriented_circle(P(s[0]), P(s[1]), P(s[2]), P(q), true));
  } else {
    static const Delaunay_3 t;
    auto P = [](const Point_d<3>& p) { return Epick::Point_3(p[0], p[1], p[2]); };
    return static_cast<Oriented_side>(
        t.side_of_oriented_sphere(P(s[0]), P(s[1]), P(s[2]), P(s[3]), P(q), true));
  }
}

template <int D>
void check_orientation(const std::array<Point_d<D>, D + 1>& s) {
  Orientation_points<D> refs;
  for (int i = 0; i <= D; ++i) refs[static_cast<std::size_t>(i)] = &s[static_cast<std::size_t>(i)];
  const Sign expected = dewall::test::gmp_orientation<D>(s);
  if (const auto f = orientation_d_filter<D>(refs)) DEWALL_FUZZ_CHECK(*f == expected);
  if (const auto f = orientation_d_interval<D>(refs)) DEWALL_FUZZ_CHECK(*f == expected);
  if (const auto f = orientation_d_running_error<D>(refs)) DEWALL_FUZZ_CHECK(*f == expected);
  DEWALL_FUZZ_CHECK(orientation_d_exact<D>(refs) == expected);
  DEWALL_FUZZ_CHECK(orientation_d<D>(refs) == expected);
}

template <int D>
Sphere_points<D> sphere_refs(const std::array<Point_d<D>, D + 1>& s, const Point_d<D>& q) {
  Sphere_points<D> refs;
  for (int i = 0; i <= D; ++i) refs[static_cast<std::size_t>(i)] = &s[static_cast<std::size_t>(i)];
  refs[D + 1] = &q;
  return refs;
}

template <int D>
void check_sphere(std::array<Point_d<D>, D + 1> s, const Point_d<D>& q) {
  const auto refs = sphere_refs<D>(s, q);
  const Oriented_side expected = dewall::test::gmp_side_of_oriented_sphere<D>(s, q);
  if (const auto f = side_of_oriented_sphere_d_filter<D>(refs)) DEWALL_FUZZ_CHECK(static_cast<Oriented_side>(*f) == expected);
  if (const auto f = side_of_oriented_sphere_d_interval<D>(refs)) DEWALL_FUZZ_CHECK(static_cast<Oriented_side>(*f) == expected);
  if (const auto f = side_of_oriented_sphere_d_running_error<D>(refs))
    DEWALL_FUZZ_CHECK(static_cast<Oriented_side>(*f) == expected);
  DEWALL_FUZZ_CHECK(static_cast<Oriented_side>(side_of_oriented_sphere_d_exact<D>(refs)) == expected);
  DEWALL_FUZZ_CHECK(side_of_oriented_sphere_d<D>(refs) == expected);

  // The perturbed test: only under its preconditions.
  Sign o = dewall::test::gmp_orientation<D>(s);
  if (o == ZERO) return;
  for (const auto& p : s)
    if (p == q) return;
  if (o == NEGATIVE) std::swap(s[0], s[1]);
  const Oriented_side plain = dewall::test::gmp_side_of_oriented_sphere<D>(s, q);
  const Oriented_side sos = side_of_oriented_sphere_d_sos<D>(sphere_refs<D>(s, q));
  DEWALL_FUZZ_CHECK(sos != ON_ORIENTED_BOUNDARY);
  if (plain != ON_ORIENTED_BOUNDARY) DEWALL_FUZZ_CHECK(sos == plain);
  // An even permutation (the 3-cycle 0 → 1 → 2) keeps the orientation, so the
  // perturbed answer must not change.
  std::array<Point_d<D>, D + 1> cycled = s;
  std::rotate(cycled.begin(), cycled.begin() + 1, cycled.begin() + 3);
  DEWALL_FUZZ_CHECK(side_of_oriented_sphere_d_sos<D>(sphere_refs<D>(cycled, q)) == sos);
  if constexpr (D <= 3) DEWALL_FUZZ_CHECK(cgal_perturbed<D>(s, q) == sos);
}

template <int D>
void run(Byte_source& in) {
  const Coordinate_decoder decoder = Coordinate_decoder::read(in);
  const int queries = in.integer(1, 4);
  std::vector<Point_d<D>> points;
  for (int i = 0; i < D + 1 + queries; ++i) {
    // One byte in eight repeats an earlier point (duplicates are legal input).
    const std::uint8_t b = in.byte();
    if (!points.empty() && b % 8 == 7) points.push_back(points[b / 8 % points.size()]);
    else points.push_back(dewall::fuzz::read_point<D>(in, decoder));
  }
  std::array<Point_d<D>, D + 1> simplex;
  std::copy_n(points.begin(), D + 1, simplex.begin());
  check_orientation<D>(simplex);
  for (int k = 0; k < queries; ++k) check_sphere<D>(simplex, points[static_cast<std::size_t>(D + 1 + k)]);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Byte_source in(data, size);
  dewall::fuzz::with_dimension(in.integer(2, 6), [&]<int D>() { run<D>(in); });
  return 0;
}
