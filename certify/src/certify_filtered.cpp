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

template <int D>
Share_report<D> certify_share_filtered(std::span<const kernel::Point_d<D>> points, Simplex_source<D>& simplices, Share share,
                                       const Options& options) {
  const kernel::Fp_environment_guard guard;
  return Certifier<kernel::Filtered_kernel_d<D>>({}, points, options).run_share(simplices, share);
}

template <int D>
Report merge_shares_filtered(std::span<const kernel::Point_d<D>> points, std::span<const Share_report<D>> shares,
                             const Options& options) {
  const kernel::Fp_environment_guard guard;
  return Certifier<kernel::Filtered_kernel_d<D>>({}, points, options).merge_shares(shares);
}

#define DEWALL_INSTANTIATE_CERTIFY(D)                                                                                    \
  template Report certify_filtered<D>(std::span<const kernel::Point_d<D>>, Simplex_source<D>&, const Options&);            \
  template Share_report<D> certify_share_filtered<D>(std::span<const kernel::Point_d<D>>, Simplex_source<D>&, Share,       \
                                                     const Options&);                                                     \
  template Report merge_shares_filtered<D>(std::span<const kernel::Point_d<D>>, std::span<const Share_report<D>>,          \
                                           const Options&);
DEWALL_FOR_EACH_DIMENSION(DEWALL_INSTANTIATE_CERTIFY)

}  // namespace dewall::certify::detail
