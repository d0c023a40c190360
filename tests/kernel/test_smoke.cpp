#include <catch2/catch.hpp>
#include "dewall/kernel/filtered_kernel_d.hpp"
TEST_CASE("smoke: unit square is cocircular") {
  using namespace dewall::kernel;
  const Point_d<2> a{{0, 0}}, b{{1, 0}}, c{{0, 1}}, d{{1, 1}};
  CHECK(side_of_oriented_sphere_d(a, b, c, d) == ON_ORIENTED_BOUNDARY);
}
