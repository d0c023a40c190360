// Errors for bad input. Exceptions are for input the caller can fix; broken
// invariants are assertions (detail/assert.hpp).
#pragma once

#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

namespace dewall {

/// The input cannot be triangulated: a non-finite coordinate, too few distinct
/// points, or points that do not span E^D. `point_index` names the offending
/// input point when there is one (npos otherwise).
class Invalid_input : public std::runtime_error {
 public:
  static constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();
  explicit Invalid_input(const std::string& what, std::size_t point_index = npos)
      : std::runtime_error(what), point_index_(point_index) {}
  std::size_t point_index() const { return point_index_; }

 private:
  std::size_t point_index_;
};

}  // namespace dewall
