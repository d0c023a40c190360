// certify() with the project's kernel, compiled once with the project's flags
// for D = 2 … 6 (floating_point.hpp says why).
#include "dewall/certify/certify.hpp"
#include "dewall/kernel/filtered_predicate.hpp"  // refuses to build under unsafe flags

namespace dewall::certify::detail {

template <int D>
Report certify_filtered(std::span<const kernel::Point_d<D>> points, std::span<const Simplex_indices<D>> simplices,
                        const Options& options) {
  const kernel::Fp_environment_guard guard;
  return Certifier<kernel::Filtered_kernel_d<D>>({}, points, simplices, options).run();
}

template Report certify_filtered<2>(std::span<const kernel::Point_d<2>>, std::span<const Simplex_indices<2>>,
                                    const Options&);
template Report certify_filtered<3>(std::span<const kernel::Point_d<3>>, std::span<const Simplex_indices<3>>,
                                    const Options&);
template Report certify_filtered<4>(std::span<const kernel::Point_d<4>>, std::span<const Simplex_indices<4>>,
                                    const Options&);
template Report certify_filtered<5>(std::span<const kernel::Point_d<5>>, std::span<const Simplex_indices<5>>,
                                    const Options&);
template Report certify_filtered<6>(std::span<const kernel::Point_d<6>>, std::span<const Simplex_indices<6>>,
                                    const Options&);

}  // namespace dewall::certify::detail
