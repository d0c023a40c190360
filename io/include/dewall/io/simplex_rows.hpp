// The bytes of the three simplex list formats, a header and whole rows at a
// time, for indices of any width: the one formatting of simplices that every
// writer uses, io's files (32-bit indices) and dewall-mpi's parts, which each
// rank formats and writes at its own offset (64-bit global indices, .dwsx
// with 4 or 8 bytes per index).
#pragma once

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

namespace dewall::io {

/// The simplex list formats a writer assembles from parts.
enum class Simplex_format {
  plain,   ///< one simplex per line, indices separated by single spaces
  ele,     ///< TetGen: "<count> <vertices per simplex> 0", then numbered rows
  binary,  ///< .dwsx (binary_simplices.hpp)
};

/// The format a simplex output's name selects: .dwsx, .ele (any case), else plain.
Simplex_format simplex_format_named_by(std::string_view path);

/// The file's header for `count` simplices of `dimension`: .dwsx's (with
/// `index_bytes` per index), .ele's; the plain list has none.
std::string simplex_file_header(Simplex_format f, int dimension, std::uint64_t count, int index_bytes = 4);

/// Appends whole rows of `k` indices from `indices`: .dwsx little-endian with
/// `index_bytes` (4 or 8) per index, .ele rows numbered from `row` (which
/// advances) with every index shifted by `shift` (a .node file numbered from
/// 1), or the plain list. \pre indices.size() is a multiple of k, and every
/// index fits `index_bytes`.
template <class Index>
void append_simplex_rows(std::string& out, std::span<const Index> indices, std::size_t k, Simplex_format f,
                         std::uint64_t& row, int index_bytes = 4, std::uint64_t shift = 0) {
  static_assert(std::is_unsigned_v<Index>);
  if (f == Simplex_format::binary) {
    const std::size_t at = out.size();
    out.resize(at + indices.size() * static_cast<std::size_t>(index_bytes));
    char* to = out.data() + at;
    if (indices.empty()) return;  // (memcpy may not be given an empty span's null pointer)
    if (std::endian::native == std::endian::little && sizeof(Index) == static_cast<std::size_t>(index_bytes)) {
      std::memcpy(to, indices.data(), indices.size() * sizeof(Index));  // the stored form already
    } else {
      for (const Index v : indices)
        for (int b = 0; b < index_bytes; ++b) *to++ = static_cast<char>(std::uint64_t{v} >> (8 * b));
    }
    row += indices.size() / k;
    return;
  }
  char number[24];
  const auto put = [&](std::uint64_t x) { out.append(number, std::to_chars(number, number + sizeof number, x).ptr); };
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (f == Simplex_format::ele && i % k == 0) {
      put(row);
      out += ' ';
    }
    put(std::uint64_t{indices[i]} + shift);
    const bool last = (i + 1) % k == 0;
    out += last ? '\n' : ' ';
    row += last;
  }
}

}  // namespace dewall::io
