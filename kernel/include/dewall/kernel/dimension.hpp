// From a dimension known at run time (a file's, an array's) to the templates
// compiled for D = min_dimension … max_dimension.
#pragma once

#include <stdexcept>
#include <string>
#include <type_traits>

#include "dewall/kernel/point.hpp"

namespace dewall::kernel {

/// "dimension 7 is not supported (2 to 6)".
inline std::string unsupported_dimension_message(int dimension) {
  return "dimension " + std::to_string(dimension) + " is not supported (" + std::to_string(min_dimension) + " to " +
         std::to_string(max_dimension) + ")";
}

/// Calls f(std::integral_constant<int, D>{}) for the dimension D = 2 … 6 known
/// at run time. \throws std::invalid_argument for any other dimension.
template <class F>
decltype(auto) with_dimension(int dimension, F&& f) {
  switch (dimension) {
#define DEWALL_DIMENSION_CASE(D) \
  case D:                        \
    return f(std::integral_constant<int, D>{});
    DEWALL_FOR_EACH_DIMENSION(DEWALL_DIMENSION_CASE)
#undef DEWALL_DIMENSION_CASE
  }
  throw std::invalid_argument(unsupported_dimension_message(dimension));
}

}  // namespace dewall::kernel
