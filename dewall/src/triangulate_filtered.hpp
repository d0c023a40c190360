// The definition behind detail::triangulate_filtered (dewall.hpp), included only
// by this folder's files, each of which instantiates it for one dimension, so
// that the dimensions compile in parallel. Not installed: a user's file never
// compiles it (floating_point.hpp says why).
#pragma once

#include "dewall/dewall.hpp"
#include "dewall/kernel/filtered_predicate.hpp"  // refuses to build under unsafe flags

namespace dewall::detail {

template <int D>
Statistics triangulate_filtered(std::span<const kernel::Point_d<D>> points, const Options& options,
                                std::vector<Simplex<D>>& simplices, std::vector<std::uint8_t>* wall_levels) {
  return triangulate_generic<kernel::Filtered_kernel_d<D>>({}, points, options, simplices, wall_levels);
}

}  // namespace dewall::detail
