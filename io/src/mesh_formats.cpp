#include "dewall/io/mesh_formats.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <istream>
#include <optional>
#include <ostream>
#include <vector>

#include "dewall/io/dimensions.hpp"
#include "dewall/io/quote.hpp"
#include "text_lines.hpp"
#include "xyz_table.hpp"

namespace dewall::io {
namespace {

using detail::where;

std::vector<std::string_view> tokens_of(std::string_view line) {
  std::vector<std::string_view> tokens;
  detail::for_each_token(detail::without_comment(line), [&](std::string_view t) { tokens.push_back(t); });
  return tokens;
}

/// The first whitespace-separated word of `head` (after blank and '#' lines).
std::string_view first_word(std::string_view head) {
  std::size_t at = 0;
  while (at < head.size()) {
    const std::size_t end = std::min(head.find_first_of("\r\n", at), head.size());
    const auto tokens = tokens_of(head.substr(at, end - at));
    if (!tokens.empty()) return tokens.front();
    at = end + 1;
  }
  return {};
}

/// A count of a header (PLY's element sizes, OFF's vertex count): decimal
/// digits, at most 2^40 (the readers never allocate for it before the data is there).
std::size_t count_of(std::string_view token, const std::string& name, std::size_t line_no, const char* what) {
  const bool digits = !token.empty() && std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (digits && token.size() > 13)
    throw Parse_error(where(name, line_no) + what + " " + quoted(token) + " is too large (at most 2^40)");
  if (!digits) throw Parse_error(where(name, line_no) + "invalid " + what + " " + quoted(token) + " (a non-negative integer)");
  std::size_t v = 0;
  for (char c : token) v = v * 10 + static_cast<std::size_t>(c - '0');
  if (v > (std::size_t{1} << 40)) throw Parse_error(where(name, line_no) + what + " " + quoted(token) + " is too large (at most 2^40)");
  return v;
}

/// The tokens of the next line that has any (a sectioned text format: gmsh,
/// CGAL), into `t`, which views `line`. \throws Parse_error "NAME:
/// truncated: the file ends in the WHAT" at the end of the input.
void next_tokens(detail::Line_source& source, std::string& line, std::vector<std::string_view>& t, const std::string& name,
                 const char* what) {
  do {
    if (!source.next(line)) throw Parse_error(name + ": truncated: the file ends in the " + what);
    t = tokens_of(line);
  } while (t.empty());
}

// ---------------------------------------------------------------- PLY

enum class Ply_type { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

std::size_t size_of(Ply_type t) {
  constexpr std::array<std::size_t, 8> sizes = {1, 1, 2, 2, 4, 4, 4, 8};
  return sizes[static_cast<std::size_t>(t)];
}

bool parse_ply_type(std::string_view word, Ply_type& t) {
  struct Named {
    std::string_view a, b;
    Ply_type type;
  };
  constexpr std::array<Named, 8> names = {{{"char", "int8", Ply_type::int8},
                                           {"uchar", "uint8", Ply_type::uint8},
                                           {"short", "int16", Ply_type::int16},
                                           {"ushort", "uint16", Ply_type::uint16},
                                           {"int", "int32", Ply_type::int32},
                                           {"uint", "uint32", Ply_type::uint32},
                                           {"float", "float32", Ply_type::float32},
                                           {"double", "float64", Ply_type::float64}}};
  for (const auto& n : names)
    if (word == n.a || word == n.b) return t = n.type, true;
  return false;
}

struct Ply_property {
  std::string name;
  Ply_type type = Ply_type::float32;
  bool list = false;
  Ply_type count_type = Ply_type::uint8;  // a list's
};

struct Ply_element {
  std::string name;
  std::size_t count = 0;
  std::vector<Ply_property> properties;
};

enum class Ply_format { ascii, little_endian, big_endian };

/// Reads binary PLY values of the file's byte order.
class Ply_binary {
 public:
  Ply_binary(std::istream& in, const std::string& name, Ply_format format) : in_(in), name_(name), format_(format) {}

  double value(Ply_type t, const char* what) {
    unsigned char b[8];
    const std::size_t n = size_of(t);
    in_.read(reinterpret_cast<char*>(b), static_cast<std::streamsize>(n));
    if (static_cast<std::size_t>(in_.gcount()) != n)
      throw Parse_error(name_ + ": truncated: the data ends in the middle of " + what);
    const bool little = format_ == Ply_format::little_endian;
    if (little != (std::endian::native == std::endian::little)) std::reverse(b, b + n);
    switch (t) {
      case Ply_type::int8: return static_cast<double>(std::bit_cast<std::int8_t>(b[0]));
      case Ply_type::uint8: return b[0];
      case Ply_type::int16: return load<std::int16_t>(b);
      case Ply_type::uint16: return load<std::uint16_t>(b);
      case Ply_type::int32: return load<std::int32_t>(b);
      case Ply_type::uint32: return load<std::uint32_t>(b);
      case Ply_type::float32: return load<float>(b);
      case Ply_type::float64: return load<double>(b);
    }
    return 0;
  }

