// dewall command-line tool (placeholder until the triangulator lands: a kernel demo).
#include <cstdio>
#include <cstring>

#include "dewall/kernel/filtered_kernel_d.hpp"

int main(int argc, char** argv) {
  using namespace dewall::kernel;
  if (argc > 1 && std::strcmp(argv[1], "demo") != 0) {
    std::fprintf(stderr, "dewall: unknown command '%s'\n", argv[1]);
    return 2;
  }
  const Point_d<2> a{{0, 0}}, b{{1, 0}}, c{{0, 1}}, d{{1, 1}};
  std::printf("orientation(a,b,c) = %d; side_of_oriented_circle(a,b,c,d) = %d, perturbed: %d\n",
              orientation_d(a, b, c), side_of_oriented_sphere_d(a, b, c, d), side_of_oriented_sphere_d_sos(a, b, c, d));
  return 0;
}
