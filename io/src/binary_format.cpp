#include "binary_format.hpp"

#include <cstring>
#include <istream>
#include <ostream>

#include "dewall/io/point_reader.hpp"

namespace dewall::io::detail {

std::uint64_t load_le(const unsigned char* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

void store_le(unsigned char* p, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i, v >>= 8) p[i] = static_cast<unsigned char>(v & 0xff);
}

void write_binary_header(std::ostream& out, const char (&magic)[4], const Binary_header& h) {
  unsigned char header[binary_header_size] = {};
  std::memcpy(header, magic, 4);
  store_le(header + 4, h.version, 4);
  store_le(header + 8, h.dimension, 4);
  store_le(header + 12, h.field12, 4);
  store_le(header + 16, h.count, 8);
  out.write(reinterpret_cast<const char*>(header), binary_header_size);
}

Binary_header read_binary_header(std::istream& in, const std::string& name, const char (&magic)[4],
                                 const std::string& what) {
  unsigned char header[binary_header_size];
  in.read(reinterpret_cast<char*>(header), binary_header_size);
  const auto got = static_cast<std::size_t>(in.gcount());
  if (got >= 4 && std::memcmp(header, magic, 4) != 0)
    throw Parse_error(name + ": not a " + what + " (the first bytes are not '" + std::string(magic, 4) + "')");
  if (got < binary_header_size)
    throw Parse_error(name + ": truncated: the header needs " + std::to_string(binary_header_size) +
                      " bytes, the file has " + std::to_string(got));
  return {static_cast<std::uint32_t>(load_le(header + 4, 4)), static_cast<std::uint32_t>(load_le(header + 8, 4)),
          static_cast<std::uint32_t>(load_le(header + 12, 4)), load_le(header + 16, 8)};
}

std::string binary_truncated(const std::string& name, const std::string& announced, std::uint64_t payload,
                             std::uint64_t size) {
  return name + ": truncated: the header announces " + announced + " (" + std::to_string(binary_header_size + payload) +
         " bytes), the file has " + std::to_string(size) + " bytes";
}

bool check_binary_size(std::istream& in, const std::string& name, std::uint64_t payload, const std::string& announced,
                       const std::string& item, std::uint64_t file_size) {
  std::uint64_t size = file_size;
  if (size == 0) {
    const auto here = in.tellg();
    if (here == std::streampos(-1)) {
      in.clear();
      return false;
    }
    in.seekg(0, std::ios::end);
    const auto end = in.tellg();
    in.seekg(here);
    const bool sized = end != std::streampos(-1) && in.good();
    in.clear();
    if (!sized) return false;
    size = static_cast<std::uint64_t>(end);
  }
  const std::uint64_t expected = binary_header_size + payload;
  if (size < expected) throw Parse_error(binary_truncated(name, announced, payload, size));
  if (size > expected)
    throw Parse_error(name + ": " + std::to_string(size - expected) + " bytes after the last " + item + " (the header announces " + announced + ")");
  return true;
}

}  // namespace dewall::io::detail