 private:
  template <class T>
  static double load(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof v);
    return static_cast<double>(v);
  }
  std::istream& in_;
  const std::string& name_;
  Ply_format format_;
};

/// An ASCII PLY value of type `t`: a float property's text is read as the
/// float it names (then widened exactly), an integer's must be whole.
double ply_text_value(std::string_view token, Ply_type t, const std::string& name, std::size_t line_no) {
  if (t == Ply_type::float32) {
    const std::string s(token);
    char* end = nullptr;
    errno = 0;
    const float v = std::strtof(s.c_str(), &end);
    if (end != s.c_str() + s.size()) throw Parse_error(where(name, line_no) + quoted(token) + " is not a number");
    if (errno == ERANGE && (std::isinf(v) || v == 0))
      throw Parse_error(where(name, line_no) + quoted(token) + " is out of the range of float (the property's type)");
    return v;
  }
  const double v = detail::parse_double(token, name, line_no);
  if (t != Ply_type::float64 && v != std::floor(v))
    throw Parse_error(where(name, line_no) + quoted(token) + " is not a whole number (the property's type is an integer)");
  return v;
}

}  // namespace

bool is_ply_header(std::string_view head) {
  return head.substr(0, 3) == "ply" && (head.size() == 3 || head[3] == '\n' || head[3] == '\r');
}

Point_table read_ply_points(std::istream& in, const std::string& name) {
  detail::Line_source source(in);
  std::string line;
  if (!source.next(line) || line != "ply") throw Parse_error(where(name, 1) + "not a PLY file (expected 'ply')");
  std::vector<Ply_element> elements;
  std::optional<Ply_format> format;
  for (;;) {
    if (!source.next(line)) throw Parse_error(name + ": truncated PLY header (no end_header)");
    const std::size_t n = source.number();
    const auto t = tokens_of(line);
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "end_header") break;
    if (t[0] == "format") {
      if (t.size() != 3 || t[2] != "1.0") throw Parse_error(where(name, n) + "expected 'format <encoding> 1.0'");
      if (t[1] == "ascii") format = Ply_format::ascii;
      else if (t[1] == "binary_little_endian") format = Ply_format::little_endian;
      else if (t[1] == "binary_big_endian") format = Ply_format::big_endian;
      else throw Parse_error(where(name, n) + "unknown PLY format " + quoted(t[1]));
    } else if (t[0] == "element") {
      if (t.size() != 3) throw Parse_error(where(name, n) + "expected 'element <name> <count>'");
      elements.push_back({std::string(t[1]), count_of(t[2], name, n, "element count"), {}});
    } else if (t[0] == "property") {
      if (elements.empty()) throw Parse_error(where(name, n) + "a property before any element");
      Ply_property p;
      const bool list = t.size() == 5 && t[1] == "list";
      if (!(list || t.size() == 3) || (list && !parse_ply_type(t[2], p.count_type)) ||
          !parse_ply_type(t[list ? 3 : 1], p.type))
        throw Parse_error(where(name, n) + "expected 'property <type> <name>' or 'property list <type> <type> <name>'" +
                          " (types: char, uchar, short, ushort, int, uint, float, double)");
      p.list = list;
      p.name = std::string(t.back());
      elements.back().properties.push_back(p);
    } else {
      throw Parse_error(where(name, n) + "unknown PLY header line " + quoted(line));
    }
  }
  if (!format) throw Parse_error(name + ": the PLY header has no format line");
  const auto vertex = std::find_if(elements.begin(), elements.end(), [](const Ply_element& e) { return e.name == "vertex"; });
  if (vertex == elements.end()) throw Parse_error(name + ": the PLY file has no vertex element");
  // Which property is which coordinate (z may be absent: a 2D set).
  std::array<int, 3> axis = {-1, -1, -1};
  for (std::size_t i = 0; i < vertex->properties.size(); ++i)
    for (std::size_t a = 0; a < 3; ++a)
      if (!vertex->properties[i].list && vertex->properties[i].name == std::string(1, static_cast<char>('x' + a)))
        axis[a] = static_cast<int>(i);
  if (axis[0] < 0 || axis[1] < 0) throw Parse_error(name + ": the PLY vertex element has no x and y properties");
  if (vertex->count == 0) throw Parse_error(name + ": no points (the PLY vertex element is empty)");

