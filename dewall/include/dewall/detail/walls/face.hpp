// Faces of the triangulation: D vertex indices, oriented.
//
// Convention: a face (f_0 … f_{D−1}) is stored so that its *outer* side is where
// orientation_d(f_0, …, f_{D−1}, q) is POSITIVE. A simplex is emitted as its
// face followed by its apex, hence positively oriented. Topology only: no
// geometry here (ARCHITECTURE.md, "Topology knows no geometry").
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>

#include "dewall/detail/common/index.hpp"

namespace dewall::detail {

template <int D>
using Face = std::array<Index, D>;

/// The key identifying a face regardless of orientation: its sorted indices.
template <int D>
Face<D> face_key(Face<D> f) {
  std::sort(f.begin(), f.end());
  return f;
}

template <int D>
std::uint64_t face_hash(const Face<D>& key) {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (Index v : key) {
    h ^= v;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 32;
  }
  return h;
}

/// The simplex of face f and apex a: f followed by a, so positively oriented
/// when a lies on f's outer side (the convention above). Every simplex DeWall
/// builds is made here.
template <int D>
Simplex<D> with_apex(const Face<D>& f, Index a) {
  Simplex<D> s;
  std::copy(f.begin(), f.end(), s.begin());
  s[D] = a;
  return s;
}

/// The face of the positively oriented simplex s opposite vertex i, oriented so
/// that its outer side is away from s[i].
/// Derivation: moving q from position i to the end of (s_0 … q … s_D) takes D − i
/// transpositions, so orientation(face, q) = (−1)^(D−i)·orientation(s with s_i → q),
/// and the latter is positive on s_i's (inner) side. For D − i even we swap two
/// vertices to make the outer side positive.
template <int D>
Face<D> opposite_face(const Simplex<D>& s, int i) {
  Face<D> f;
  int k = 0;
  for (int j = 0; j <= D; ++j)
    if (j != i) f[static_cast<std::size_t>(k++)] = s[static_cast<std::size_t>(j)];
  if ((D - i) % 2 == 0) std::swap(f[0], f[1]);
  return f;
}

/// The same face with its outer side flipped.
template <int D>
Face<D> flipped(Face<D> f) {
  std::swap(f[0], f[1]);
  return f;
}

}  // namespace dewall::detail
