// Errors for bad input. Exceptions are for input the caller can fix; broken
// invariants are assertions (detail/common/assert.hpp).
#pragma once

#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

namespace dewall {

/// The input cannot be triangulated: a non-finite coordinate, too few distinct
/// points, or points that do not span E^D. When one input point is at fault,
/// `point_index` names it (npos otherwise) and what() is "point N " followed by
/// `reason` ("has a non-finite coordinate …"), so a caller that numbers points
/// otherwise (a file counting from 1) can say "point " + its number + " " +
/// reason() instead of editing the text.
class Invalid_input : public std::runtime_error {
 public:
  static constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();
  /// The input as a whole is at fault; what() and reason() are `reason`.
  explicit Invalid_input(const std::string& reason) : std::runtime_error(reason), reason_(reason) {}
  /// Point `point_index` (zero-based, in input order) is at fault.
  Invalid_input(std::size_t point_index, const std::string& reason)
      : std::runtime_error("point " + std::to_string(point_index) + " " + reason),
        point_index_(point_index),
        reason_(reason) {}
  std::size_t point_index() const { return point_index_; }
  /// What is wrong, without the "point N " that names the point.
  const std::string& reason() const { return reason_; }

 private:
  std::size_t point_index_ = npos;
  std::string reason_;
};

/// The caller stopped the work: Options::progress returned false. Thrown by
/// dewall::triangulate and triangulate_to once every thread of the
/// triangulation has unwound, having freed what it built (a streaming sink
/// keeps the simplices it was given before).
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("dewall: cancelled by the caller (Options::progress returned false)") {}
};

}  // namespace dewall
