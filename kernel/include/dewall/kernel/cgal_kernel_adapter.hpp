// Cgal_kernel_adapter: CGAL kernels as DelaunayKernel models.
//
// Lets the same DeWall code run on CGAL's predicates, an independent check of
// our own kernel. Supported: CGAL::Epick (and any 2D/3D CGAL kernel with
// Orientation_2/3, Side_of_oriented_circle_2 / Side_of_oriented_sphere_3) for
// D = 2, 3, and CGAL::Epick_d<Dimension_tag<D>> (any NewKernel_d kernel) for
// D ≥ 2. The perturbation is the shared scheme of perturbation.hpp on top of
// CGAL's exact unperturbed predicates. Include only where CGAL is wanted: this
// is the one kernel header that pulls in CGAL.
#pragma once

#include <CGAL/Epick_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "dewall/kernel/concepts.hpp"
#include "dewall/kernel/perturbation.hpp"

namespace dewall::kernel {

namespace detail {
template <class CK, int D>
struct Is_cgal_d_kernel : std::false_type {};
template <int D>
struct Is_cgal_d_kernel<CGAL::Epick_d<CGAL::Dimension_tag<D>>, D> : std::true_type {};

// The point type, selected lazily: only the chosen branch's member is named.
template <class CK, int D, bool is_d_kernel>
struct Cgal_point;
template <class CK, int D>
struct Cgal_point<CK, D, true> {
  using type = typename CK::Point_d;
};
template <class CK>
struct Cgal_point<CK, 2, false> {
  using type = typename CK::Point_2;
};
template <class CK>
struct Cgal_point<CK, 3, false> {
  using type = typename CK::Point_3;
};
}  // namespace detail

/// CK: a CGAL kernel. For D = 2, 3 a 2D/3D kernel (e.g. CGAL::Epick); otherwise
/// CGAL::Epick_d<CGAL::Dimension_tag<D>>.
template <class CK, int D>
class Cgal_kernel_adapter {
  static constexpr bool is_d_kernel = detail::Is_cgal_d_kernel<CK, D>::value;

 public:
  static constexpr int dimension = D;
  using Cgal_kernel = CK;
  using Point_d = typename detail::Cgal_point<CK, D, is_d_kernel>::type;
  /// Coordinates held as doubles are their own approximations: the search
  /// prunes with them as exact, and CGAL's predicates decide everything
  /// (an independent check). Other number types state nothing (concepts.hpp).
  static constexpr double approximate_coordinates_error =
      std::is_same_v<std::remove_cvref_t<decltype(std::declval<const Point_d&>()[0])>, double>
          ? 0.0
          : std::numeric_limits<double>::infinity();

  struct Orientation_d {
    CK kernel;
    Sign operator()(const std::array<const Point_d*, D + 1>& s) const {
      if constexpr (is_d_kernel) {
        std::array<Point_d, D + 1> pts;
        for (int i = 0; i <= D; ++i) pts[static_cast<std::size_t>(i)] = *s[static_cast<std::size_t>(i)];
        return static_cast<Sign>(kernel.orientation_d_object()(pts.begin(), pts.end()));
      } else if constexpr (D == 2) {
        return static_cast<Sign>(kernel.orientation_2_object()(*s[0], *s[1], *s[2]));
      } else {
        return static_cast<Sign>(kernel.orientation_3_object()(*s[0], *s[1], *s[2], *s[3]));
      }
    }
  };

  struct Compare_lexicographically_d {
    CK kernel;
    Comparison_result operator()(const Point_d& a, const Point_d& b) const {
      if constexpr (is_d_kernel)
        return static_cast<Comparison_result>(kernel.compare_lexicographically_d_object()(a, b));
      else if constexpr (D == 2)
        return static_cast<Comparison_result>(kernel.compare_xy_2_object()(a, b));
      else
        return static_cast<Comparison_result>(kernel.compare_xyz_3_object()(a, b));
    }
  };

  struct Side_of_oriented_sphere_unperturbed_d {
    CK kernel;
    Oriented_side operator()(const std::array<const Point_d*, D + 2>& s) const {
      if constexpr (is_d_kernel) {
        std::array<Point_d, D + 1> pts;
        for (int i = 0; i <= D; ++i) pts[static_cast<std::size_t>(i)] = *s[static_cast<std::size_t>(i)];
        return static_cast<Oriented_side>(
            kernel.side_of_oriented_sphere_d_object()(pts.begin(), pts.end(), *s[D + 1]));
      } else if constexpr (D == 2) {
        return static_cast<Oriented_side>(kernel.side_of_oriented_circle_2_object()(*s[0], *s[1], *s[2], *s[3]));
      } else {
        return static_cast<Oriented_side>(
            kernel.side_of_oriented_sphere_3_object()(*s[0], *s[1], *s[2], *s[3], *s[4]));
      }
    }
  };

  struct Side_of_oriented_sphere_d {
    CK kernel;
    Oriented_side operator()(const std::array<const Point_d*, D + 2>& s) const {
      const Oriented_side side = Side_of_oriented_sphere_unperturbed_d{kernel}(s);
      if (side != ON_ORIENTED_BOUNDARY) return side;
      const Compare_lexicographically_d compare{kernel};
      return perturbed_side_of_sphere<D>(s, Orientation_d{kernel},
                                         [&](const Point_d& a, const Point_d& b) { return compare(a, b) == SMALLER; });
    }
  };

  struct Approximate_coordinates_d {
    std::array<double, D> operator()(const Point_d& p) const {
      std::array<double, D> x;
      for (int i = 0; i < D; ++i) x[static_cast<std::size_t>(i)] = CGAL::to_double(p[i]);
      return x;
    }
  };

  Orientation_d orientation_d_object() const { return {}; }
  Side_of_oriented_sphere_d side_of_oriented_sphere_d_object() const { return {}; }
  Side_of_oriented_sphere_unperturbed_d side_of_oriented_sphere_unperturbed_d_object() const { return {}; }
  Compare_lexicographically_d compare_lexicographically_d_object() const { return {}; }
  Approximate_coordinates_d approximate_coordinates_object() const { return {}; }
};

}  // namespace dewall::kernel