  std::vector<double> xyz;
  xyz.reserve(3 * std::min<std::size_t>(vertex->count, std::size_t{1} << 16));  // not trusting the count
  std::vector<double> values;
  // The elements up to the vertices, in the file's order: those before are skipped.
  for (auto e = elements.begin(); e <= vertex; ++e) {
    const bool keep = e == vertex;
    for (std::size_t r = 0; r < e->count; ++r) {
      values.clear();
      if (*format == Ply_format::ascii) {
        if (!source.next(line))
          throw Parse_error(name + ": truncated: the PLY header announces " + std::to_string(e->count) + " " + e->name +
                            " rows, the file has " + std::to_string(r));
        const std::size_t n = source.number();
        const auto t = tokens_of(line);
        std::size_t at = 0;
        for (const auto& p : e->properties) {
          const auto take = [&](Ply_type type) {
            if (at == t.size()) throw Parse_error(where(name, n) + "too few values for the " + e->name + " element");
            return ply_text_value(t[at++], type, name, n);
          };
          if (p.list) {
            const double items = take(p.count_type);
            if (items < 0) throw Parse_error(where(name, n) + "a negative list length");
            for (double k = 0; k < items; ++k) take(p.type);
            values.push_back(0);
          } else {
            values.push_back(take(p.type));
          }
        }
        if (at != t.size()) throw Parse_error(where(name, n) + "more values than the " + e->name + " element's properties");
      } else {
        Ply_binary b(in, name, *format);
        const std::string what = "the " + e->name + " element's row " + std::to_string(r);
        for (const auto& p : e->properties) {
          if (p.list) {
            const double items = b.value(p.count_type, what.c_str());
            if (items < 0) throw Parse_error(name + ": a negative list length in " + what);
            for (double k = 0; k < items; ++k) b.value(p.type, what.c_str());
            values.push_back(0);
          } else {
            values.push_back(b.value(p.type, what.c_str()));
          }
        }
      }
      if (keep)
        for (std::size_t a = 0; a < 3; ++a) xyz.push_back(axis[a] < 0 ? 0.0 : values[static_cast<std::size_t>(axis[a])]);
    }
  }
  return detail::table_from_xyz(std::move(xyz));
}

// ---------------------------------------------------------------- OFF

bool is_off_header(std::string_view head) {
  const auto w = first_word(head);
  return w.size() >= 3 && w.substr(w.size() - 3) == "OFF" &&
         std::all_of(w.begin(), w.end() - 3, [](char c) { return c == 'C' || c == 'N' || c == 'S' || c == 'T'; });
}

Point_table read_off_points(std::istream& in, const std::string& name) {
  detail::Line_source source(in);
  std::string line;
  std::vector<std::string_view> t;
  const auto next_data = [&] {
    while (source.next(line)) {
      t = tokens_of(line);
      if (!t.empty()) return true;
    }
    return false;
  };
  if (!next_data()) throw Parse_error(name + ": no points (an empty OFF file)");
  // The key word may share its line with the counts ("OFF 8 6 0").
  std::size_t extra = 0;  // per-vertex values after x y z: normals (N), colours (C), texture (ST)
  if (!t.empty() && is_off_header(t[0])) {
    const std::string_view key = t[0];
    extra = (key.find('N') != std::string_view::npos ? 3 : 0) + (key.find('C') != std::string_view::npos ? 4 : 0) +
            (key.find("ST") != std::string_view::npos ? 2 : 0);
    t.erase(t.begin());
    if (t.empty() && !next_data()) throw Parse_error(name + ": truncated OFF header (no counts)");
  }
  const std::size_t header_line = source.number();
  if (t.size() < 2 || t.size() > 3) throw Parse_error(where(name, header_line) + "expected the OFF counts '<vertices> <faces> <edges>'");
  const std::size_t count = count_of(t[0], name, header_line, "vertex count");
  if (count == 0) throw Parse_error(where(name, header_line) + "no points (the OFF header announces 0 vertices)");
  std::vector<double> xyz;
  xyz.reserve(3 * std::min<std::size_t>(count, std::size_t{1} << 16));
  for (std::size_t r = 0; r < count; ++r) {
    if (!next_data())
      throw Parse_error(name + ": truncated: the OFF header announces " + std::to_string(count) + " vertices, the file has " +
                        std::to_string(r));
    const std::size_t n = source.number();
    // Colours may be given as 3 or 4 values, or as one index: take x y z, check the rest are numbers.
    if (t.size() < 3) throw Parse_error(where(name, n) + "expected a vertex 'x y z', found " + std::to_string(t.size()) + " values");
    if (extra == 0 && t.size() != 3)
      throw Parse_error(where(name, n) + "expected a vertex 'x y z', found " + std::to_string(t.size()) + " values");
    for (std::size_t i = 0; i < t.size(); ++i) {
      const double v = detail::parse_double(t[i], name, n);
      if (i < 3) xyz.push_back(v);
    }
  }
  return detail::table_from_xyz(std::move(xyz));
}

// ---------------------------------------------------------------- OBJ

bool is_obj_header(std::string_view head) {
  const auto w = first_word(head);
  constexpr std::array<std::string_view, 9> statements = {"v", "vt", "vn", "f", "o", "g", "s", "mtllib", "usemtl"};
  return std::find(statements.begin(), statements.end(), w) != statements.end();
}

Point_table read_obj_points(std::istream& in, const std::string& name) {
  detail::Line_source source(in);
  std::string line;
  std::vector<double> xyz;
  while (source.next(line)) {
    const auto t = tokens_of(line);
    if (t.empty() || t[0] != "v") continue;
    const std::size_t n = source.number();
    // v x y z [w], or v x y z r g b (a common extension for colours).
    if (t.size() != 4 && t.size() != 5 && t.size() != 7)
      throw Parse_error(where(name, n) + "expected a vertex 'v x y z [w]', found " + std::to_string(t.size() - 1) + " values");
    for (std::size_t i = 1; i < t.size(); ++i) {
      const double v = detail::parse_double(t[i], name, n);
      if (i <= 3) xyz.push_back(v);
    }
  }
  if (xyz.empty()) throw Parse_error(name + ": no points (no 'v' line in the OBJ file)");
  return detail::table_from_xyz(std::move(xyz));
}

