// What the two binary formats (points, binary_points.hpp; simplices,
// binary_simplices.hpp) share: a 24-byte header of little-endian fields
// (4 magic bytes, version, two 32-bit fields, a 64-bit count), then a payload
// whose size the header fixes, checked before anything is allocated when the
// input can tell its size.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>

namespace dewall::io::detail {

inline constexpr std::size_t binary_header_size = 24;

struct Binary_header {
  std::uint32_t version = 0;
  std::uint32_t dimension = 0;
  std::uint32_t field12 = 0;  // points: flags; simplices: bytes per index
  std::uint64_t count = 0;
};

// The fields are decoded byte by byte, so the code is the same on any host.
std::uint64_t load_le(const unsigned char* p, int bytes);
void store_le(unsigned char* p, std::uint64_t v, int bytes);

void write_binary_header(std::ostream& out, const char (&magic)[4], const Binary_header& h);

/// \throws Parse_error "NAME: not a WHAT (the first bytes are not 'MAGIC')" or
/// "NAME: truncated: the header needs 24 bytes, …".
Binary_header read_binary_header(std::istream& in, const std::string& name, const char (&magic)[4],
                                 const std::string& what);

/// Checks the file's size against `payload` (the header's promise, described
/// by `announced`, e.g. "10 points of dimension 3"): `file_size`, the whole
/// file's bytes when the caller knows them (Input_file::size()), else what a
/// seekable `in` tells. \returns false when neither is known (a pipe); the
/// reader then finds truncation as it reads. \throws Parse_error when the
/// file is shorter (binary_truncated) or longer ("N bytes after the last ITEM").
bool check_binary_size(std::istream& in, const std::string& name, std::uint64_t payload, const std::string& announced,
                       const std::string& item, std::uint64_t file_size = 0);

/// The error for a file that ends after `size` bytes of the `header + payload`
/// that `announced` promises.
std::string binary_truncated(const std::string& name, const std::string& announced, std::uint64_t payload,
                             std::uint64_t size);

}  // namespace dewall::io::detail
