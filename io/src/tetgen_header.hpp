// Recognising TetGen's .node and .ele files by their content, for inputs whose
// name does not say (standard input, a pipe, <(…), any other extension).
#pragma once

#include <string_view>

namespace dewall::io::detail {

enum class Tetgen_file { node, ele };

/// True when `head`, an input's first bytes (the whole input when `whole`),
/// starts as a TetGen file of `kind`: a header of whole numbers, the first
/// the count ("<count> <dimension> [<#attributes> [<markers>]]" for .node,
/// "<count> <vertices per simplex> [<#attributes>]" for .ele), then rows of
/// the width the header implies, numbered consecutively from 0 or 1, as many
/// as the count says (no more in the first bytes; exactly that many when they
/// are the whole input). Plain
/// text of the same numbers would read the header as a point or a simplex:
/// such a file cannot be meant as one (its rows would have consecutive first
/// values and a header of another width or of these exact values).
bool looks_like_tetgen(std::string_view head, bool whole, Tetgen_file kind);

}  // namespace dewall::io::detail
