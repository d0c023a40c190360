// Hashing shared by the engines: a 64-bit finalizer whose every input bit
// moves every output bit (the BRIO rounds' draws, the ridge table's keys).
#pragma once

#include <cstdint>

namespace dewall::detail {

/// splitmix64's finalizer: a well-mixed 64-bit hash (the seeded draws of the rounds).
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

}  // namespace dewall::detail
