// dewall: Delaunay triangulation in E^D (D = 2 … 6) by the DeWall algorithm,
// P. Cignoni, C. Montani, R. Scopigno, "DeWall: A fast divide and conquer
// Delaunay triangulation algorithm in E^d", Computer-Aided Design 30(5), 1998.
//
// The output is the Delaunay triangulation under CGAL's symbolic perturbation:
// the same simplices as CGAL's Delaunay_triangulation_2/_3 and dD
// Delaunay_triangulation, on every input, degenerate ones included.
//
// Where each step of the paper lives:
//   splitting plane α ............ detail/walls/split.hpp
//   DeWall recursion and wall .... detail/walls/wall.hpp
//   MakeFirstSimplex ............. detail/walls/first_simplex.hpp
//   active face lists, Update .... detail/walls/active_face_list.hpp, detail/walls/face.hpp
//   MakeSimplex (dd-nearest) ..... detail/walls/make_simplex.hpp, detail/walls/simplex_sphere.hpp,
//                                  detail/walls/face_side_filter.hpp, detail/walls/pencil_rank.hpp
//   uniform grid (here a kd-tree)  detail/walls/kd_tree.hpp
//   input checks, duplicates ..... detail/common/input.hpp
//   the whole run, any kernel .... detail/walls/dewall_engine.hpp (DeWall, the hybrid)
//   which engine runs ............ dewall/src/engine_choice.hpp (compiled; automatic_engine.hpp)
//
// With the project's kernel (Filtered_kernel_d, the default) the triangulation
// runs in the compiled library dewall::dewall (dewall/src/), built with the
// project's floating-point flags, so it is exact whatever flags the caller
// compiles with (-ffast-math, -Ofast included) and whatever floating-point
// environment the caller runs in. With another kernel the algorithm is compiled
// in the caller's file, which then must not use such flags (floating_point.hpp).
#pragma once

#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

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
#include "dewall/detail/common/progress_meter.hpp"
#include "dewall/detail/common/simplex_output.hpp"
#include "dewall/options.hpp"
#ifndef DEWALL_UNSAFE_FP_FLAGS
#include "dewall/detail/walls/dewall_engine.hpp"
#endif

namespace dewall {

/// A simplex as D + 1 indices into the input, positively oriented.
template <int D>
using Simplex = detail::Simplex<D>;

namespace detail {

/// The triangulation with the project's kernel by the engine Options::engine
/// names, compiled into dewall::dewall (dewall/src/engine_choice.hpp,
/// instantiated by engine_choice_<D>.cpp for D = 2 … 6); as triangulate_walls.
template <int D>
Statistics run_chosen_engine(std::span<const kernel::Point_d<D>> points, const Options& options,
                                Simplex_output<D>& output);

template <class>
inline constexpr bool always_false = false;

/// Runs the triangulation with kernel K: compiled for the project's kernel
/// (with the choice of engine, Options::engine), here for any other (DeWall).
template <kernel::DelaunayKernel K>
Statistics run_engine(std::span<const typename K::Point_d> points, const Options& options, const K& k,
                      Simplex_output<K::dimension>& output) {
  if constexpr (std::is_same_v<K, kernel::Filtered_kernel_d<K::dimension>>) {
    (void)k;
    return run_chosen_engine<K::dimension>(points, options, output);
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
    if (options.engine == Engine::cgal || options.engine == Engine::incremental || options.engine == Engine::hybrid)
      throw std::invalid_argument(std::string("dewall: Engine::") + engine_name(options.engine) +
                                  " needs the project's kernel (Filtered_kernel_d)");
    return triangulate_dewall<K>(k, points, options, output);
#endif
  }
}

/// `output` with the meter of Options::progress (progress_meter.hpp).
template <int D>
class Metered_output final : public Simplex_output<D> {
 public:
  Metered_output(Simplex_output<D>& output, Progress_meter& meter) : output_(output), meter_(meter) {}
  Cell_graph_output<D>* cell_graph() override { return output_.cell_graph(); }
  void expect(std::size_t count) override { output_.expect(count); }
  void put(std::span<const Built_simplex<D>> block) override { output_.put(block); }
  void input_no_longer_read() override { output_.input_no_longer_read(); }
  bool frees_input() const override { return output_.frees_input(); }
  Progress_meter* progress() override { return &meter_; }

