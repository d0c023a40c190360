// dewall: Delaunay triangulation in E^D (D = 2 … 6) by the DeWall algorithm,
// P. Cignoni, C. Montani, R. Scopigno, "DeWall: A fast divide and conquer
// Delaunay triangulation algorithm in E^d", Computer-Aided Design 30(5), 1998.
//
// The output is the Delaunay triangulation under CGAL's symbolic perturbation:
// the same simplices as CGAL's Delaunay_triangulation_2/_3 and dD
// Delaunay_triangulation, on every input, degenerate ones included.
//
// Where each step of the paper lives:
//   splitting plane α ............ detail/split.hpp
//   DeWall recursion and wall .... detail/wall.hpp
//   MakeFirstSimplex ............. detail/first_simplex.hpp
//   active face lists, Update .... detail/active_face_list.hpp, detail/face.hpp
//   MakeSimplex (dd-nearest) ..... detail/make_simplex.hpp, detail/simplex_sphere.hpp,
//                                  detail/face_side_filter.hpp, detail/pencil_rank.hpp
//   uniform grid (here a kd-tree)  detail/kd_tree.hpp
//   input checks, duplicates ..... detail/input.hpp
//   the whole run, any kernel .... detail/triangulate_generic.hpp
//
// With the project's kernel (Filtered_kernel_d, the default) the triangulation
// runs in the compiled library dewall::dewall (dewall/src/), built with the
// project's floating-point flags, so it is exact whatever flags the caller
// compiles with (-ffast-math, -Ofast included) and whatever floating-point
// environment the caller runs in. With another kernel the algorithm is compiled
// in the caller's file, which then must not use such flags (floating_point.hpp).
#pragma once

#include <tbb/task_arena.h>

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "dewall/error.hpp"
#include "dewall/kernel/concepts.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/options.hpp"
#ifndef DEWALL_UNSAFE_FP_FLAGS
#include "dewall/detail/triangulate_generic.hpp"
#endif

namespace dewall {

/// A simplex as D + 1 indices into the input, positively oriented.
template <int D>
using Simplex = std::array<std::uint32_t, D + 1>;

namespace detail {

/// The triangulation with the project's kernel, compiled into dewall::dewall
/// (dewall/src/triangulate_filtered.hpp, instantiated by triangulate_filtered_<D>.cpp
/// for D = 2 … 6); as triangulate_generic.
template <int D>
Statistics triangulate_filtered(std::span<const kernel::Point_d<D>> points, const Options& options,
                                std::vector<Simplex<D>>& simplices, std::vector<std::uint8_t>* wall_levels);

template <class>
inline constexpr bool always_false = false;

/// Runs the triangulation with kernel K: compiled for the project's kernel
/// (with the choice of engine, Options::engine), here for any other (DeWall).
template <kernel::DelaunayKernel K>
Statistics run_engine(std::span<const typename K::Point_d> points, const Options& options, const K& k,
                             std::vector<Simplex<K::dimension>>& simplices, std::vector<std::uint8_t>* wall_levels) {
  if constexpr (std::is_same_v<K, kernel::Filtered_kernel_d<K::dimension>>) {
    (void)k;
    return triangulate_filtered<K::dimension>(points, options, simplices, wall_levels);
  } else {
#ifdef DEWALL_UNSAFE_FP_FLAGS
    static_assert(always_false<K>,
                  "dewall: triangulating with a kernel other than Filtered_kernel_d compiles the algorithm "
                  "in this file, which is compiled with " DEWALL_UNSAFE_FP_FLAGS "; its error bounds need "
                  "IEEE arithmetic. Compile this file without that flag, or use the default kernel "
                  "(dewall::triangulate<D>), which is compiled into the dewall library and works whatever "
                  "your flags are.");
    return {};
#else
    if (options.engine == Engine::cgal || options.engine == Engine::hybrid)
      throw std::invalid_argument(std::string("dewall: Engine::") + engine_name(options.engine) +
                                  " needs the project's kernel (Filtered_kernel_d)");
    return triangulate_generic<K>(k, points, options, simplices, wall_levels);
#endif
  }
}

/// run_engine in an arena of Options::threads threads, when that is given.
template <kernel::DelaunayKernel K>
Statistics run_triangulation(std::span<const typename K::Point_d> points, const Options& options, const K& k,
                             std::vector<Simplex<K::dimension>>& simplices, std::vector<std::uint8_t>* wall_levels) {
  if (options.threads < 0)
    throw std::invalid_argument("dewall: Options::threads must be 0 (all cores) or positive, not " +
                                std::to_string(options.threads));
  if (options.threads == 0) return run_engine<K>(points, options, k, simplices, wall_levels);
  tbb::task_arena arena(options.threads);
  return arena.execute([&] { return run_engine<K>(points, options, k, simplices, wall_levels); });
}

}  // namespace detail

/// The Delaunay triangulation of `points`, handed to `sink(simplex)` once for
/// each simplex (a dewall::Simplex<D> of input indices, positively oriented), in
/// DeWall's depth-first order, then the hybrid's gift-wrapped closing
/// simplices (the same for any number of threads). The
/// simplices are handed over once the triangulation is complete; true streaming
/// (memory near the size of the walls) is future work. A sink callable as
/// sink(simplex, level) also receives the recursion level of the wall that
/// built the simplex (0: the first wall; the paper's Figures 2, 4, 5).
/// When the incremental engine built them (Options::engine, Statistics::engine)
/// the order is CGAL's and every level is 0.
/// \throws Invalid_input for non-finite coordinates, fewer than D + 1 distinct
/// points, or points that do not span E^D.
/// Complexity: expected O(n log n) on uniformly distributed points; with
/// Engine::automatic (the default) at most a small multiple of the incremental
/// construction's on any input.
template <kernel::DelaunayKernel K, class Sink>
Statistics triangulate_to(std::span<const typename K::Point_d> points, Sink&& sink, const Options& options = {},
                          const K& k = {}) {
  constexpr int D = K::dimension;
  constexpr bool wants_level = std::is_invocable_v<Sink, const Simplex<D>&, int>;
  std::vector<Simplex<D>> simplices;
  std::vector<std::uint8_t> levels;
  const Statistics st = detail::run_triangulation<K>(points, options, k, simplices, wants_level ? &levels : nullptr);
  for (std::size_t i = 0; i < simplices.size(); ++i) {
    if constexpr (wants_level) sink(simplices[i], static_cast<int>(levels[i]));
    else sink(simplices[i]);
  }
  return st;
}

/// The triangulation as a list of simplices.
template <int D>
struct Triangulation {
  std::vector<Simplex<D>> simplices;
  Statistics statistics;
};

/// The Delaunay triangulation of `points` with kernel K (default: the project's
/// filtered exact kernel). See triangulate_to.
template <kernel::DelaunayKernel K>
Triangulation<K::dimension> triangulate(std::span<const typename K::Point_d> points, const Options& options = {},
                                        const K& k = {}) {
  Triangulation<K::dimension> t;
  t.statistics = detail::run_triangulation<K>(points, options, k, t.simplices, nullptr);
  return t;
}

template <int D>
Triangulation<D> triangulate(std::span<const kernel::Point_d<D>> points, const Options& options = {}) {
  return triangulate<kernel::Filtered_kernel_d<D>>(points, options);
}
template <int D>
Triangulation<D> triangulate(const std::vector<kernel::Point_d<D>>& points, const Options& options = {}) {
  return triangulate<D>(std::span<const kernel::Point_d<D>>(points), options);
}

}  // namespace dewall
