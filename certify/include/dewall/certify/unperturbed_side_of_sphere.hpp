// The unperturbed in-sphere sign, for the closed-sphere ("Delaunay") test.
//
// The DelaunayKernel concept exposes only the perturbed predicate, which never
// answers ON_ORIENTED_BOUNDARY and so cannot tell "Delaunay" from "canonical".
// The certifier therefore takes the unperturbed sign from, in this order:
//  * the kernel's own `side_of_oriented_sphere_unperturbed_d_object()`, when it
//    has one (an optional extension of the concept);
//  * the kernel library's exact filtered predicate
//    dewall::kernel::side_of_oriented_sphere_d<D>, when the kernel declares that
//    its points are exactly their double coordinates
//    (approximate_coordinates_are_exact), as Filtered_kernel_d does.
// Either way the answer is the sign of the exact determinant.
#pragma once

#include <array>
#include <type_traits>

#include "dewall/kernel/concepts.hpp"
#include "dewall/kernel/orientation.hpp"  // side_of_sphere.hpp uses it without including it
#include "dewall/kernel/side_of_sphere.hpp"

namespace dewall::certify::detail {

template <class K>
concept Has_unperturbed_sphere = requires(const K& k, const std::array<const typename K::Point_d*, K::dimension + 2>& s) {
  { k.side_of_oriented_sphere_unperturbed_d_object()(s) } -> std::same_as<kernel::Oriented_side>;
};

/// True when certify<K> can decide the unperturbed sphere test.
template <class K>
inline constexpr bool has_unperturbed_sphere =
    Has_unperturbed_sphere<K> || kernel::approximate_coordinates_are_exact<K>;

/// ON_POSITIVE_SIDE: q strictly inside the sphere of the positively oriented
/// simplex s[0..D]; ON_ORIENTED_BOUNDARY: cospherical. Exact, unperturbed.
template <kernel::DelaunayKernel K>
kernel::Oriented_side unperturbed_side_of_sphere(const K& k,
                                                 const std::array<const typename K::Point_d*, K::dimension + 2>& s) {
  constexpr int D = K::dimension;
  if constexpr (Has_unperturbed_sphere<K>) {
    return k.side_of_oriented_sphere_unperturbed_d_object()(s);
  } else if constexpr (std::is_same_v<typename K::Point_d, kernel::Point_d<D>>) {
    return kernel::side_of_oriented_sphere_d<D>(s);
  } else {
    static_assert(kernel::approximate_coordinates_are_exact<K>,
                  "certify<K> needs the unperturbed sphere sign: give K a "
                  "side_of_oriented_sphere_unperturbed_d_object() or exact coordinates");
    std::array<kernel::Point_d<D>, D + 2> copy;
    kernel::Sphere_points<D> refs;
    const auto coords = k.approximate_coordinates_object();
    for (std::size_t i = 0; i < D + 2; ++i) {
      copy[i].x = coords(*s[i]);
      refs[i] = &copy[i];
    }
    return kernel::side_of_oriented_sphere_d<D>(refs);
  }
}

}  // namespace dewall::certify::detail