 private:
  Simplex_output<D>& output_;
  Progress_meter& meter_;
};

/// run_engine in an arena of Options::threads threads, when that is given,
/// and in a task group context of its own: a caller's TBB work being
/// cancelled must not reach our tasks (a parallel_invoke in a cancelled
/// context returns without running them, and the triangulation would have
/// holes); it then waits for the triangulation to finish.
template <kernel::DelaunayKernel K>
Statistics run_triangulation(std::span<const typename K::Point_d> points, const Options& options, const K& k,
                             Simplex_output<K::dimension>& output) {
  if (options.threads < 0)
    throw std::invalid_argument("dewall: Options::threads must be 0 (all cores) or positive, not " +
                                std::to_string(options.threads));
  auto isolated = [&] {
    tbb::task_group_context context(tbb::task_group_context::isolated);
    tbb::task_group group(context);
    Statistics statistics;
    if (options.progress) {
      Progress_meter meter(options.progress, points.size());
      Metered_output<K::dimension> metered(output, meter);
      group.run_and_wait([&] { statistics = run_engine<K>(points, options, k, metered); });
      meter.complete();
    } else {
      group.run_and_wait([&] { statistics = run_engine<K>(points, options, k, output); });
    }
    return statistics;
  };
  // More threads than the process may run on (its affinity mask) are capped:
  // TBB would print a warning and use no more anyway, and the output is the
  // same for every thread count.
  const int usable = tbb::info::default_concurrency();
  if (options.threads == 0 || options.threads >= usable) return isolated();
  tbb::task_arena arena(options.threads);
  return arena.execute(isolated);
}

/// `options` for a caller who asks for wall levels: Engine::automatic
/// becomes Engine::dewall (the automatic choice may build small inputs without
/// a wall). \throws std::invalid_argument for an engine that builds no walls.
inline Options options_with_walls(Options options) {
  if (options.engine == Engine::automatic) options.engine = Engine::dewall;
  if (options.engine == Engine::incremental || options.engine == Engine::cgal)
    throw std::invalid_argument(std::string("dewall: wall levels come from DeWall's walls, and Engine::") +
                                engine_name(options.engine) + " builds none (use Engine::dewall or Engine::hybrid)");
  return options;
}

/// Hands each simplex of the engine's blocks to a caller's sink: sink(simplex),
/// or sink(simplex, level) when it takes the wall's recursion level.
template <int D, class Sink>
class Sink_output final : public Simplex_output<D> {
 public:
  explicit Sink_output(Sink& sink) : sink_(sink) {}
  Cell_graph_output<D>* cell_graph() override {
    if constexpr (requires { sink_.cell_graph(); }) return sink_.cell_graph();
    else return nullptr;
  }
  void expect(std::size_t count) override {
    if constexpr (requires { sink_.reserve(count); }) sink_.reserve(count);
  }
  void input_no_longer_read() override {
    if constexpr (requires { sink_.input_no_longer_read(); }) sink_.input_no_longer_read();
  }
  bool frees_input() const override { return requires { sink_.input_no_longer_read(); }; }
  void put(std::span<const Built_simplex<D>> block) override {
    for (const Built_simplex<D>& s : block) {
      if constexpr (std::is_invocable_v<Sink&, const Simplex<D>&, int>) sink_(s.vertices, static_cast<int>(s.wall_level));
      else sink_(s.vertices);
    }
  }

 private:
  Sink& sink_;
};

}  // namespace detail

/// The Delaunay triangulation of `points`, handed to `sink(simplex)` once for
/// each simplex (a dewall::Simplex<D> of input indices, positively oriented).
/// A sink callable as sink(simplex, level) also receives the recursion level
/// of the wall that built the simplex (0: the first wall; the paper's
/// Figures 2, 4, 5). Levels come from walls: with such a sink,
/// Engine::automatic runs DeWall's walls all the way down (Engine::dewall),
/// Engine::hybrid gives each region's simplices the region's level, and
/// Engine::incremental and Engine::cgal, which build no walls, are refused
/// (std::invalid_argument).
///
/// By default the simplices are handed over once the triangulation is
/// complete, in DeWall's depth-first order, then the hybrid's gift-wrapped
/// closing simplices: the same order for any number of threads; when the
/// incremental engine built them (Options::engine, Statistics::engine), in
/// CGAL's order. With Options::stream they are handed over as they are built
/// and not kept (memory: the points, the search structure and the regions in
/// progress); the set is the same, and with one thread (Options::threads = 1)
/// so is the order, given the same Options::region_points (by default
/// streaming takes other regions above 131072 points, and Engine::automatic
/// collecting builds up to automatic_whole_limit points without regions).
/// The sink is never called concurrently, but it may be called from a thread
/// other than the caller's (the incremental construction hands its cells
/// over from a pipeline), and when streamed with more threads from several,
/// in an order that depends on their timing. A sink with a member reserve(n)
/// is told the number of simplices before the first one when that is known
/// (collected output, and the incremental engine's). A sink with a member
/// input_no_longer_read() is told once, when the engine will read `points` no
/// more (the incremental construction, once it has copied them in its own
/// order; the walls, with the project's kernel, once their search structure
/// has: an engine taking over from them takes the points from it): a caller
/// that owns them may free them then (the tool does: at 10^6 points, 24 MB
/// of its peak). Never while the sink is called.
/// \throws Invalid_input for non-finite coordinates, fewer than D + 1 distinct
/// points, or points that do not span E^D; Cancelled when Options::progress
/// returned false. An exception from the sink (or from Options::progress)
/// ends the triangulation and is passed on.
/// Complexity: expected O(n log n) on uniformly distributed points; with
/// Engine::automatic (the default) at most a small multiple of the incremental
/// construction's on any input. Streamed, only until the first region is
/// kept (Options::stream): a part of the input that would have handed over
/// after that is built at DeWall's speed (a cube of points beside a sphere of
/// them; Engine::cgal keeps the bound, with the triangulation in memory).
template <kernel::DelaunayKernel K, class Sink>
Statistics triangulate_to(std::span<const typename K::Point_d> points, Sink&& sink, const Options& options = {},
                          const K& k = {}) {
  detail::Sink_output<K::dimension, std::remove_reference_t<Sink>> output(sink);
  if constexpr (std::is_invocable_v<Sink&, const Simplex<K::dimension>&, int>)
    return detail::run_triangulation<K>(points, detail::options_with_walls(options), k, output);
  else
    return detail::run_triangulation<K>(points, options, k, output);
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
  struct Append {
    std::vector<Simplex<K::dimension>>& simplices;
    void reserve(std::size_t n) { simplices.reserve(simplices.size() + n); }
    void operator()(const Simplex<K::dimension>& s) { simplices.push_back(s); }
  };
  Triangulation<K::dimension> t;
  t.statistics = triangulate_to<K>(points, Append{t.simplices}, options, k);
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
