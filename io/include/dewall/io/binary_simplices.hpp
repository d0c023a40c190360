// The binary simplex format ("DWSX", extension .dwsx): the triangulation of
// 10^7 points and more without formatting or parsing a number. The same
// 24-byte header layout as the binary points (binary_points.hpp):
//
//   offset  size  field
//        0     4  magic: the bytes 'D' 'W' 'S' 'X'
//        4     4  version: 1 (unsigned, little-endian)
//        8     4  dimension D: 2 … 6 (a simplex has D + 1 vertices)
//       12     4  bytes per index: 4 or 8
//       16     8  count: number of simplices; 2^64 − 1 when the writer could
//                 not know it (a stream to a pipe): the simplices then run to
//                 the end of the input
//       24     w·(D+1)·count  the indices, unsigned little-endian, simplex
//                 after simplex, zero-based, each simplex positively oriented
//
// With a known count the file is exactly 24 + w·(D+1)·count bytes; anything
// else is an error. docs/formats.md has the description and a NumPy reader.
#pragma once

#include <cstdint>
#include <cstddef>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include "dewall/io/simplex_reader.hpp"

namespace dewall::io {

class Progress;

inline constexpr char binary_simplices_magic[4] = {'D', 'W', 'S', 'X'};
inline constexpr std::uint32_t binary_simplices_version = 1;
/// The count of a file whose writer did not know it.
inline constexpr std::uint64_t binary_simplices_unknown_count = ~std::uint64_t{0};

/// Writes `t` (simplices of dimension t.vertices_per_simplex − 1) with 4-byte
/// indices (simplex_rows.hpp formats them); `progress`, when given, receives
/// the simplices written. The caller checks the stream state.
void write_binary_simplices(std::ostream& out, const Simplex_table& t, Progress* progress = nullptr);

/// The header alone, for a writer that streams the indices after it
/// (binary_simplices_unknown_count when it cannot know the count yet), with
/// `index_bytes` (4 or 8) per index (dewall-mpi writes 8 beyond 2^32 − 2 points).
void write_binary_simplices_header(std::ostream& out, int dimension, std::uint64_t count, int index_bytes = 4);
/// Byte offset of the header's count field.
inline constexpr std::size_t binary_simplices_count_offset = 16;

/// A binary simplex file read a block of rows at a time (dewall certify reads
/// its rows so, never holding the file twice).
class Binary_simplex_reader {
 public:
  /// Reads and checks the header from `in` (opened in binary mode), magic
  /// included; `file_size` as for read_binary_points. \throws Parse_error as
  /// read_binary_simplices.
  Binary_simplex_reader(std::istream& in, std::string name, int dimension, std::uint64_t file_size = 0);
  /// Reads the next whole rows into `indices` (at most indices.size() / (D + 1),
  /// and at most 2^19 at a time: a corrupt count never makes a caller allocate
  /// more than the file has delivered); returns how many, 0 at the end.
  /// \throws Parse_error as read_binary_simplices.
  std::size_t read(std::span<std::uint32_t> indices);
  /// The count in the header (binary_simplices_unknown_count when unknown).
  std::uint64_t count() const { return count_; }
  /// Whether the count is known and the file's size matches it.
  bool sized() const { return sized_; }
  std::uint64_t rows_read() const { return rows_read_; }

  static constexpr std::size_t chunk_rows = std::size_t{1} << 19;

 private:
  std::istream& in_;
  std::string name_, announced_;
  std::size_t k_, width_ = 4, row_bytes_ = 0;
  std::uint64_t count_ = 0, rows_read_ = 0;
  bool known_ = false, sized_ = false, ended_ = false;
  std::vector<unsigned char> bytes_;
};

/// Reads a binary simplex file from `in` (opened in binary mode), magic
/// included; the rows get no line numbers (Simplex_list::lines stays empty).
/// \throws Parse_error on a wrong magic, version or index width, a dimension
/// other than `dimension` (the points'), an index of 2^32 or more, a truncated
/// file or bytes after the last simplex.
Simplex_list read_binary_simplices(std::istream& in, const std::string& name, int dimension, std::uint64_t file_size = 0);

}  // namespace dewall::io
