#include "dewall/io/binary_points.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <istream>
#include <ostream>
#include <vector>

#include "binary_format.hpp"
#include "dewall/io/dimensions.hpp"
#include "dewall/io/progress.hpp"

namespace dewall::io {
namespace {

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

Point_table read_binary_points(std::istream& in, const std::string& name, Progress* progress, std::uint64_t file_size) {
  const auto header = detail::read_binary_header(in, name, binary_points_magic, "binary point file");
  const std::uint64_t version = header.version, dimension = header.dimension, flags = header.field12,
                      count = header.count;
  if (version != binary_points_version)
    throw Parse_error(name + ": binary point format version " + std::to_string(version) + " is not supported (1)");
  if (flags != 0) throw Parse_error(name + ": unknown flags " + std::to_string(flags) + " in the header (expected 0)");
  if (!is_supported_dimension(dimension))
    throw Parse_error(name + ": dimension " + std::to_string(dimension) + " is not supported (" + dimension_range() + ")");
  if (count == 0) throw Parse_error(name + ": no points");
  // 2^58 points would already overflow the byte count; no real file is near it.
  if (count > (std::uint64_t{1} << 56))
    throw Parse_error(name + ": the header announces an impossible point count " + std::to_string(count));
  const std::uint64_t values = count * dimension;
  const std::uint64_t expected_size = binary_points_file_size(count, static_cast<int>(dimension));
  const std::string announced = std::to_string(count) + " points of dimension " + std::to_string(dimension);
  // A file's size is known up front: reject a wrong size before reading, and
  // allocate once.
  const bool sized = detail::check_binary_size(in, name, values * 8, announced, "point", file_size);

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
    if (got != n * 8)
      throw Parse_error(detail::binary_truncated(name, announced, values * 8, binary_points_header_size + read * 8 + got));
    swap_doubles_if_big_endian(t.coordinates.data() + read, n);
    read += n;
    if (progress) progress->advance_to(binary_points_header_size + read * 8);
  }
  if (!sized && in.peek() != std::char_traits<char>::eof())
    throw Parse_error(name + ": bytes after the last point (the header announces " + announced + ")");
  if (progress) progress->finish();
  return t;
}

void write_binary_points(std::ostream& out, const Point_table& t, Progress* progress) {
  detail::write_binary_header(out, binary_points_magic,
                              {binary_points_version, static_cast<std::uint32_t>(t.dimension), 0, t.size()});
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
