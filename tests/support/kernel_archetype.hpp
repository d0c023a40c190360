// Kernel_archetype<D>: a model of kernel::DelaunayKernel with nothing beyond the
// concept (concepts.hpp). Its point type is opaque — no coordinates, no
// comparison, no arithmetic — and its functors are exactly the five required
// ones, so an algorithm that compiles against it uses the concept and nothing
// else. It states nothing about its approximate coordinates (neither
// approximate_coordinates_are_exact nor an error bound), so every decision
// goes to its functors and the searches do not prune (concepts.hpp). They
// answer with Filtered_kernel_d<D>'s predicates, so results can be checked
// against CGAL too.
#pragma once

#include <array>
#include <vector>

#include "dewall/kernel/concepts.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"

namespace dewall::test {

template <int D>
class Kernel_archetype {
  using Inner = kernel::Filtered_kernel_d<D>;

 public:
  static constexpr int dimension = D;

  class Point_d {
   public:
    explicit Point_d(const kernel::Point_d<D>& p) : p_(p) {}

   private:
    friend class Kernel_archetype;
    kernel::Point_d<D> p_;
  };

  struct Orientation_d {
    kernel::Sign operator()(const std::array<const Point_d*, D + 1>& s) const { return Inner().orientation_d_object()(unwrap(s)); }
  };
  struct Side_of_oriented_sphere_d {
    kernel::Oriented_side operator()(const std::array<const Point_d*, D + 2>& s) const {
      return Inner().side_of_oriented_sphere_d_object()(unwrap(s));
    }
  };
  struct Side_of_oriented_sphere_unperturbed_d {
    kernel::Oriented_side operator()(const std::array<const Point_d*, D + 2>& s) const {
      return Inner().side_of_oriented_sphere_unperturbed_d_object()(unwrap(s));
    }
  };
  struct Compare_lexicographically_d {
    kernel::Comparison_result operator()(const Point_d& a, const Point_d& b) const {
      return Inner().compare_lexicographically_d_object()(a.p_, b.p_);
    }
  };
  struct Approximate_coordinates_d {
    std::array<double, D> operator()(const Point_d& p) const { return Inner().approximate_coordinates_object()(p.p_); }
  };

  Orientation_d orientation_d_object() const { return {}; }
  Side_of_oriented_sphere_d side_of_oriented_sphere_d_object() const { return {}; }
  Side_of_oriented_sphere_unperturbed_d side_of_oriented_sphere_unperturbed_d_object() const { return {}; }
  Compare_lexicographically_d compare_lexicographically_d_object() const { return {}; }
  Approximate_coordinates_d approximate_coordinates_object() const { return {}; }

  static std::vector<Point_d> points(const std::vector<kernel::Point_d<D>>& ps) {
    return {ps.begin(), ps.end()};
  }

 private:
  template <std::size_t N>
  static std::array<const kernel::Point_d<D>*, N> unwrap(const std::array<const Point_d*, N>& s) {
    std::array<const kernel::Point_d<D>*, N> r;
    for (std::size_t i = 0; i < N; ++i) r[i] = &s[i]->p_;
    return r;
  }
};

static_assert(kernel::DelaunayKernel<Kernel_archetype<2>> && kernel::DelaunayKernel<Kernel_archetype<6>>);

}  // namespace dewall::test
