// The dimensions the file formats and generators accept: those the library is
// compiled for. io/ depends on nothing of ours, so the range is stated here
// and cli/cli.hpp checks that it is the kernel's (kernel/point.hpp).
#pragma once

#include <string>

namespace dewall::io {

inline constexpr int min_dimension = 2;
inline constexpr int max_dimension = 6;

/// Whether `d` is a supported dimension.
template <class Integer>
constexpr bool is_supported_dimension(Integer d) {
  return d >= min_dimension && d <= max_dimension;
}

/// "2 to 6", for messages.
inline std::string dimension_range() { return std::to_string(min_dimension) + " to " + std::to_string(max_dimension); }

}  // namespace dewall::io
