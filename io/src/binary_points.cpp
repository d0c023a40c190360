#include "dewall/io/binary_points.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <istream>
#include <ostream>
#include <vector>

#include "dewall/io/progress.hpp"

namespace dewall::io {
namespace {

// The header fields are decoded byte by byte, so the code is the same on any
// host; only the coordinate block needs a swap on a big-endian one.
std::uint64_t load_le(const unsigned char* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

void store_le(unsigned char* p, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i, v >>= 8) p[i] = static_cast<unsigned char>(v & 0xff);
}

void swap_doubles_if_big_endian(double* values, std::size_t n) {
  if constexpr (std::endian::native == std::endian::big) {
    for (std::size_t i = 0; i < n; ++i) {
      unsigned char b[8];
      std::memcpy(b, &values[i], 8);
      std::reverse(b, b + 8);
      std::memcpy(&values[i], b, 8);
    }
  } else {
    (void)values, (void)n;
  }
}

// Chunks of 1 Mi doubles (8 MiB): large enough to run at disk speed, small
// enough that a corrupt count never makes us allocate memory the file cannot fill.
constexpr std::size_t chunk_values = std::size_t{1} << 20;

}  // namespace

Point_table read_binary_points(std::istream& in, const std::string& name, Progress* progress) {
  unsigned char header[binary_points_header_size];
  in.read(reinterpret_cast<char*>(header), binary_points_header_size);
  const auto got_header = static_cast<std::size_t>(in.gcount());
  if (got_header >= 4 && std::memcmp(header, binary_points_magic, 4) != 0)
    throw Parse_error(name + ": not a binary point file (the first bytes are not 'DWPT')");
  if (got_header < binary_points_header_size)
    throw Parse_error(name + ": truncated: the header needs " + std::to_string(binary_points_header_size) +
                      " bytes, the file has " + std::to_string(got_header));
  const auto version = load_le(header + 4, 4);
  const auto dimension = load_le(header + 8, 4);
  const auto flags = load_le(header + 12, 4);
  const auto count = load_le(header + 16, 8);
  if (version != binary_points_version)
    throw Parse_error(name + ": binary point format version " + std::to_string(version) + " is not supported (1)");
  if (flags != 0) throw Parse_error(name + ": unknown flags " + std::to_string(flags) + " in the header (expected 0)");
  if (dimension < 2 || dimension > 6)
    throw Parse_error(name + ": dimension " + std::to_string(dimension) + " is not supported (2 to 6)");
  if (count == 0) throw Parse_error(name + ": no points");
  // 2^58 points would already overflow the byte count; no real file is near it.
  if (count > (std::uint64_t{1} << 56))
    throw Parse_error(name + ": the header announces an impossible point count " + std::to_string(count));
  const std::uint64_t values = count * dimension;
  const std::uint64_t expected_size = binary_points_file_size(count, static_cast<int>(dimension));
  auto truncated = [&](std::uint64_t size) {
    return Parse_error(name + ": truncated: the header announces " + std::to_string(count) + " points of dimension " +
                       std::to_string(dimension) + " (" + std::to_string(expected_size) + " bytes), the file has " +
                       std::to_string(size) + " bytes");
  };

  // A seekable stream (a file) tells its size up front: reject a wrong size
  // before reading, and allocate once.
  const auto here = in.tellg();
  bool sized = false;
  if (here != std::streampos(-1)) {
    in.seekg(0, std::ios::end);
    const auto end = in.tellg();
    in.seekg(here);
    if (end != std::streampos(-1) && in) {
      const auto size = static_cast<std::uint64_t>(end);
      if (size < expected_size) throw truncated(size);
      if (size > expected_size)
        throw Parse_error(name + ": " + std::to_string(size - expected_size) +
                          " bytes after the last point (the header announces " + std::to_string(count) +
                          " points of dimension " + std::to_string(dimension) + ")");
      sized = true;
    }
    in.clear();
  }

  Point_table t;
  t.dimension = static_cast<int>(dimension);
  if (sized) t.coordinates.reserve(values);
  if (progress) progress->phase("reading " + name, expected_size);
  std::uint64_t read = 0;
  while (read < values) {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(chunk_values, values - read));
    t.coordinates.resize(read + n);
    in.read(reinterpret_cast<char*>(t.coordinates.data() + read), static_cast<std::streamsize>(n * 8));
    const auto got = static_cast<std::uint64_t>(in.gcount());
    if (got != n * 8) throw truncated(binary_points_header_size + read * 8 + got);
    swap_doubles_if_big_endian(t.coordinates.data() + read, n);
    read += n;
    if (progress) progress->advance_to(binary_points_header_size + read * 8);
  }
  if (!sized && in.peek() != std::char_traits<char>::eof())
    throw Parse_error(name + ": bytes after the last point (the header announces " + std::to_string(count) +
                      " points of dimension " + std::to_string(dimension) + ")");
  if (progress) progress->finish();
  return t;
}

void write_binary_points(std::ostream& out, const Point_table& t, Progress* progress) {
  unsigned char header[binary_points_header_size] = {};
  std::memcpy(header, binary_points_magic, 4);
  store_le(header + 4, binary_points_version, 4);
  store_le(header + 8, static_cast<std::uint64_t>(t.dimension), 4);
  store_le(header + 12, 0, 4);
  store_le(header + 16, t.size(), 8);
  out.write(reinterpret_cast<const char*>(header), binary_points_header_size);
  const std::size_t values = t.size() * static_cast<std::size_t>(t.dimension);
  std::vector<double> buffer;
  for (std::size_t done = 0; done < values && out;) {
    const std::size_t n = std::min(chunk_values, values - done);
    const double* chunk = t.coordinates.data() + done;
    if constexpr (std::endian::native == std::endian::big) {
      buffer.assign(chunk, chunk + n);
      swap_doubles_if_big_endian(buffer.data(), n);
      chunk = buffer.data();
    }
    out.write(reinterpret_cast<const char*>(chunk), static_cast<std::streamsize>(n * 8));
    done += n;
    if (progress) progress->advance_to(binary_points_header_size + done * 8);
  }
}

}  // namespace dewall::io
