// The index type of every engine: a point's index (local or the caller's),
// and a simplex as D + 1 of them. Topology only.
#pragma once

#include <array>
#include <cstdint>

namespace dewall::detail {

using Index = std::uint32_t;

template <int D>
using Simplex = std::array<Index, D + 1>;

}  // namespace dewall::detail
