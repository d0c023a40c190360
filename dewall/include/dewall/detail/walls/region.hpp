// Regions: the parts of the DeWall recursion that an incremental construction
// triangulates instead of more walls (Engine::hybrid, options.hpp).
//
// Why it is exact. A region R is a set of points that every wall above it has
// put on one side. A simplex of the whole triangulation DT(P) with all its
// vertices in R is empty of P, hence of R: it is a simplex of DT(R) (the
// perturbation depends on the points alone, so both triangulations break ties
// alike). Conversely a simplex of DT(R) belongs to DT(P) exactly when its
// sphere holds no point of P \ R — an exact perturbed in-sphere test. The
// simplices with vertices on both sides of a wall are the walls' own. So the
// walls plus, for each region, the simplices of DT(R) whose spheres are empty
// of the other points are DT(P), each simplex once, whatever builds DT(R).
//
// The faces where the region's simplices meet the walls close the walls'
// active faces (Update). Faces still open afterwards (hull faces, and the
// faces of a simplex no wall reached) are finished by gift-wrapping once all
// regions are done (wall.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <vector>

#include "dewall/detail/common/coords.hpp"
#include "dewall/detail/walls/face.hpp"

namespace dewall::detail {

/// What a region's triangulator asks of the recursion (wall.hpp) while it
/// walks DT(R), which it builds and keeps itself: copying DT(R) out as a
/// list of cells with their neighbours cost a visible share of the run and of
/// a region's memory (docs/engines.md).
template <int D>
class Region_filter {
 public:
  /// DT(R) has `cells` simplices; called once, before the others.
  virtual void begin(std::size_t cells) = 0;
  /// Whether the sphere of `cell`, a simplex of DT(R) (positively oriented),
  /// holds no point outside R. Which cells are asked: those on the hull of R,
  /// and every neighbour of a cell found not empty; the others are empty
  /// untested. The cells holding one outside point q form a connected set
  /// that reaches the hull (Bowyer–Watson: the cavity q would open in DT(R)
  /// is connected, and q lies outside the convex hull of R, so the cavity
  /// includes hull facets), so that walk meets all of them, asking few cells
  /// on volume data (docs/engines.md).
  virtual bool empty_of_others(const Simplex<D>& cell) = 0;
  /// When true, every finite cell is asked instead (in DT(R)'s order), and a
  /// cell answered false is simply not kept: a wall's slab (wall.hpp) keeps
  /// only the cells that cross its wall, each proven on its own, so the walk
  /// would spread through cells it never keeps.
  virtual bool asks_every_cell() const { return false; }
  /// A simplex of DT(R) whose sphere holds no point outside R, so of DT(P)
  /// (positively oriented), in DT(R)'s order. Bit i of `open` is set when the
  /// face opposite vertex i is on no other such simplex (on the hull of R, or
  /// its neighbour there was not empty).
  virtual void keep(const Simplex<D>& cell, unsigned open) = 0;

 protected:
  ~Region_filter() = default;
};

/// Builds DT(R) of the points `region` (local indices into `coords`) with the
/// perturbation of the kernel and passes it through `filter`. Returns false,
/// having called nothing, when the points do not span E^D (the region is then
/// left to DeWall).
template <int D>
using Region_triangulator = std::function<bool(std::span<const Index> region, const std::vector<Coords<D>>& coords,
                                               Region_filter<D>& filter)>;

/// The open box that every point of a region lies in and every point outside
/// it does not: the walls above the region cut it along coordinate planes
/// (split.hpp), and a point on the other side of a cut at value v along axis a
/// has x_a ≥ v (or ≤ v). A closed ball strictly inside holds no outside point.
template <int D>
struct Region_bounds {
  Coords<D> lo, hi;
  Region_bounds() {
    lo.fill(-std::numeric_limits<double>::infinity());
    hi.fill(std::numeric_limits<double>::infinity());
  }
  /// The bounds of the side below (side1) or above the cut at `value` on `axis`.
  Region_bounds cut(int axis, double value, bool side1) const {
    Region_bounds b = *this;
    if (side1) b.hi[axis] = std::min(b.hi[axis], value);
    else b.lo[axis] = std::max(b.lo[axis], value);
    return b;
  }
  bool strictly_contains(const Coords<D>& box_lo, const Coords<D>& box_hi) const {
    for (int j = 0; j < D; ++j)
      if (!(lo[j] < box_lo[j] && box_hi[j] < hi[j])) return false;
    return true;
  }
};

}  // namespace dewall::detail
