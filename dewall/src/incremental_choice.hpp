// Which incremental construction runs where: Options::incremental_engine,
// resolved once per run into the construction that builds a whole
// triangulation (Engine::automatic's hand-over, its small and 4D+ inputs) and
// the one that builds the hybrid's regions. The defaults are
// default_incremental_engine and default_region_engine (options.hpp); why
// they are what they are: docs/engines.md. Private to dewall/src.
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "cgal_engine.hpp"
#include "incremental_engine.hpp"
#include "dewall/detail/walls/region.hpp"
#include "dewall/options.hpp"

namespace dewall::detail {

template <int D>
class Incremental_choice {
 public:
  /// \throws std::invalid_argument when Options::incremental_engine is not
  /// automatic, incremental or cgal.
  explicit Incremental_choice(const Options& options) {
    const Engine chosen = options.incremental_engine;
    if (chosen != Engine::automatic && chosen != Engine::incremental && chosen != Engine::cgal)
      throw std::invalid_argument(
          std::string("dewall: Options::incremental_engine must be automatic, incremental or cgal, not ") +
          engine_name(chosen));
    own_whole_ = (chosen == Engine::automatic ? default_incremental_engine(D) : chosen) == Engine::incremental;
    const bool own_regions = (chosen == Engine::automatic ? default_region_engine(D) : chosen) == Engine::incremental;
    regions_ = own_regions ? incremental_region_cells<D> : cgal_region_cells<D>;
  }

  /// The whole triangulation by the chosen construction (see
  /// triangulate_with_cgal, triangulate_incremental). `distinct`, when given,
  /// is distinct_points(points), computed by the caller.
  Statistics whole(std::span<const kernel::Point_d<D>> points, Simplex_output<D>& output,
                   const Distinct_points* distinct = nullptr) const {
    return own_whole_ ? triangulate_incremental<D>(points, output, distinct)
                      : triangulate_with_cgal<D>(points, output, distinct);
  }

  /// The triangulator of the hybrid's regions.
  const Region_triangulator<D>& regions() const { return regions_; }

 private:
  bool own_whole_ = false;
  Region_triangulator<D> regions_;
};

}  // namespace dewall::detail