// ---------------------------------------------------------------- PCD

namespace {

/// A field of a PCD file: its name, TYPE (I, U or F), SIZE in bytes and COUNT of values.
struct Pcd_field {
  std::string name;
  char type = 'F';
  std::size_t size = 4;
  std::size_t count = 1;
};

/// Integers beyond 2^53 are not all doubles: a coordinate there is refused, not rounded.
constexpr double largest_exact_integer = 9007199254740992.0;

/// A coordinate of field `f` from its text: a float field's text is the float it
/// names (then widened exactly, as PLY's), an integer field's must be whole and exact.
double pcd_text_value(std::string_view token, const Pcd_field& f, const std::string& name, std::size_t line_no) {
  if (f.type == 'F') return ply_text_value(token, f.size == 4 ? Ply_type::float32 : Ply_type::float64, name, line_no);
  // Digits are read as the integer they are (a double would round 2^53 + 1 to 2^53 unnoticed).
  std::int64_t whole = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), whole);
  const bool integer = error == std::errc() && end == token.data() + token.size();
  const double v = integer ? static_cast<double>(whole) : ply_text_value(token, Ply_type::int32, name, line_no);
  if (integer ? (whole > (std::int64_t{1} << 53) || whole < -(std::int64_t{1} << 53)) : std::fabs(v) > largest_exact_integer)
    throw Parse_error(where(name, line_no) + quoted(token) + " is not exactly a double (beyond 2^53)");
  if (f.type == 'U' && v < 0) throw Parse_error(where(name, line_no) + quoted(token) + " is negative (the field's type is unsigned)");
  return v;
}

/// A coordinate of field `f` from its little-endian bytes (PCL writes the machine's order, little endian on
/// every platform it runs on).
double pcd_binary_value(const unsigned char* b, const Pcd_field& f, const std::string& name, std::size_t point) {
  unsigned char bytes[8];
  std::memcpy(bytes, b, f.size);
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + f.size);
  const auto load = [&](auto v) {
    std::memcpy(&v, bytes, sizeof v);
    return v;
  };
  if (f.type == 'F') return f.size == 4 ? static_cast<double>(load(float{})) : load(double{});
  const auto exact = [&](auto v) {
    if (static_cast<double>(v) > largest_exact_integer || static_cast<double>(v) < -largest_exact_integer)
      throw Parse_error(name + ": point " + std::to_string(point) + ": field " + f.name + " = " + std::to_string(v) +
                        " is not exactly a double (beyond 2^53)");
    return static_cast<double>(v);
  };
  switch (f.size) {
    case 1: return f.type == 'I' ? exact(load(std::int8_t{})) : exact(load(std::uint8_t{}));
    case 2: return f.type == 'I' ? exact(load(std::int16_t{})) : exact(load(std::uint16_t{}));
    case 4: return f.type == 'I' ? exact(load(std::int32_t{})) : exact(load(std::uint32_t{}));
    default: return f.type == 'I' ? exact(load(std::int64_t{})) : exact(load(std::uint64_t{}));
  }
}

}  // namespace

bool is_pcd_header(std::string_view head) { return head.substr(0, 6) == "# .PCD" || first_word(head) == "VERSION"; }

