// The predicates compiled once, with the project's flags, for D = 2 … 6: what a
// translation unit compiled with unsafe floating-point flags calls instead of
// compiling the predicates itself (floating_point.hpp). Any file may call
// them; files with safe flags usually inline their own copies.
#include "dewall/kernel/filtered_predicate.hpp"  // first: refuses to build under unsafe flags
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/side_of_sphere.hpp"

namespace dewall::kernel {

#define DEWALL_INSTANTIATE_PREDICATES(D)                                                     \
  template std::optional<Sign> orientation_d_filter<D>(const Orientation_points<D>&);        \
  template std::optional<Sign> orientation_d_interval<D>(const Orientation_points<D>&);      \
  template Sign orientation_d_exact<D>(const Orientation_points<D>&);                        \
  template Sign orientation_d<D>(const Orientation_points<D>&);                              \
  template std::optional<Sign> side_of_oriented_sphere_d_filter<D>(const Sphere_points<D>&);   \
  template std::optional<Sign> side_of_oriented_sphere_d_interval<D>(const Sphere_points<D>&); \
  template Sign side_of_oriented_sphere_d_exact<D>(const Sphere_points<D>&);                   \
  template Oriented_side side_of_oriented_sphere_d<D>(const Sphere_points<D>&);                \
  template Oriented_side side_of_oriented_sphere_d_sos<D>(const Sphere_points<D>&);

DEWALL_INSTANTIATE_PREDICATES(2)
DEWALL_INSTANTIATE_PREDICATES(3)
DEWALL_INSTANTIATE_PREDICATES(4)
DEWALL_INSTANTIATE_PREDICATES(5)
DEWALL_INSTANTIATE_PREDICATES(6)

}  // namespace dewall::kernel
