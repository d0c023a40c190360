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

}  // namespace

void write_binary_simplices_header(std::ostream& out, int dimension, std::uint64_t count, int index_bytes) {
  detail::write_binary_header(out, binary_simplices_magic,
                              {binary_simplices_version, static_cast<std::uint32_t>(dimension),
                               static_cast<std::uint32_t>(index_bytes), count});
}

Binary_simplex_reader::Binary_simplex_reader(std::istream& in, std::string name, int dimension, std::uint64_t file_size)
    : in_(in), name_(std::move(name)), k_(static_cast<std::size_t>(dimension + 1)) {
  const auto header = detail::read_binary_header(in, name_, binary_simplices_magic, "binary simplex file");
  if (header.version != binary_simplices_version)
    throw Parse_error(name_ + ": binary simplex format version " + std::to_string(header.version) +
                      " is not supported (1)");
  if (header.dimension != static_cast<std::uint32_t>(dimension))
    throw Parse_error(name_ + ": simplices of dimension " + std::to_string(header.dimension) +
                      ", the points are of dimension " + std::to_string(dimension));
  width_ = header.field12;
  if (width_ != 4 && width_ != 8)
    throw Parse_error(name_ + ": " + std::to_string(width_) + " bytes per index is not supported (4 or 8)");
  row_bytes_ = width_ * k_;
  count_ = header.count;
  known_ = count_ != binary_simplices_unknown_count;
  if (known_ && count_ > (std::uint64_t{1} << 56) / row_bytes_)
    throw Parse_error(name_ + ": the header announces an impossible simplex count " + std::to_string(count_));
  announced_ = known_ ? std::to_string(count_) + " simplices of dimension " + std::to_string(dimension) : "";
  sized_ = known_ && detail::check_binary_size(in, name_, count_ * row_bytes_, announced_, "simplex", file_size);
}

std::size_t Binary_simplex_reader::read(std::span<std::uint32_t> indices) {
  if (ended_) return 0;
  std::size_t rows = std::min<std::size_t>(indices.size() / k_, chunk_rows);
  if (known_) rows = static_cast<std::size_t>(std::min<std::uint64_t>(rows, count_ - rows_read_));
  // 4-byte little-endian indices go straight to their place; others through a buffer.
  const bool direct = std::endian::native == std::endian::little && width_ == 4;
  char* to = reinterpret_cast<char*>(indices.data());
  if (!direct) {
    bytes_.resize(rows * row_bytes_);
    to = reinterpret_cast<char*>(bytes_.data());
  }
  in_.read(to, static_cast<std::streamsize>(rows * row_bytes_));
  const auto got = static_cast<std::size_t>(in_.gcount());
  if (known_ && got != rows * row_bytes_)
    throw Parse_error(detail::binary_truncated(name_, announced_, count_ * row_bytes_,
                                               detail::binary_header_size + rows_read_ * row_bytes_ + got));
  if (!known_ && got % row_bytes_ != 0)
    throw Parse_error(name_ + ": truncated: the file ends inside simplex " + std::to_string(rows_read_ + got / row_bytes_) +
                      " (" + std::to_string(got % row_bytes_) + " of its " + std::to_string(row_bytes_) + " bytes)");
  const std::size_t values = got / width_;
  if (!direct)
    for (std::size_t i = 0; i < values; ++i) {
      const std::uint64_t v = detail::load_le(bytes_.data() + i * width_, static_cast<int>(width_));
      if (v > UINT32_MAX)
        throw Parse_error(name_ + ": simplex " + std::to_string(rows_read_ + i / k_) + ": vertex index " +
                          std::to_string(v) + " is too large (2^32 points at most)");
      indices[i] = static_cast<std::uint32_t>(v);
    }
  rows_read_ += got / row_bytes_;
  if ((!known_ && got < rows * row_bytes_) || (known_ && rows_read_ == count_)) {
    ended_ = true;  // the end of the input
    if (known_ && !sized_ && in_.peek() != std::char_traits<char>::eof())
      throw Parse_error(name_ + ": bytes after the last simplex (the header announces " + announced_ + ")");
  }
  return got / row_bytes_;
}

Simplex_list read_binary_simplices(std::istream& in, const std::string& name, int dimension, std::uint64_t file_size) {
  Binary_simplex_reader reader(in, name, dimension, file_size);
  Simplex_list list;
  list.format = "binary";
  list.table.vertices_per_simplex = dimension + 1;
  const auto k = static_cast<std::size_t>(dimension + 1);
  if (reader.sized()) list.table.indices.reserve(reader.count() * k);
  for (;;) {
    const std::size_t before = list.table.indices.size();
    const std::size_t want = reader.sized() ? static_cast<std::size_t>(std::min<std::uint64_t>(
                                                  Binary_simplex_reader::chunk_rows, reader.count() - reader.rows_read()))
                                            : Binary_simplex_reader::chunk_rows;
    if (want == 0) break;
    list.table.indices.resize(before + want * k);
    const std::size_t rows = reader.read(std::span<std::uint32_t>(list.table.indices).subspan(before));
    list.table.indices.resize(before + rows * k);
    if (rows == 0) break;
  }
  return list;
}

}  // namespace dewall::io
