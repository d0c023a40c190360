// Options of dewall::triangulate.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string_view>

namespace dewall {

/// Which construction builds the triangulation. Each gives the same simplices
/// (the Delaunay triangulation under CGAL's symbolic perturbation); only the
/// time and the statistics differ.
enum class Engine {
  /// In 2D and 3D, Engine::hybrid, handing over to the incremental
  /// construction when the walls' searches prove the input is one no
  /// gift-wrapping search is fast on (points on or near one sphere, thin
  /// surfaces, lattices): see Options::handover_candidates_per_search. An
  /// input of at most automatic_whole_limit distinct points (33554432 when
  /// collected with the default region size; one region's size otherwise) is
  /// built by the incremental construction alone: up to there the walls and
  /// regions cost more than it on one thread and gain nothing on two
  /// (docs/engines.md, "The rule"); the project's own inserts in parallel
  /// zones there. In 4D and up, the incremental construction alone (the walls
  /// only add to it there).
  /// "The incremental construction" is the project's own (Engine::incremental)
  /// where it is measured faster than CGAL's, CGAL's (Engine::cgal) elsewhere:
  /// see default_incremental_engine and default_region_engine.
  automatic,
  /// DeWall only: walls all the way down (the paper's algorithm).
  dewall,
  /// CGAL's incremental construction only (Delaunay_triangulation_2/_3, the dD
  /// Delaunay_triangulation), compiled into the library.
  cgal,
  /// The project's own incremental construction only (Bowyer–Watson over the
  /// project's kernel: dewall/detail/incremental/incremental_delaunay.hpp). Its 32-bit cell
  /// references hold 2^30 cells in 2D and 3D (about 1.6·10^8 points in 3D)
  /// and 2^29 above; beyond, std::length_error.
  incremental,
  /// DeWall's walls down to regions of Options::region_points points, each
  /// region triangulated by the incremental construction and the simplices
  /// whose spheres hold no point of the other regions kept (no merge step:
  /// dewall/detail/walls/region.hpp says why this is exact). The regions are
  /// independent, so they run in parallel like DeWall's subproblems.
  hybrid,
};

/// The incremental construction Engine::automatic leaves an input to (one
/// region's size, a spent search budget, 4D and up) in dimension D: the
/// project's own, faster than CGAL's on one thread on every class measured
/// in every dimension (docs/performance.md, the benchmark suite).
constexpr Engine default_incremental_engine(int /*dimension*/) { return Engine::incremental; }

/// The incremental construction of the hybrid's regions: the project's own in
/// every dimension, faster than CGAL's on what reaches the regions, which is
/// volume-like (docs/engines.md).
constexpr Engine default_region_engine(int /*dimension*/) { return Engine::incremental; }

/// "automatic", "dewall", "cgal", "incremental" or "hybrid".
constexpr const char* engine_name(Engine e) {
  switch (e) {
    case Engine::automatic: return "automatic";
    case Engine::dewall: return "dewall";
    case Engine::cgal: return "cgal";
    case Engine::incremental: return "incremental";
    case Engine::hybrid: return "hybrid";
  }
  return "?";
}

/// The names parse_engine accepts, for messages.
inline constexpr const char* engine_choices = "auto, dewall, hybrid, incremental or cgal";

/// The engine a user names: "auto", "dewall", "cgal", "incremental" or "hybrid" (the CLI's
/// --engine and the Python bindings' engine=), or nothing for any other name.
constexpr std::optional<Engine> parse_engine(std::string_view name) {
  if (name == "auto") return Engine::automatic;
  if (name == "dewall") return Engine::dewall;
  if (name == "cgal") return Engine::cgal;
  if (name == "incremental") return Engine::incremental;
  if (name == "hybrid") return Engine::hybrid;
  return std::nullopt;
}

struct Options {
  /// Points per leaf of the search structure (a kd-tree; the paper's uniform
  /// grid has about one per cell). Only the speed depends on it.
  std::size_t points_per_leaf = 8;
  /// Recursion levels whose two halves run as parallel tasks (TBB): up to
  /// 2^parallel_depth tasks. 0 runs serially. The output is the same either way.
  int parallel_depth = 6;
  /// At most this many threads (a TBB arena); 0: TBB's default, all cores.
  /// The output is the same for every value (tested for 1, 2, 3 and 8).
  int threads = 0;
  /// The construction. Engines other than DeWall need the project's kernel
  /// (Filtered_kernel_d); with another kernel, automatic means DeWall.
  Engine engine = Engine::automatic;
  /// The incremental construction that builds the hybrid's regions and what
  /// Engine::automatic leaves to one: Engine::incremental (the project's own),
  /// Engine::cgal, or Engine::automatic for default_region_engine(D) in the
  /// regions and default_incremental_engine(D) for the rest.
  /// Any other value is refused (std::invalid_argument). The simplices are
  /// the same with each.
  Engine incremental_engine = Engine::automatic;
  /// Engine::automatic hands over to the incremental construction once the
  /// searches of any task of DeWall's recursion have cost more than this many
  /// candidate points per search on average, a predicate evaluation that the
  /// filters leave to the exact stage costing 100 candidates (a second stage,
  /// running error or intervals, 10), counted from the first search, with an
  /// allowance of 64 searches' worth plus 4^(D−2)·n candidates
  /// (handover_rule.hpp). A search
  /// must look at every point near the sphere it proves empty: the average
  /// stays small on volume data and clusters and grows by orders of magnitude
  /// on points near one sphere or surface, where the incremental construction
  /// is much faster (on lattices and cospherical points the exact tests
  /// decide). A measured rule, not a guess about the input's name: the
  /// figures are in docs/engines.md.
  double handover_candidates_per_search = 150;
  /// Engine::hybrid and automatic: the largest region left to the incremental
  /// construction; 0 chooses region_points_for(n): n / 4 within
  /// [smallest_default_region, largest_default_region] (two levels of walls,
  /// four regions to run in parallel), and with Options::stream at most
  /// largest_streaming_region(n). The walls cost more per simplex than the
  /// incremental construction, so each level costs time on any number of
  /// cores; but a region's triangulation is in memory while it runs, so the
  /// upper bound keeps large inputs from holding gigabytes per region, and
  /// streaming, which is for memory, takes smaller ones up to millions of
  /// points. Fixed by n and Options::stream, never by the number of threads,
  /// so the output does not depend on them. The measurements: docs/engines.md.
  std::size_t region_points = 0;
  /// triangulate_to hands the simplices to its sink as they are built, and
  /// does not keep them (dewall.hpp). The same simplices; with one thread in
  /// the order collecting gives with the same region_points (by default
  /// streaming takes other regions above 131072 points, but for 2^24 − 63 to
  /// 2^24 points, where both take 262144; and Engine::automatic collecting
  /// builds up to automatic_whole_limit points without regions), with more
  /// in an order that depends on the threads' timing.
  /// Simplices passed on cannot be taken back, so Engine::automatic decides
  /// once whether to hand over to the incremental engine: it holds what it
  /// builds until the first region's simplices are kept, and never hands over
  /// after that (handover_rule.hpp, Handover_decision): a part of the input
  /// that would have handed over later is built by the walls and regions, at
  /// their speed (docs/engines.md). When it hands over, the incremental
  /// engine's triangulation is whole in memory, as it is without streaming.
  bool stream = false;
  /// Progress and cancellation for long work, or empty (the default): called
  /// with the fraction of the work done, in [0, 1], every few thousand points
  /// inserted, every thousand simplices a wall builds and after each region
  /// (a few milliseconds apart; the walls' and regions' fraction counts the
  /// points whose part is done, an estimate that never goes back), and with
  /// 1 once the triangulation is complete. Never called concurrently, but
  /// possibly from a thread other than the caller's; it should return at once.
  /// Returning false stops the work: triangulate and triangulate_to throw
  /// dewall::Cancelled once the threads have stopped, within a few
  /// milliseconds (Engine::cgal's CGAL construction is not polled: it stops
  /// when it is done; the hybrid's regions, each at its end). An exception
  /// the callback throws stops the work the same way and is passed on.
  std::function<bool(double fraction)> progress = {};
};

/// The bounds of the default region size (Options::region_points); the CLI's
/// help prints them, and a test checks docs/cli.md against them.
inline constexpr std::size_t smallest_default_region = 16384;
inline constexpr std::size_t largest_default_region = 262144;
inline constexpr std::size_t largest_default_streaming_region = 32768;
/// Streaming's regions grow with the input beyond that: up to one
/// streaming_region_share-th of it (rounded up: a split's halves differ by
/// one point, and a half one point above the size would take another level
/// of walls), at most largest_streaming_region_at_scale. On millions of
/// points the points and the walls' tree outweigh the regions in flight, one
/// a thread, and each level of walls costs time, so larger regions are
/// faster at the same peak (docs/engines.md has the measurements). A region
/// in flight holds a few hundred bytes a point, so each thread adds up to
/// about 0.3 GB at 2^20 (Options::region_points sets a smaller size). Above
/// collecting's largest_default_region: collecting holds its output too,
/// streaming only its regions in flight.
inline constexpr std::size_t streaming_region_share = 64;
inline constexpr std::size_t largest_streaming_region_at_scale = std::size_t{1} << 20;

/// The largest default region when streaming n points.
constexpr std::size_t largest_streaming_region(std::size_t n) {
  const std::size_t share = (n + streaming_region_share - 1) / streaming_region_share;
  return share < largest_default_streaming_region    ? largest_default_streaming_region
         : share > largest_streaming_region_at_scale ? largest_streaming_region_at_scale
                                                     : share;
}

/// Engine::automatic builds collected inputs of at most this many distinct
/// points by the incremental construction alone (automatic_whole_limit).
/// 2^25: the incremental construction is faster than the hybrid at every
/// measured size, on one core and on two (docs/engines.md, "The rule"), and
/// 2^25 points keep its 2^30 cell slots enough at 20 cells a point (tori);
/// above, the hybrid's regions.
inline constexpr std::size_t largest_automatic_whole_input = 33554432;

/// The region size Options::region_points asks for, for n points.
constexpr std::size_t region_points_for(const Options& o, std::size_t n) {
  if (o.region_points) return o.region_points;
  const std::size_t largest = o.stream ? largest_streaming_region(n) : largest_default_region;
  return n / 4 < smallest_default_region ? smallest_default_region : n / 4 > largest ? largest : n / 4;
}

/// The most distinct points Engine::automatic leaves to the incremental
/// construction alone, without walls: largest_automatic_whole_input when
/// collected with the default region size (larger than any default region),
/// else one region's size (a user who sets Options::region_points asks for
/// regions; streaming, which is for memory, keeps its small regions). Fixed
/// by n and the options, never by the number of threads.
constexpr std::size_t automatic_whole_limit(const Options& o, std::size_t n) {
  static_assert(largest_default_region < largest_automatic_whole_input);
  return o.region_points || o.stream ? region_points_for(o, n) : largest_automatic_whole_input;
}

/// Counters for the paper's Table 1, filled by triangulate.
struct Statistics {
  std::size_t input_points = 0;
  std::size_t distinct_points = 0;
  std::size_t simplices = 0;
  std::size_t first_wall_simplices = 0;
  std::size_t recursion_depth = 0;
  std::size_t simplex_searches = 0;
  std::size_t nodes_visited = 0;       // kd-tree nodes, by all searches
  std::size_t candidates_tested = 0;   // points examined by all searches
  std::size_t tree_leaves = 0;
  std::size_t region_simplices = 0;    // hybrid: simplices the regions' incremental construction built
  Engine engine = Engine::dewall;            // the construction that built the output
  std::size_t searches_before_handover = 0;  // automatic: DeWall's searches before handing over
  double mean_nodes_per_simplex() const { return simplices ? double(nodes_visited) / double(simplices) : 0.0; }
};

}  // namespace dewall
