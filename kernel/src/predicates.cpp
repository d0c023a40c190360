// The predicates compiled once, with the project's flags, for D = 2 … 6: what a
// translation unit compiled with unsafe floating-point flags calls instead of
// compiling the predicates itself, and the only out-of-line copies of their
// later stages in any program (floating_point.hpp; the headers declare these
// instantiations extern).
#include "dewall/kernel/filtered_predicate.hpp"  // first: refuses to build under unsafe flags
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/side_of_sphere.hpp"

namespace dewall::kernel {

#define DEWALL_DEFINE_PREDICATES(D)   \
  DEWALL_ORIENTATION_INSTANTIATION(, D) \
  DEWALL_SIDE_OF_SPHERE_INSTANTIATION(, D)
DEWALL_FOR_EACH_DIMENSION(DEWALL_DEFINE_PREDICATES)

}  // namespace dewall::kernel
