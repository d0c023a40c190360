// certify() with the project's kernel, compiled once with the project's flags
// for D = 2 … 6 (floating_point.hpp says why).
#include "dewall/certify/certify.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/filtered_predicate.hpp"  // refuses to build under unsafe flags

namespace dewall::certify::detail {

template <int D>
Report certify_filtered(std::span<const kernel::Point_d<D>> points, Simplex_source<D>& simplices, const Options& options) {
  const kernel::Fp_environment_guard guard;
  return Certifier<kernel::Filtered_kernel_d<D>>({}, points, options).run(simplices);
}

#define DEWALL_INSTANTIATE_CERTIFY(D)                                                                         \
  template Report certify_filtered<D>(std::span<const kernel::Point_d<D>>, Simplex_source<D>&, const Options&);
DEWALL_FOR_EACH_DIMENSION(DEWALL_INSTANTIATE_CERTIFY)

}  // namespace dewall::certify::detail
