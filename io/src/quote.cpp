#include "dewall/io/quote.hpp"

#include <cstdint>
#include <cstdio>

namespace dewall::io {
namespace {

/// One character of `s` starting at byte i: its code point and its length in
/// bytes, or code point -1 and length 1 for a byte that does not start a valid
/// UTF-8 sequence (overlong forms, surrogates and values above U+10FFFF included).
struct Character {
  std::int32_t code;
  std::size_t length;
};

Character decode(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return {b0, 1};
  const std::size_t length = b0 >= 0xc2 && b0 <= 0xdf ? 2 : b0 >= 0xe0 && b0 <= 0xef ? 3 : b0 >= 0xf0 && b0 <= 0xf4 ? 4 : 0;
  if (length == 0 || i + length > s.size()) return {-1, 1};
  std::int32_t code = b0 & (0x7f >> length);
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return {-1, 1};
    code = (code << 6) | (byte(i + k) & 0x3f);
  }
  const std::int32_t smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (code < smallest[length] || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) return {-1, 1};
  return {code, length};
}

/// Characters a terminal may obey instead of printing: C0, DEL, C1, and the
/// bidirectional embeddings and isolates that reorder what follows them; and
/// characters that print as nothing, so that a message would show a token
/// as another one: the byte order mark U+FEFF (a second one in a file is data),
/// zero-width spaces and joiners, the directional marks, the line and
/// paragraph separators and the invisible operators.
bool is_control(std::int32_t code) {
  return code < 0x20 || (code >= 0x7f && code <= 0x9f) || (code >= 0x202a && code <= 0x202e) ||
         (code >= 0x2066 && code <= 0x2069) || code == 0xfeff || code == 0x061c || (code >= 0x200b && code <= 0x200f) ||
         code == 0x2028 || code == 0x2029 || (code >= 0x2060 && code <= 0x2064);
}

std::string hex_escape(std::string_view bytes, const char* form) {
  std::string out;
  char buffer[8];
  for (char c : bytes) {
    std::snprintf(buffer, sizeof buffer, form, static_cast<unsigned>(static_cast<unsigned char>(c)));
    out += buffer;
  }
  return out;
}

}  // namespace

std::string printable(std::string_view s, std::size_t max_bytes) {
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    const auto [code, length] = decode(s, i);
    const std::string_view bytes = s.substr(i, length);
    std::string piece;
    if (code == '\\') piece = "\\\\";
    else if (code == '\t') piece = "\\t";
    else if (code == '\n') piece = "\\n";
    else if (code == '\r') piece = "\\r";
    else if (code < 0 || is_control(code)) piece = hex_escape(bytes, "\\x%02x");
    else piece = bytes;
    if (out.size() + piece.size() > max_bytes) {
      out += "… (";
      out += std::to_string(s.size());
      out += " bytes)";
      return out;
    }
    out += piece;
    i += length;
  }
  return out;
}

std::string file_name(std::string_view path) {
  constexpr std::size_t longest = 200, kept = 96;
  std::string whole = printable(path, longest);
  if (whole.size() <= longest) return whole;
  // The start says where, the end which file: keep both, each cut at a
  // character boundary (never inside a UTF-8 sequence or an escape).
  std::string head = printable(path, kept);
  head.resize(head.rfind("… ("));
  const auto next_character = [&](std::size_t i) {
    do ++i;
    while (i < path.size() && (static_cast<unsigned char>(path[i]) & 0xc0) == 0x80);
    return i;
  };
  // (A short path may exceed the limit through its escapes alone: \xNN per byte.)
  std::size_t from = path.size() > kept ? next_character(path.size() - kept - 1) : 0;
  std::string tail = printable(path.substr(from));
  while (tail.size() > kept) tail = printable(path.substr(from = next_character(from)));  // escapes lengthened it
  return head + "…" + tail + " (" + std::to_string(path.size()) + " bytes)";
}

std::string quoted(std::string_view s) {
  std::string out(1, '\'');
  out += printable(s, 60);
  out += '\'';
  return out;
}

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (std::size_t i = 0; i < s.size();) {
    const auto [code, length] = decode(s, i);
    if (code < 0) out += hex_escape(s.substr(i, 1), "\\\\x%02x");
    else if (code == '"' || code == '\\') out += '\\', out += static_cast<char>(code);
    else if (code < 0x20) out += hex_escape(s.substr(i, 1), "\\u%04x");
    else out += s.substr(i, length);
    i += length;
  }
  return out + "\"";
}

}  // namespace dewall::io
