// Filtered_kernel_d<D>: the project's own DelaunayKernel model over double.
// Filter → interval → exact for both predicates, CGAL's perturbation for the
// sphere test. Stateless and trivially copyable.
#pragma once

#include "dewall/kernel/concepts.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/side_of_sphere.hpp"

namespace dewall::kernel {

template <int D>
struct Filtered_kernel_d {
  static constexpr int dimension = D;
  static constexpr bool approximate_coordinates_are_exact = true;
  using Point_d = kernel::Point_d<D>;

  struct Orientation_d {
    Sign operator()(const std::array<const Point_d*, D + 1>& s) const { return orientation_d<D>(s); }
  };
  struct Side_of_oriented_sphere_d {
    Oriented_side operator()(const std::array<const Point_d*, D + 2>& s) const {
      return side_of_oriented_sphere_d_sos<D>(s);
    }
  };
  struct Side_of_oriented_sphere_unperturbed_d {
    Oriented_side operator()(const std::array<const Point_d*, D + 2>& s) const {
      return side_of_oriented_sphere_d<D>(s);
    }
  };
  struct Compare_lexicographically_d {
    Comparison_result operator()(const Point_d& a, const Point_d& b) const {
      return compare_lexicographically(a, b);
    }
  };
  struct Approximate_coordinates_d {
    const std::array<double, D>& operator()(const Point_d& p) const { return p.x; }
  };

  Orientation_d orientation_d_object() const { return {}; }
  Side_of_oriented_sphere_d side_of_oriented_sphere_d_object() const { return {}; }
  Side_of_oriented_sphere_unperturbed_d side_of_oriented_sphere_unperturbed_d_object() const { return {}; }
  Compare_lexicographically_d compare_lexicographically_d_object() const { return {}; }
  Approximate_coordinates_d approximate_coordinates_object() const { return {}; }
};

static_assert(DelaunayKernel<Filtered_kernel_d<2>>);
static_assert(DelaunayKernel<Filtered_kernel_d<3>>);
static_assert(DelaunayKernel<Filtered_kernel_d<6>>);

}  // namespace dewall::kernel
