// dewall::mpi: the Delaunay triangulation of points distributed over the ranks
// of an MPI communicator, without any rank holding all points, equal as a set
// of simplices to CGAL's (and to dewall::triangulate's) on one machine, for
// every number of ranks. The algorithm and its correctness argument are at the
// top of mpi/src/triangulate_mpi.cpp; in short:
//  1. the top walls of DeWall (cuts at the median along cycling axes, side 1
//     strictly below the cut value) split the points into one block per rank,
//     found by a distributed exact selection, and MPI_Alltoallv moves them;
//  2. each rank triangulates its block (the library's incremental engine) and
//     asks the ranks whose blocks a cell's ball may reach (a box proven to
//     hold the closed ball) for their points there, in rounds, until no rank
//     receives a new point;
//  3. each rank then hands its sink the cells whose smallest global vertex
//     index lies in its block: each simplex of the triangulation on exactly
//     one rank.
#pragma once

#include <mpi.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "dewall/kernel/point.hpp"

namespace dewall::mpi {

/// A simplex as D + 1 global point indices, positively oriented, in a form
/// that depends on the simplex alone: the indices ascending, except the last
/// two swapped when ascending order is negatively oriented.
template <int D>
using Global_simplex = std::array<std::uint64_t, D + 1>;

/// Tuning; no option changes the simplices (region_points changes their order on a rank).
struct Options {
  /// Before the first round each rank fetches the points within this many
  /// mean point spacings of its block's box (its first halo guess; the rounds
  /// fetch whatever else is needed). 0: none.
  double seed_spacings = 1.0;
  /// Each rank builds its block in regions of at most about this many points
  /// (DeWall's cuts again, inside the block), one region after another, all
  /// ranks in step: a region's simplices go to the sink as soon as its rounds
  /// are over, and its triangulation is freed. A rank then holds its block's
  /// points and one region's triangulation instead of the whole block's (the
  /// way to blocks too large for memory), at the cost of a halo around every
  /// region. 0: the whole block at once (the fastest).
  std::uint64_t region_points = 0;
};

/// What one rank did (its own numbers; nothing is summed over ranks).
struct Statistics {
  std::size_t local_points = 0;    ///< points given to this rank
  std::size_t block_points = 0;    ///< distinct points of its block after the exchange
  std::size_t halo_points = 0;     ///< points from outside the block (outside the region, with regions) it fetched, summed over regions
  std::size_t regions = 0;         ///< regions the block was built in (Options::region_points; the same on every rank)
  std::size_t rounds = 0;          ///< halo rounds, over all regions (the same on every rank)
  std::size_t builds = 0;          ///< triangulation updates: the first build, then one insertion per round with new points
  std::size_t queries_sent = 0;    ///< ball and hull-facet questions to other ranks
  std::size_t simplices = 0;       ///< simplices this rank owns
  double decompose_seconds = 0;    ///< cuts and point exchange
  double build_seconds = 0;        ///< triangulations
  double index_seconds = 0;        ///< the kd-tree over the block's points (for answering questions)
  double halo_seconds = 0;         ///< answers and the exchanges of questions and answers
  double verify_seconds = 0;       ///< finding the cells to ask about, and the questions
  double finish_seconds = 0;       ///< the owned simplices taken out and handed to the sink
};

/// Where a rank's owned simplices go (the compiled entry point's form; the
/// templates below build one from any callable). The simplices come in parts:
/// one part per region (Options::region_points; one part without regions),
/// each handed over as soon as its region is proven, all ranks in step. An
/// exception thrown from either function ends every rank (it is agreed on
/// after the part, as the library's own errors are; no rank is left waiting).
template <int D>
struct Simplex_sink {
  /// Optional: called first in each part with how many simplices this rank
  /// hands over in it — on every rank, 0 included, outside dewall::mpi's
  /// own collective calls, so a sink may make collective calls of its own
  /// here (dewall-mpi's MPI_Exscan of the file offsets); it must make them
  /// on every rank.
  std::function<void(std::uint64_t)> start;
  /// The part's owned simplices, a batch at a time (batches of a few thousand).
  std::function<void(std::span<const Global_simplex<D>>)> take;
};

/// Collective over `comm`: the Delaunay triangulation (under CGAL's symbolic
/// perturbation) of the union of every rank's `local` points, local point i
/// having the global index `global_offset + i`; each rank hands `sink` the
/// simplices it owns — the cells whose smallest vertex index lies in its
/// block — so that over all ranks each simplex of the triangulation comes
/// exactly once. The order on a rank is the order of its regions, each's in
/// the order of the region's cells: the same on every run with the same
/// points, number of ranks and Options (sort them for an order that does not
/// depend on R). Global indices must be distinct over
/// the ranks (the ranges disjoint); they define the input order for
/// duplicates: of equal points, the one of smallest global index is the
/// vertex, the others appear in no simplex (dewall::triangulate's and CGAL's
/// rule). A rank may pass no points.
/// \throws dewall::Invalid_input on every rank, with the same message, for a
/// non-finite coordinate (naming the smallest such global index), fewer than
/// D + 1 distinct points, or points not spanning E^D. Any other exception on
/// one rank during the collective work (std::bad_alloc, the engine's
/// std::length_error) is thrown on every rank, as std::runtime_error with
/// the message of the lowest failing rank: no rank is left waiting.
/// \pre every rank calls it with the same D and Options; MPI is initialised.
/// Complexity: per rank, about the incremental construction of its block and
/// halo, once per round with new points (2 – 5 rounds measured; per region
/// with regions); memory: the rank's points, halo and cells (with regions:
/// the block's points, and one region's halo and cells), no list of
/// simplices kept.
template <int D>
Statistics triangulate_into(MPI_Comm comm, std::span<const kernel::Point_d<D>> local, std::uint64_t global_offset,
                            const Simplex_sink<D>& sink, const Options& options = {});

/// As above, the rank's points moved in: `local` is freed (left empty) once
/// they are packed for their blocks, so that the rank holds no copy of its
/// share while it triangulates (24 bytes per point in 3D; dewall-mpi's way).
template <int D>
Statistics triangulate_into(MPI_Comm comm, std::vector<kernel::Point_d<D>>&& local, std::uint64_t global_offset,
                            const Simplex_sink<D>& sink, const Options& options = {});

/// As triangulate_into, handing each owned simplex to sink(const
/// Global_simplex<D>&), after sink.start(count) when the sink has that member.
template <int D, class Sink>
Statistics triangulate_to(MPI_Comm comm, std::span<const kernel::Point_d<D>> local, std::uint64_t global_offset,
                          Sink&& sink, const Options& options = {}) {
  Simplex_sink<D> s;
  if constexpr (requires { sink.start(std::uint64_t{}); }) s.start = [&](std::uint64_t n) { sink.start(n); };
  s.take = [&](std::span<const Global_simplex<D>> batch) {
    for (const Global_simplex<D>& x : batch) sink(x);
  };
  return triangulate_into<D>(comm, local, global_offset, s, options);
}

/// The rank's share of the triangulation.
template <int D>
struct Result {
  /// The simplices this rank owns, in triangulate_into's order.
  std::vector<Global_simplex<D>> simplices;
  Statistics statistics;
};

/// As triangulate_into, collecting the rank's simplices.
template <int D>
Result<D> triangulate(MPI_Comm comm, std::span<const kernel::Point_d<D>> local, std::uint64_t global_offset,
                      const Options& options = {}) {
  Result<D> r;
  Simplex_sink<D> s;
  s.start = [&](std::uint64_t n) {
    if (r.simplices.empty()) r.simplices.reserve(n);  // the first part (the only one without regions)
  };
  s.take = [&](std::span<const Global_simplex<D>> batch) { r.simplices.insert(r.simplices.end(), batch.begin(), batch.end()); };
  r.statistics = triangulate_into<D>(comm, local, global_offset, s, options);
  return r;
}

}  // namespace dewall::mpi
