#include "dewall/io/binary_simplices.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <istream>
#include <ostream>
#include <span>
#include <vector>

#include "binary_format.hpp"
#include "dewall/io/point_reader.hpp"
#include "dewall/io/progress.hpp"

namespace dewall::io {
namespace {

// Rows per chunk: 8 MiB of 4-byte indices in 3D; a corrupt count never makes
// us allocate more than the file has delivered.
constexpr std::size_t chunk_rows = std::size_t{1} << 19;

}  // namespace

void write_binary_simplices_header(std::ostream& out, int dimension, std::uint64_t count, int index_bytes) {
  detail::write_binary_header(out, binary_simplices_magic,
                              {binary_simplices_version, static_cast<std::uint32_t>(dimension),
                               static_cast<std::uint32_t>(index_bytes), count});
}

Simplex_list read_binary_simplices(std::istream& in, const std::string& name, int dimension) {
  const auto header = detail::read_binary_header(in, name, binary_simplices_magic, "binary simplex file");
  if (header.version != binary_simplices_version)
    throw Parse_error(name + ": binary simplex format version " + std::to_string(header.version) +
                      " is not supported (1)");
  if (header.dimension != static_cast<std::uint32_t>(dimension))
    throw Parse_error(name + ": simplices of dimension " + std::to_string(header.dimension) + ", the points are of dimension " +
                      std::to_string(dimension));
  const std::uint32_t width = header.field12;
  if (width != 4 && width != 8)
    throw Parse_error(name + ": " + std::to_string(width) + " bytes per index is not supported (4 or 8)");
  const auto k = static_cast<std::size_t>(dimension + 1);
  const std::uint64_t row_bytes = width * k;
  const bool known = header.count != binary_simplices_unknown_count;
  if (known && header.count > (std::uint64_t{1} << 56) / row_bytes)
    throw Parse_error(name + ": the header announces an impossible simplex count " + std::to_string(header.count));
  const std::string announced =
      known ? std::to_string(header.count) + " simplices of dimension " + std::to_string(dimension) : "";
  const bool sized = known && detail::check_binary_size(in, name, header.count * row_bytes, announced, "simplex");

  Simplex_list list;
  list.format = "binary";
  list.table.vertices_per_simplex = static_cast<int>(k);
  if (sized) list.table.indices.reserve(header.count * k);
  std::vector<unsigned char> bytes;
  std::uint64_t rows_read = 0;
  while (!known || rows_read < header.count) {
    const auto rows = known ? static_cast<std::size_t>(std::min<std::uint64_t>(chunk_rows, header.count - rows_read))
                            : chunk_rows;
    bytes.resize(rows * row_bytes);
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (known && got != bytes.size())
      throw Parse_error(detail::binary_truncated(name, announced, header.count * row_bytes,
                                                 detail::binary_header_size + rows_read * row_bytes + got));
    if (!known && got % row_bytes != 0)
      throw Parse_error(name + ": truncated: the file ends inside simplex " + std::to_string(rows_read + got / row_bytes) +
                        " (" + std::to_string(got % row_bytes) + " of its " + std::to_string(row_bytes) + " bytes)");
    const std::size_t values = got / width;
    const std::size_t before = list.table.indices.size();
    list.table.indices.resize(before + values);
    if (std::endian::native == std::endian::little && width == 4) {  // the indices as they are
      // (values == 0: an empty list's data() may be null, which memcpy must not get.)
      if (values > 0) std::memcpy(list.table.indices.data() + before, bytes.data(), values * 4);
    } else {
      for (std::size_t i = 0; i < values; ++i) {
        const std::uint64_t v = detail::load_le(bytes.data() + i * width, static_cast<int>(width));
        if (v > UINT32_MAX)
          throw Parse_error(name + ": simplex " + std::to_string(rows_read + i / k) + ": vertex index " +
                            std::to_string(v) + " is too large (2^32 points at most)");
        list.table.indices[before + i] = static_cast<std::uint32_t>(v);
      }
    }
    rows_read += got / row_bytes;
    if (!known && got < bytes.size()) break;  // the end of the input
  }
  if (known && !sized && in.peek() != std::char_traits<char>::eof())
    throw Parse_error(name + ": bytes after the last simplex (the header announces " + announced + ")");
  return list;
}

}  // namespace dewall::io