Point_table read_pcd_points(std::istream& in, const std::string& name) {
  detail::Line_source source(in);
  std::string line;
  std::vector<Pcd_field> fields;
  std::optional<std::size_t> width, height, points;
  std::string_view data;
  std::string data_line;
  while (data.empty()) {
    if (!source.next(line)) throw Parse_error(name + ": truncated PCD header (no DATA line)");
    const std::size_t n = source.number();
    const auto t = tokens_of(line);
    if (t.empty()) continue;
    const std::string_view key = t[0];
    const std::size_t values = t.size() - 1;
    const auto per_field = [&](const char* what) {
      if (fields.empty()) throw Parse_error(where(name, n) + what + " before FIELDS");
      if (values != fields.size())
        throw Parse_error(where(name, n) + what + " has " + std::to_string(values) + " values for " +
                          std::to_string(fields.size()) + " fields");
    };
    if (key == "VERSION") {
      continue;
    } else if (key == "FIELDS" || key == "COLUMNS") {  // (COLUMNS: PCD 0.5's name)
      if (values == 0) throw Parse_error(where(name, n) + "FIELDS names no field");
      fields.assign(values, {});
      for (std::size_t i = 0; i < values; ++i) fields[i].name = std::string(t[i + 1]);
    } else if (key == "SIZE") {
      per_field("SIZE");
      for (std::size_t i = 0; i < values; ++i) {
        const std::size_t size = count_of(t[i + 1], name, n, "field size");
        if (size != 1 && size != 2 && size != 4 && size != 8)
          throw Parse_error(where(name, n) + "field size " + quoted(t[i + 1]) + " is not 1, 2, 4 or 8");
        fields[i].size = size;
      }
    } else if (key == "TYPE") {
      per_field("TYPE");
      for (std::size_t i = 0; i < values; ++i) {
        if (t[i + 1] != "F" && t[i + 1] != "I" && t[i + 1] != "U")
          throw Parse_error(where(name, n) + "field type " + quoted(t[i + 1]) + " is not F, I or U");
        fields[i].type = t[i + 1][0];
      }
    } else if (key == "COUNT") {
      per_field("COUNT");
      for (std::size_t i = 0; i < values; ++i) fields[i].count = count_of(t[i + 1], name, n, "field count");
    } else if (key == "WIDTH" || key == "HEIGHT" || key == "POINTS") {
      if (values != 1) throw Parse_error(where(name, n) + "expected '" + std::string(key) + " <count>'");
      (key == "WIDTH" ? width : key == "HEIGHT" ? height : points) = count_of(t[1], name, n, "point count");
    } else if (key == "VIEWPOINT") {
      continue;  // the sensor's pose: not the points'
    } else if (key == "DATA") {
      if (values != 1) throw Parse_error(where(name, n) + "expected 'DATA ascii', 'DATA binary' or 'DATA binary_compressed'");
      if (t[1] == "binary_compressed")
        throw Parse_error(where(name, n) + "compressed PCD data (DATA binary_compressed) is not read: convert the file "
                          "to DATA binary or ascii first (PCL's pcl_convert_pcd_ascii_binary)");
      if (t[1] != "ascii" && t[1] != "binary")
        throw Parse_error(where(name, n) + "unknown PCD data encoding " + quoted(t[1]) + " (ascii or binary)");
      data_line = std::string(t[1]);
      data = data_line;
    } else {
      throw Parse_error(where(name, n) + "unknown PCD header line " + quoted(line));
    }
  }
  const std::size_t data_line_no = source.number();
  if (fields.empty()) throw Parse_error(name + ": the PCD header has no FIELDS line");
  for (const Pcd_field& f : fields)
    if (f.type == 'F' && f.size != 4 && f.size != 8)
      throw Parse_error(name + ": field " + quoted(f.name) + " is of type F and size " + std::to_string(f.size) +
                        " (a float is 4 or 8 bytes)");
  // Which field is which coordinate (z may be absent: a 2D set).
  std::array<int, 3> axis = {-1, -1, -1};
  for (std::size_t i = 0; i < fields.size(); ++i)
    for (std::size_t a = 0; a < 3; ++a)
      if (fields[i].name == std::string(1, static_cast<char>('x' + a))) {
        if (fields[i].count != 1)
          throw Parse_error(name + ": field " + fields[i].name + " has COUNT " + std::to_string(fields[i].count) +
                            " (a coordinate is one value)");
        axis[a] = static_cast<int>(i);
      }
  if (axis[0] < 0 || axis[1] < 0) throw Parse_error(name + ": the PCD fields have no x and y");
  if (width && height && points && *points != *width * *height)
    throw Parse_error(name + ": the PCD header announces POINTS " + std::to_string(*points) + " but WIDTH x HEIGHT = " +
                      std::to_string(*width) + " x " + std::to_string(*height));
  if (!points && !(width && height)) throw Parse_error(name + ": the PCD header gives neither POINTS nor WIDTH and HEIGHT");
  const std::size_t count = points ? *points : *width * *height;
  if (count == 0) throw Parse_error(where(name, data_line_no) + "no points (the PCD header announces 0)");

  std::vector<double> xyz;
  xyz.reserve(3 * std::min<std::size_t>(count, std::size_t{1} << 16));  // not trusting the count
  const auto truncated = [&](std::size_t read) {
    return Parse_error(name + ": truncated: the PCD header announces " + std::to_string(count) + " points, the file has " +
                       std::to_string(read));
  };
  if (data == "ascii") {
    std::size_t values_per_point = 0;
    for (const Pcd_field& f : fields) values_per_point += f.count;
    for (std::size_t r = 0; r < count; ++r) {
      std::vector<std::string_view> t;
      do {
        if (!source.next(line)) throw truncated(r);
        t = tokens_of(line);
      } while (t.empty());
      const std::size_t n = source.number();
      if (t.size() != values_per_point)
        throw Parse_error(where(name, n) + "expected " + std::to_string(values_per_point) + " values (the FIELDS' COUNTs), found " +
                          std::to_string(t.size()));
      std::array<double, 3> p = {0, 0, 0};
      std::size_t at = 0;
      for (std::size_t i = 0; i < fields.size(); ++i)
        for (std::size_t k = 0; k < fields[i].count; ++k, ++at) {
          const auto a = std::find(axis.begin(), axis.end(), static_cast<int>(i));
          if (a != axis.end()) p[static_cast<std::size_t>(a - axis.begin())] = pcd_text_value(t[at], fields[i], name, n);
          else detail::parse_double(t[at], name, n);  // another field's value: a number too
        }
      xyz.insert(xyz.end(), p.begin(), p.end());
    }
    source.expect_no_more_rows(name, std::to_string(count) + " points");
  } else {
    std::size_t row_size = 0;
    std::vector<std::size_t> offset(fields.size());
    for (std::size_t i = 0; i < fields.size(); ++i) {
      offset[i] = row_size;
      if (fields[i].count > (std::size_t{1} << 20)) throw Parse_error(name + ": field " + quoted(fields[i].name) + " has COUNT " + std::to_string(fields[i].count) + " (too large)");
      row_size += fields[i].size * fields[i].count;
    }
    std::vector<unsigned char> row(row_size);
    for (std::size_t r = 0; r < count; ++r) {
      in.read(reinterpret_cast<char*>(row.data()), static_cast<std::streamsize>(row_size));
      if (static_cast<std::size_t>(in.gcount()) != row_size) throw truncated(r);
      for (std::size_t a = 0; a < 3; ++a) {
        const int i = axis[a];
        xyz.push_back(i < 0 ? 0.0 : pcd_binary_value(row.data() + offset[static_cast<std::size_t>(i)], fields[static_cast<std::size_t>(i)], name, r));
      }
    }
    if (in.peek() != std::char_traits<char>::eof())
      throw Parse_error(name + ": more data than the PCD header announces (" + std::to_string(count) + " points of " +
                        std::to_string(row_size) + " bytes)");
  }
  return detail::table_from_xyz(std::move(xyz));
}

