// The binary point format ("DWPT", extension .dwpt) for 10^7 points and more:
// a fixed 24-byte header, then the coordinates as raw doubles. Reading and
// writing run at disk speed and round-trip every double bit for bit (text
// formats need 17 significant digits and a parse per value).
//
//   offset  size  field
//        0     4  magic: the bytes 'D' 'W' 'P' 'T'
//        4     4  version: 1 (unsigned, little-endian)
//        8     4  dimension: 2 … 6 (unsigned, little-endian)
//       12     4  flags: 0 (reserved; a reader rejects other values, so a
//                 future extension is never misread)
//       16     8  count: number of points (unsigned, little-endian)
//       24  8·count·dimension  coordinates: IEEE 754 binary64, little-endian,
//                 point after point (x0 y0 z0 x1 y1 z1 …)
//
// The file size is exactly 24 + 8·count·dimension bytes; anything else is an
// error (a truncated file is never taken for a smaller point set). The full
// description, with a Python reader, is in docs/formats.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>

#include "dewall/io/point_reader.hpp"

namespace dewall::io {

class Progress;

/// The four magic bytes that open a binary point file.
inline constexpr char binary_points_magic[4] = {'D', 'W', 'P', 'T'};
inline constexpr std::uint32_t binary_points_version = 1;
inline constexpr std::size_t binary_points_header_size = 24;

/// Reads a binary point file from `in` (opened in binary mode), magic included;
/// `name` is used in messages. `progress`, when given, receives the bytes read.
/// \throws Parse_error on a wrong magic, version, flags or dimension, a
/// truncated file (the message says how many bytes were expected and found), or
/// bytes after the last point. `file_size`: the file's bytes when the caller
/// knows them (0: asked of `in` when it can seek): a file of known size is
/// checked before it is read, and its points allocated once.
Point_table read_binary_points(std::istream& in, const std::string& name, Progress* progress = nullptr,
                               std::uint64_t file_size = 0);

/// Writes `t` in the binary format; `progress`, when given, receives the bytes
/// written. The caller checks the stream state.
void write_binary_points(std::ostream& out, const Point_table& t, Progress* progress = nullptr);

/// Size in bytes of a binary file holding `count` points of `dimension`.
constexpr std::uint64_t binary_points_file_size(std::uint64_t count, int dimension) {
  return binary_points_header_size + 8 * count * static_cast<std::uint64_t>(dimension);
}

}  // namespace dewall::io
