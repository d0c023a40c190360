// Helpers shared by the text readers and writers (points, simplices, VTK): one
// place for how lines are read, how a line is split into tokens and numbers,
// how a double is written back exactly, and how a message names its file, its
// line and a bad token (quoted: escaped and cut).
#pragma once

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <istream>
#include <string>
#include <string_view>

#include "dewall/io/point_reader.hpp"
#include "dewall/io/quote.hpp"

namespace dewall::io::detail {

/// "name:line: ", the prefix of every message about a line of a file.
inline std::string where(const std::string& name, std::size_t line) {
  return name + ":" + std::to_string(line) + ": ";
}

/// `line` up to its first '#' (the rest is a comment).
inline std::string_view without_comment(std::string_view line) {
  return line.substr(0, line.find('#'));
}

/// True when `line` holds nothing but blanks and a comment.
inline bool is_blank(std::string_view line) {
  return without_comment(line).find_first_not_of(" \t\r\v\f") == std::string_view::npos;
}

/// Calls on_token(std::string_view) for each whitespace-separated token of `line`.
template <class OnToken>
void for_each_token(std::string_view line, OnToken&& on_token) {
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i == line.size()) break;
    std::size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    on_token(line.substr(i, j - i));
    i = j;
  }
}

/// True when `token` is a complete decimal number in strtod's syntax.
inline bool is_number(std::string_view token) {
  const std::string s(token);
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size();
}

/// `token` as a complete decimal number (strtod syntax: NaN and infinities
/// included; the triangulator rejects them with the point's index).
/// \throws Parse_error at `name`:`line_no` for anything else or a value out of
/// the range of double (too large, or so small that it would round to 0).
inline double parse_double(std::string_view token_view, const std::string& name, std::size_t line_no) {
  const std::string token(token_view);
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(token.c_str(), &end);
  if (end != token.c_str() + token.size()) throw Parse_error(where(name, line_no) + quoted(token) + " is not a number");
  if (errno == ERANGE && std::isinf(v))
    throw Parse_error(where(name, line_no) + quoted(token) + " is out of the range of double");
  // Too small is out of range too: 1e-400 is not 0 (a subnormal result is a double, and kept).
  if (errno == ERANGE && v == 0)
    throw Parse_error(where(name, line_no) + quoted(token) + " is out of the range of double (it would round to 0)");
  return v;
}

/// Appends the shortest decimal form of `v` that reads back to the same double
/// (std::to_chars guarantees the round trip), so text output loses nothing.
inline void append_shortest(std::string& text, double v) {
  char number[32];
  const auto r = std::to_chars(number, number + sizeof number, v);
  text.append(number, r.ptr);
}

/// The lines of a text stream, numbered from 1. A line ends at "\n", "\r\n" or
/// a lone "\r" (classic Mac OS), so a file with CR line endings is read line by
/// line instead of as one long line.
class Line_source {
 public:
  explicit Line_source(std::istream& in) : in_(in) {}

  /// The next line into `line` (its terminator removed); false at the end of the input.
  bool next(std::string& line) {
    if (!splitting_) {
      if (!std::getline(in_, raw_)) return false;
      bytes_ += raw_.size() + 1;
      if (!raw_.empty() && raw_.back() == '\r') raw_.pop_back();
      ++number_;
      splitting_ = raw_.find('\r') != std::string::npos;
      if (!splitting_) {
        line.swap(raw_);
        return true;
      }
      from_ = 0;
    } else {
      ++number_;
    }
    // Lone '\r's inside what getline read: serve the pieces one by one.
    const auto cr = raw_.find('\r', from_);
    line.assign(raw_, from_, cr == std::string::npos ? std::string::npos : cr - from_);
    if (cr == std::string::npos) splitting_ = false;
    else from_ = cr + 1;
    return true;
  }
  /// The number of the line `next` returned last.
  std::size_t number() const { return number_; }
  /// Bytes consumed so far (for a progress bar).
  std::uint64_t bytes() const { return bytes_; }

  /// After the last row a header announced: the rest of the input may hold
  /// blank and comment lines only. \throws Parse_error naming the first extra
  /// row and what the header announced ("3 points").
  void expect_no_more_rows(const std::string& name, const std::string& announced) {
    std::string line;
    while (next(line))
      if (!is_blank(line))
        throw Parse_error(where(name, number_) + "more rows than the header announces (" + announced + ")");
  }

 private:
  std::istream& in_;
  std::string raw_;        // what getline read last
  bool splitting_ = false;  // raw_ holds lone '\r's and is served piece by piece
  std::size_t from_ = 0;    // the next piece's start
  std::size_t number_ = 0;
  std::uint64_t bytes_ = 0;
};

}  // namespace dewall::io::detail