// ---------------------------------------------------------------- gmsh

namespace {

/// A gmsh mesh as read: the nodes' coordinates in file order, and the
/// elements of one type with their nodes as 0-based indices into that order.
struct Msh_mesh {
  std::vector<double> xyz;
  Simplex_table elements;
};

/// Reads MSH 2.2 or 4.1 ASCII; keeps the elements of gmsh type `type` (2: a
/// triangle, 4: a tetrahedron), `vertices` nodes each; 0 keeps none.
Msh_mesh read_msh(std::istream& in, const std::string& name, int type, int vertices) {
  detail::Line_source source(in);
  std::string line;
  std::vector<std::string_view> t;
  const auto next = [&](const char* what) { next_tokens(source, line, t, name, what); };
  const auto number = [&](std::size_t i) {
    if (i >= t.size()) throw Parse_error(where(name, source.number()) + "too few values on the line");
    return count_of(t[i], name, source.number(), "number");
  };
  Msh_mesh mesh;
  mesh.elements.vertices_per_simplex = vertices;
  std::vector<std::pair<std::size_t, std::size_t>> tag_index;  // node tag → its index in file order
  int major = 0;
  bool have_nodes = false;
  while (source.next(line)) {
    t = tokens_of(line);
    if (t.empty()) continue;
    const std::size_t at = source.number();
    if (t[0] == "$MeshFormat") {
      next("$MeshFormat section");
      if (t.size() < 3) throw Parse_error(where(name, source.number()) + "expected '<version> <file-type> <data-size>'");
      major = t[0].substr(0, 2) == "2." ? 2 : t[0].substr(0, 2) == "4." ? 4 : 0;
      if (!major) throw Parse_error(where(name, source.number()) + "gmsh format version " + quoted(t[0]) + " is not supported (2.2, 4.1)");
      if (t[1] != "0") throw Parse_error(where(name, source.number()) + "binary .msh files are not supported (write ASCII: gmsh -format msh22 or msh41)");
    } else if (t[0] == "$Nodes") {
      if (!major) throw Parse_error(where(name, at) + "$Nodes before $MeshFormat");
      next("$Nodes section");
      const std::size_t blocks = major == 2 ? 1 : number(0);
      const std::size_t count = major == 2 ? number(0) : number(1);
      for (std::size_t b = 0; b < blocks; ++b) {
        std::size_t in_block = count;
        if (major == 4) {
          next("$Nodes section");
          if (t.size() != 4 || t[2] != "0") throw Parse_error(where(name, source.number()) + "expected a node block '<dim> <tag> 0 <count>' (parametric nodes are not supported)");
          in_block = number(3);
          for (std::size_t i = 0; i < in_block; ++i) next("$Nodes section"), tag_index.emplace_back(number(0), tag_index.size());
        }
        for (std::size_t i = 0; i < in_block; ++i) {
          next("$Nodes section");
          const std::size_t first = major == 2 ? 1 : 0;
          if (t.size() != first + 3) throw Parse_error(where(name, source.number()) + "expected a node '" + (major == 2 ? "<tag> " : "") + "x y z'");
          if (major == 2) tag_index.emplace_back(number(0), tag_index.size());
          for (std::size_t j = first; j < first + 3; ++j) mesh.xyz.push_back(detail::parse_double(t[j], name, source.number()));
        }
      }
      if (tag_index.size() != count)
        throw Parse_error(where(name, at) + "the $Nodes section announces " + std::to_string(count) + " nodes, its blocks hold " + std::to_string(tag_index.size()));
      have_nodes = true;
      std::sort(tag_index.begin(), tag_index.end());
    } else if (t[0] == "$Elements") {
      if (!have_nodes) throw Parse_error(where(name, at) + "$Elements before $Nodes");
      next("$Elements section");
      const std::size_t blocks = major == 2 ? 1 : number(0);
      const std::size_t count = major == 2 ? number(0) : number(1);
      std::size_t seen = 0;
      const auto node = [&](std::size_t i) {
        const std::size_t tag = number(i);
        const auto it = std::lower_bound(tag_index.begin(), tag_index.end(), std::pair{tag, std::size_t{0}});
        if (it == tag_index.end() || it->first != tag) throw Parse_error(where(name, source.number()) + "node " + std::to_string(tag) + " is not in $Nodes");
        return static_cast<std::uint32_t>(it->second);
      };
      for (std::size_t b = 0; b < blocks; ++b) {
        std::size_t in_block = count, block_type = 0;
        if (major == 4) {
          next("$Elements section");
          if (t.size() != 4) throw Parse_error(where(name, source.number()) + "expected an element block '<dim> <tag> <type> <count>'");
          block_type = number(2), in_block = number(3);
        }
        for (std::size_t i = 0; i < in_block; ++i, ++seen) {
          next("$Elements section");
          // 2.2: tag type #tags tags… nodes…; 4.1: tag nodes… (the type is the block's).
          const std::size_t element_type = major == 2 ? number(1) : block_type;
          const std::size_t first = major == 2 ? 3 + number(2) : 1;
          if (element_type != static_cast<std::size_t>(type) || type == 0) continue;
          if (t.size() != first + static_cast<std::size_t>(vertices))
            throw Parse_error(where(name, source.number()) + "expected an element of " + std::to_string(vertices) + " nodes");
          for (std::size_t j = first; j < t.size(); ++j) mesh.elements.indices.push_back(node(j));
        }
      }
      if (seen != count)
        throw Parse_error(where(name, at) + "the $Elements section announces " + std::to_string(count) + " elements, its blocks hold " + std::to_string(seen));
    }
  }
  if (!have_nodes) throw Parse_error(name + ": no $Nodes section: not a gmsh mesh");
  return mesh;
}

}  // namespace

