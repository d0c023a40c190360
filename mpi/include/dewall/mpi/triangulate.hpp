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
//  3. each rank then keeps the cells whose smallest global vertex index lies
//     in its block: each simplex of the triangulation on exactly one rank.
#pragma once

#include <mpi.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "dewall/kernel/point.hpp"

namespace dewall::mpi {

/// A simplex as D + 1 global point indices, positively oriented, in a form
/// that depends on the simplex alone: the indices ascending, except the last
/// two swapped when ascending order is negatively oriented.
template <int D>
using Global_simplex = std::array<std::uint64_t, D + 1>;

/// Tuning; no option changes the result.
struct Options {
  /// Before the first round each rank fetches the points within this many
  /// mean point spacings of its block's box (its first halo guess; the rounds
  /// fetch whatever else is needed). 0: none.
  double seed_spacings = 1.0;
};

/// What one rank did (its own numbers; nothing is summed over ranks).
struct Statistics {
  std::size_t local_points = 0;    ///< points given to this rank
  std::size_t block_points = 0;    ///< distinct points of its block after the exchange
  std::size_t halo_points = 0;     ///< points of other blocks it fetched
  std::size_t rounds = 0;          ///< halo rounds (the same on every rank)
  std::size_t builds = 0;          ///< triangulation updates: the first build, then one insertion per round with new points
  std::size_t queries_sent = 0;    ///< ball and hull-facet questions to other ranks
  std::size_t simplices = 0;       ///< simplices this rank owns
  double decompose_seconds = 0;    ///< cuts and point exchange
  double build_seconds = 0;        ///< triangulations
  double halo_seconds = 0;         ///< answers and the exchanges of questions and answers
  double verify_seconds = 0;       ///< finding the cells to ask about, and the questions
  double finish_seconds = 0;       ///< the owned simplices taken out and sorted
};

/// The rank's share of the triangulation.
template <int D>
struct Result {
  /// The simplices this rank owns, sorted: the cells whose smallest vertex
  /// index lies in this rank's block. Over all ranks, each simplex of the
  /// triangulation of all points exactly once.
  std::vector<Global_simplex<D>> simplices;
  Statistics statistics;
};

/// Collective over `comm`: the Delaunay triangulation (under CGAL's symbolic
/// perturbation) of the union of every rank's `local` points, local point i
/// having the global index `global_offset + i`. Global indices must be
/// distinct over the ranks (the ranges disjoint); they define the input order
/// for duplicates: of equal points, the one of smallest global index is the
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
/// halo, once per round with new points (2 – 4 rounds measured).
template <int D>
Result<D> triangulate(MPI_Comm comm, std::span<const kernel::Point_d<D>> local, std::uint64_t global_offset,
                      const Options& options = {});

/// As triangulate, handing each owned simplex to sink(const Global_simplex<D>&)
/// on its rank (after the collective work: an exception from the sink is that
/// rank's alone).
template <int D, class Sink>
Statistics triangulate_to(MPI_Comm comm, std::span<const kernel::Point_d<D>> local, std::uint64_t global_offset,
                          Sink&& sink, const Options& options = {}) {
  Result<D> r = triangulate<D>(comm, local, global_offset, options);
  for (const Global_simplex<D>& s : r.simplices) sink(s);
  return r.statistics;
}

}  // namespace dewall::mpi
