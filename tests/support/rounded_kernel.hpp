// Rounded_kernel<D, Bits, Declared>: Kernel_archetype<D> (exact predicates on
// opaque points) whose approximate coordinates are the points' coordinates
// rounded to `Bits` significant bits, the way a kernel over exact rationals or
// lazy numbers hands out an approximation: close, not equal. With Declared it
// states the bound through `approximate_coordinates_error` (concepts.hpp); the
// search must then prune only with that bound honoured. Without it the kernel
// says nothing about its approximations and the search may not prune at all.
// Few bits make the rounding comparable to the points' spacing, so a search
// that trusted the approximations would miss apexes.
#pragma once

#include <array>
#include <cmath>

#include "support/kernel_archetype.hpp"

namespace dewall::test {

template <int D, int Bits, bool Declared>
class Rounded_kernel : public Kernel_archetype<D> {
  using Base = Kernel_archetype<D>;

 public:
  using typename Base::Point_d;

  struct Approximate_coordinates_d {
    std::array<double, D> operator()(const Point_d& p) const {
      std::array<double, D> x = typename Base::Approximate_coordinates_d{}(p);
      for (double& v : x) v = round_to_bits(v);
      return x;
    }
  };
  Approximate_coordinates_d approximate_coordinates_object() const { return {}; }

  /// |x − x̂| ≤ 2^-Bits·|x̂|: x = m·2^e with ½ ≤ |m| < 1 is rounded to a
  /// multiple of 2^(e−Bits), an error of at most 2^(e−Bits−1), and |x̂| ≥ 2^(e−1).
  static double round_to_bits(double v) {
    if (v == 0) return 0;
    int e = 0;
    const double m = std::frexp(v, &e);
    return std::ldexp(std::nearbyint(std::ldexp(m, Bits)), e - Bits);
  }
};

template <int D, int Bits>
class Rounded_kernel<D, Bits, true> : public Rounded_kernel<D, Bits, false> {
 public:
  static constexpr double approximate_coordinates_error = 1.0 / (1 << Bits);
};

static_assert(kernel::DelaunayKernel<Rounded_kernel<3, 6, false>> && kernel::DelaunayKernel<Rounded_kernel<3, 6, true>>);

}  // namespace dewall::test