bool is_msh_header(std::string_view head) { return first_word(head) == "$MeshFormat"; }

Point_table read_msh_points(std::istream& in, const std::string& name) {
  auto mesh = read_msh(in, name, 0, 0);
  if (mesh.xyz.empty()) throw Parse_error(name + ": no points (the $Nodes section is empty)");
  return detail::table_from_xyz(std::move(mesh.xyz));
}

Simplex_table read_msh_simplices(std::istream& in, const std::string& name, int dimension) {
  if (dimension != 2 && dimension != 3)
    throw Parse_error(name + ": a gmsh mesh holds triangles or tetrahedra, not simplices of dimension " + std::to_string(dimension));
  auto mesh = read_msh(in, name, dimension == 2 ? 2 : 4, dimension + 1);
  if (mesh.elements.size() == 0)
    throw Parse_error(name + ": no " + (dimension == 2 ? "triangles" : "tetrahedra") + " in the gmsh mesh");
  return std::move(mesh.elements);
}

// ---------------------------------------------------------------- CGAL

Cgal_triangulation read_cgal_triangulation(std::istream& in, const std::string& name) {
  detail::Line_source source(in);
  std::string line;
  std::vector<std::string_view> t;
  const auto next = [&](const char* what) { next_tokens(source, line, t, name, what); };
  const auto fail = [&](const std::string& what) { return Parse_error(where(name, source.number()) + what); };
  const auto number = [&](std::size_t i, const char* what) { return count_of(t.at(i), name, source.number(), what); };
  const auto full_dimensional = [&](std::size_t dimension, std::size_t ambient) {
    if (dimension != ambient)
      throw Parse_error(name + ": the triangulation has dimension " + std::to_string(dimension) + ", its points " +
                        std::to_string(ambient) + ": it is not full-dimensional, and has no cell to certify");
  };

  // The header: "n m 2" (Triangulation_2, n counting the infinite vertex), or
  // the dimension and then the number of finite vertices (3D and dD).
  next("header");
  std::size_t dimension = 0, finite = 0, cell_count = 0;
  bool two = false;
  if (t.size() == 3) {
    two = true;
    const std::size_t n = number(0, "vertex count");
    cell_count = number(1, "face count");
    dimension = number(2, "dimension");
    full_dimensional(dimension, 2);
    if (n < 2) throw fail("no points");
    finite = n - 1;
  } else if (t.size() == 1) {
    dimension = number(0, "dimension");
    next("header");
    if (t.size() != 1) throw fail("expected the number of vertices");
    finite = number(0, "vertex count");
    if (finite == 0) throw fail("no points");
  } else {
    throw fail("not a CGAL triangulation: the first line holds 'n m 2' (2D) or the dimension (3D, dD)");
  }

  // The vertex lines: Triangulation_2 and _3 write the finite points; the dD
  // Triangulation first its infinite vertex ("0", or its dimension and
  // zeros), then each point after its dimension. The line after the first
  // `finite` says which: a lone count (the cells) or one more point.
  std::vector<double> first, values;
  std::size_t width = 0;  // values on every vertex line after the first
  const auto vertex_line = [&](std::vector<double>& into) {
    next("vertices");
    for (std::string_view token : t) into.push_back(detail::parse_double(token, name, source.number()));
    return t.size();
  };
  const std::size_t first_width = vertex_line(first);
  for (std::size_t i = 1; i < finite; ++i) {
    const std::size_t w = vertex_line(values);
    if (width == 0) width = w;
    if (w != width) throw fail("a vertex of " + std::to_string(w) + " values after vertices of " + std::to_string(width));
  }
  if (!two) next("cells");
  Point_table points;
  if (two || t.size() == 1) {
    points.dimension = two ? 2 : 3;
    if (!two) full_dimensional(dimension, 3);
    const auto d = static_cast<std::size_t>(points.dimension);
    if (first_width != d || (width != 0 && width != d))
      throw Parse_error(name + ": expected points of " + std::to_string(d) + " coordinates (a vertex or cell base that writes more is not supported)");
    points.coordinates = std::move(first);
    points.coordinates.insert(points.coordinates.end(), values.begin(), values.end());
  } else {
    // dD: the line just read is the last point.
    const std::size_t w = t.size();
    std::vector<double> last;
    for (std::string_view token : t) last.push_back(detail::parse_double(token, name, source.number()));
    if (width == 0) width = w;
    if (w != width || width < 2) throw fail("a vertex of " + std::to_string(w) + " values after vertices of " + std::to_string(width));
    const std::size_t d = width - 1;
    const bool infinite_ok = (first_width == 1 && first[0] == 0) || (first_width == width && first[0] == double(d));
    if (!infinite_ok) throw Parse_error(name + ": not a CGAL triangulation: its infinite vertex is neither '0' nor '" + std::to_string(d) + " 0 …'");
    if (!is_supported_dimension(d))
      throw Parse_error(name + ": dimension " + std::to_string(d) + " is not supported (" + dimension_range() + ")");
    full_dimensional(dimension, d);
    values.insert(values.end(), last.begin(), last.end());
    points.dimension = static_cast<int>(d);
    points.coordinates.reserve(finite * d);
    for (std::size_t i = 0; i < values.size(); i += width) {
      if (values[i] != double(d)) throw Parse_error(name + ": a point written after dimension " + std::to_string(values[i]) + ", not " + std::to_string(d));
      points.coordinates.insert(points.coordinates.end(), values.begin() + static_cast<std::ptrdiff_t>(i + 1),
                                values.begin() + static_cast<std::ptrdiff_t>(i + width));
    }
    next("cells");
  }

  // The cells: vertex 0 is the infinite vertex, v > 0 finite point v − 1;
  // then as many rows of neighbours, checked for their shape only.
  if (!two) {
    if (t.size() != 1) throw fail("expected the number of cells");
    cell_count = number(0, "cell count");
  }
  const auto k = static_cast<std::size_t>(points.dimension) + 1;
  Cgal_triangulation result;
  result.cells.vertices_per_simplex = static_cast<int>(k);
  for (std::size_t c = 0; c < cell_count; ++c) {
    next("cells");
    if (t.size() != k) throw fail("expected a cell of " + std::to_string(k) + " vertex numbers (a cell base that writes more is not supported)");
    std::array<std::uint32_t, 7> row{};
    bool finite_cell = true;
    for (std::size_t i = 0; i < k; ++i) {
      const std::size_t v = number(i, "vertex number");
      if (v > finite) throw fail("vertex " + std::to_string(v) + " of a cell is not one of the " + std::to_string(finite + 1) + " vertices");
      finite_cell = finite_cell && v != 0;
      row[i] = static_cast<std::uint32_t>(v - (v != 0));
    }
    if (finite_cell) result.cells.indices.insert(result.cells.indices.end(), row.begin(), row.begin() + static_cast<std::ptrdiff_t>(k));
  }
  for (std::size_t c = 0; c < cell_count; ++c) {
    next("neighbours of the cells");
    if (t.size() != k) throw fail("expected the " + std::to_string(k) + " neighbours of a cell");
    for (std::size_t i = 0; i < k; ++i)
      if (number(i, "cell number") >= cell_count) throw fail("neighbour " + std::string(t[i]) + " is not one of the " + std::to_string(cell_count) + " cells");
  }
  while (source.next(line))
    if (!tokens_of(line).empty()) throw fail("more lines after the triangulation's cells and neighbours");
  if (result.cells.size() == 0) throw Parse_error(name + ": the triangulation has no finite cell");
  result.points = std::move(points);
  return result;
}

