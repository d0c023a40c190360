// Helpers shared by the text readers (points, simplices, VTK): one place for
// how a line is split into tokens and how a message names its file and line.
#pragma once

#include <cctype>
#include <cstddef>
#include <string>
#include <string_view>

namespace dewall::io::detail {

/// "name:line: ", the prefix of every message about a line of a file.
inline std::string where(const std::string& name, std::size_t line) {
  return name + ":" + std::to_string(line) + ": ";
}

/// `line` up to its first '#' (the rest is a comment).
inline std::string_view without_comment(std::string_view line) {
  return line.substr(0, line.find('#'));
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

}  // namespace dewall::io::detail
