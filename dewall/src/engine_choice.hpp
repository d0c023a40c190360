// The engine Options::engine names, for the project's kernel: the definition
// behind detail::run_chosen_engine (dewall.hpp), included only by the
// engine_choice_<D>.cpp files of this folder, each of which instantiates it
// for one dimension, so that the dimensions compile in parallel. Not
// installed: a user's file never compiles it (floating_point.hpp says why).
//
// The engines, one file each:
//   DeWall, the hybrid .......... dewall/detail/walls/dewall_engine.hpp (any kernel)
//   automatic ................... automatic_engine.hpp (the choice and the hand-over)
//   the project's incremental ... incremental_engine.hpp, .cpp
//   CGAL's incremental .......... cgal_engine.hpp, .cpp
//   which incremental, where .... incremental_choice.hpp (Options::incremental_engine)
#pragma once

#include "automatic_engine.hpp"
#include "cgal_engine.hpp"
#include "incremental_choice.hpp"
#include "incremental_engine.hpp"
#include "dewall/detail/walls/dewall_engine.hpp"
#include "dewall/dewall.hpp"
#include "dewall/kernel/filtered_predicate.hpp"  // refuses to build under unsafe flags

namespace dewall::detail {

/// The engine Options::engine names. The incremental engine's simplices get
/// wall level 0 (it builds no walls); a hybrid region's, its recursion level.
template <int D>
Statistics run_chosen_engine(std::span<const kernel::Point_d<D>> points, const Options& options,
                             Simplex_output<D>& output) {
  using K = kernel::Filtered_kernel_d<D>;
  const Incremental_choice<D> incremental(options);
  switch (options.engine) {
    case Engine::cgal: return triangulate_with_cgal<D>(points, output);
    case Engine::incremental: return triangulate_incremental<D>(points, output);
    case Engine::dewall: return triangulate_dewall<K>({}, points, options, output);
    case Engine::hybrid: return triangulate_hybrid<K>({}, points, options, output, Hybrid<D>{incremental.regions()});
    case Engine::automatic: break;
  }
  return triangulate_automatic<D>(points, options, output, incremental);
}

}  // namespace dewall::detail

/// The explicit instantiation for dimension D, one per engine_choice_<D>.cpp
/// (one file per D so that the dimensions compile in parallel).
#define DEWALL_INSTANTIATE_ENGINE_CHOICE(D)                                                             \
  template dewall::Statistics dewall::detail::run_chosen_engine<D>(std::span<const kernel::Point_d<D>>, \
                                                                   const Options&, Simplex_output<D>&);
