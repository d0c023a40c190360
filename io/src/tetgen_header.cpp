#include "tetgen_header.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "text_lines.hpp"

namespace dewall::io::detail {
namespace {

/// A whole number in decimal digits (as TetGen writes counts and indices), or -1.
std::int64_t whole_number(std::string_view token) {
  if (token.empty() || token.size() > 15 || !std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return -1;
  std::int64_t v = 0;
  for (char c : token) v = v * 10 + (c - '0');
  return v;
}

std::vector<std::string_view> tokens_of(std::string_view line) {
  std::vector<std::string_view> tokens;
  for_each_token(without_comment(line), [&](std::string_view t) { tokens.push_back(t); });
  return tokens;
}

}  // namespace

bool looks_like_tetgen(std::string_view head, bool whole, Tetgen_file kind) {
  // The complete lines of `head`, data lines only.
  std::vector<std::vector<std::string_view>> rows;
  std::size_t start = 0;
  while (start < head.size()) {
    const std::size_t end = head.find_first_of("\r\n", start);
    if (end == std::string_view::npos && !whole) break;  // a line cut by the prefix's end
    const std::string_view line = head.substr(start, end == std::string_view::npos ? head.size() - start : end - start);
    if (!is_blank(line)) rows.push_back(tokens_of(line));
    start = end == std::string_view::npos ? head.size() : end + 1;
  }
  if (rows.size() < 2) return false;
  const auto& header = rows.front();
  const std::size_t most = kind == Tetgen_file::node ? 4 : 3;
  if (header.size() < 2 || header.size() > most) return false;
  std::vector<std::int64_t> h;
  for (auto t : header) h.push_back(whole_number(t));
  if (std::any_of(h.begin(), h.end(), [](std::int64_t v) { return v < 0; }) || h[0] < 1) return false;
  const std::int64_t vertices = h[1];  // coordinates of a point, or vertices of a simplex
  if (kind == Tetgen_file::node ? (vertices < 2 || vertices > 6) : (vertices < 3 || vertices > 7)) return false;
  // The rows must be the header's count: more than it (or, when the whole
  // input is here, fewer) and the file is not what the header says.
  const auto data_rows = static_cast<std::int64_t>(rows.size()) - 1;
  if (data_rows > h[0] || (whole && data_rows != h[0])) return false;
  std::int64_t width = 1 + vertices;
  for (std::size_t i = 2; i < h.size(); ++i) width += h[i];
  if (width > 64) return false;
  std::int64_t first = -1;
  for (std::size_t r = 1; r < rows.size() && static_cast<std::int64_t>(r) <= h[0]; ++r) {
    const auto& row = rows[r];
    if (static_cast<std::int64_t>(row.size()) != width) return false;
    const std::int64_t index = whole_number(row[0]);
    if (r == 1) {
      if (index != 0 && index != 1) return false;
      first = index;
    } else if (index != first + static_cast<std::int64_t>(r) - 1) {
      return false;
    }
    for (std::int64_t i = 1; i <= vertices; ++i) {
      const auto value = row[static_cast<std::size_t>(i)];
      if (kind == Tetgen_file::node ? !is_number(value) : whole_number(value) < 0) return false;
    }
  }
  return true;
}

}  // namespace dewall::io::detail