void write_msh_triangulation(std::ostream& out, const Point_table& points, const Simplex_table& t) {
  const auto d = static_cast<std::size_t>(points.dimension);
  const auto k = static_cast<std::size_t>(t.vertices_per_simplex);
  std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" + std::to_string(points.size()) + "\n";
  const auto flush = [&] {
    if (text.size() > (std::size_t{1} << 16)) out.write(text.data(), static_cast<std::streamsize>(text.size())), text.clear();
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    text += std::to_string(i + 1);
    for (std::size_t j = 0; j < d; ++j) {
      text += ' ';
      detail::append_shortest(text, points.coordinates[i * d + j]);
    }
    text += d == 2 ? " 0\n" : "\n";
    flush();
  }
  // Element types: 2 a triangle, 4 a tetrahedron; two tags (physical 0, elementary 1).
  const char* type = k == 3 ? " 2 2 0 1" : " 4 2 0 1";
  text += "$EndNodes\n$Elements\n" + std::to_string(t.size()) + "\n";
  for (std::size_t s = 0; s < t.size(); ++s) {
    text += std::to_string(s + 1);
    text += type;
    for (std::size_t i = 0; i < k; ++i) text += ' ' + std::to_string(std::uint64_t{t.indices[s * k + i]} + 1);
    text += '\n';
    flush();
  }
  text += "$EndElements\n";
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

}  // namespace dewall::io
