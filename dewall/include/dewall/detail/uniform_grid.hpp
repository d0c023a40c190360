// Uniform_grid: the paper's uniform grid ("Uniform grid" section): about one
// point per cell, points stored contiguously in cell order.
//
// The grid only ranks and prunes: a cell is skipped when a conservative test
// proves it cannot hold a point of interest; every decision about a point
// found in a visited cell is made by exact predicates elsewhere.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "dewall/detail/face.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <int D>
using Coords = std::array<double, D>;

/// An axis-aligned box of cells, inclusive bounds.
template <int D>
struct Cell_box {
  std::array<int, D> lo, hi;
};

template <int D>
class Uniform_grid {
 public:
  /// Builds the grid over `coords` (indexed by point). `cells_per_point` scales
  /// the cell count (the paper uses about one cell per point).
  explicit Uniform_grid(const std::vector<Coords<D>>& coords, double cells_per_point = 1.0) {
    const std::size_t n = coords.size();
    lo_ = hi_ = coords.at(0);
    for (const auto& p : coords)
      for (int i = 0; i < D; ++i) {
        lo_[i] = std::min(lo_[i], p[i]);
        hi_[i] = std::max(hi_[i], p[i]);
      }
    // Cubic cells of volume ≈ (box volume)/(n·cells_per_point), ignoring flat
    // axes. In logarithms: the volume itself overflows or underflows for boxes
    // of extent 2^±300 in 4D, and a grid of one cell makes every search a scan.
    double log2_volume = 0;
    int spanned = 0;
    for (int i = 0; i < D; ++i)
      if (hi_[i] > lo_[i]) {
        log2_volume += std::log2(hi_[i] - lo_[i]);
        ++spanned;
      }
    const double target = std::max(1.0, static_cast<double>(n) * cells_per_point);
    double side = spanned ? std::exp2((log2_volume - std::log2(target)) / spanned) : 1.0;
    std::size_t total = 1;
    for (int i = 0; i < D; ++i) {
      const double extent = hi_[i] - lo_[i];
      double cells = extent > 0 && side > 0 && std::isfinite(extent / side) ? std::ceil(extent / side) : 1.0;
      cells = std::clamp(cells, 1.0, 4.0 * target);
      dims_[i] = static_cast<int>(cells);
      total *= static_cast<std::size_t>(dims_[i]);
    }
    while (total > 4 * static_cast<std::size_t>(target) + 16) {  // flat boxes: cap the cell count
      int widest = 0;
      for (int i = 1; i < D; ++i)
        if (dims_[i] > dims_[widest]) widest = i;
      total /= static_cast<std::size_t>(dims_[widest]);
      dims_[widest] = std::max(1, dims_[widest] / 2);
      total *= static_cast<std::size_t>(dims_[widest]);
    }
    for (int i = 0; i < D; ++i) {
      const double extent = hi_[i] - lo_[i];
      inv_side_[i] = extent > 0 ? dims_[i] / extent : 0.0;
      if (!std::isfinite(inv_side_[i])) inv_side_[i] = 0.0;
      side_[i] = dims_[i] > 0 && extent > 0 ? extent / dims_[i] : 0.0;
    }
    cell_start_.assign(total + 1, 0);
    std::vector<std::uint32_t> cell_of(n);
    for (std::size_t k = 0; k < n; ++k) {
      cell_of[k] = static_cast<std::uint32_t>(linear(cell_of_point(coords[k])));
      ++cell_start_[cell_of[k] + 1];
    }
    for (std::size_t c = 0; c < total; ++c) cell_start_[c + 1] += cell_start_[c];
    points_.resize(n);
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t k = 0; k < n; ++k) points_[fill[cell_of[k]]++] = static_cast<Index>(k);
    for (std::size_t c = 0; c < total; ++c) max_points_in_cell_ = std::max<std::size_t>(max_points_in_cell_, cell_start_[c + 1] - cell_start_[c]);
  }

  std::size_t cell_count() const { return cell_start_.size() - 1; }
  /// The bounding box of the points.
  const Coords<D>& lower() const { return lo_; }
  const Coords<D>& upper() const { return hi_; }
  std::size_t max_points_in_cell() const { return max_points_in_cell_; }
  const std::array<int, D>& dims() const { return dims_; }

  /// The cell containing x (clamped to the grid).
  std::array<int, D> cell_of_point(const Coords<D>& x) const {
    std::array<int, D> c;
    for (int i = 0; i < D; ++i) c[i] = clamp_cell(i, (x[i] - lo_[i]) * inv_side_[i]);
    return c;
  }

  /// The cells meeting the box [lo, hi] (clamped to the grid). Conservative:
  /// a point inside [lo, hi] lies in one of them, since cell_of_point is
  /// monotone in each coordinate.
  Cell_box<D> cells_meeting(const Coords<D>& lo, const Coords<D>& hi) const {
    Cell_box<D> b;
    for (int i = 0; i < D; ++i) {
      b.lo[i] = clamp_cell(i, (lo[i] - lo_[i]) * inv_side_[i]);
      b.hi[i] = clamp_cell(i, (hi[i] - lo_[i]) * inv_side_[i]);
    }
    return b;
  }
  Cell_box<D> all_cells() const {
    Cell_box<D> b;
    for (int i = 0; i < D; ++i) {
      b.lo[i] = 0;
      b.hi[i] = dims_[i] - 1;
    }
    return b;
  }

  /// The coordinate range a cell may hold, widened so that it contains every
  /// point assigned to it despite the rounding of cell_of_point.
  void cell_bounds(const std::array<int, D>& c, Coords<D>& lo, Coords<D>& hi) const {
    for (int i = 0; i < D; ++i) {
      const double slack = 1e-9 * (hi_[i] - lo_[i]);
      lo[i] = c[i] == 0 ? lo_[i] : lo_[i] + c[i] * side_[i] - slack;
      hi[i] = c[i] == dims_[i] - 1 ? hi_[i] : lo_[i] + (c[i] + 1) * side_[i] + slack;
    }
  }

  std::size_t linear(const std::array<int, D>& c) const {
    std::size_t k = 0;
    for (int i = D - 1; i >= 0; --i) k = k * static_cast<std::size_t>(dims_[i]) + static_cast<std::size_t>(c[i]);
    return k;
  }

  /// The points of cell c (by linear index), as a [begin, end) range.
  const Index* begin(std::size_t cell) const { return points_.data() + cell_start_[cell]; }
  const Index* end(std::size_t cell) const { return points_.data() + cell_start_[cell + 1]; }

 private:
  int clamp_cell(int axis, double t) const {
    if (!(t > 0)) return 0;  // also NaN
    if (t >= dims_[axis]) return dims_[axis] - 1;
    return static_cast<int>(t);
  }

  Coords<D> lo_{}, hi_{}, side_{}, inv_side_{};
  std::array<int, D> dims_{};
  std::vector<std::uint32_t> cell_start_;
  std::vector<Index> points_;
  std::size_t max_points_in_cell_ = 0;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
