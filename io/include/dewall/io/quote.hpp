// Bytes from outside (file names, tokens of an input file, command-line
// arguments) as they may appear in a message or a JSON report. This is the one
// place where untrusted text is made safe to print: a file may hold escape
// sequences that would reprogram the reader's terminal, a NUL that would cut
// the message short in C's printf, invalid UTF-8, or a megabyte-long token.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace dewall::io {

/// `s` with every byte that is not printable text escaped: the C0 controls
/// and DEL as \t, \n, \r or \xNN, the C1 controls (U+0080 … U+009F, which some
/// terminals obey), the bidirectional overrides (U+202A … U+202E, U+2066 …
/// U+2069), the characters that print as nothing (U+FEFF, U+200B … U+200F,
/// U+2028, U+2029, U+2060 … U+2064, U+061C) and bytes that are not valid
/// UTF-8 as \xNN per byte, and the backslash as \\. Valid UTF-8 text
/// (accents, CJK) is kept as it is. When the
/// escaped text would exceed `max_bytes`, it is cut at a character boundary and
/// "… (N bytes)" says how long `s` was. Complexity: O(|s|).
std::string printable(std::string_view s, std::size_t max_bytes = std::string::npos);

/// How a message names a file: printable(path), and for a path whose escaped
/// form exceeds 200 bytes its first and last 96 or so bytes around "…" and
/// " (N bytes)" (the start says where, the end which file). O(|path|).
std::string file_name(std::string_view path);

/// printable(s, 60) between single quotes: how an input token or an argument is
/// named in a message ("'1e3x' is not a number").
std::string quoted(std::string_view s);

/// `s` as a JSON string literal, quotes included: valid UTF-8 is kept, `"` and
/// `\` and the controls below U+0020 are escaped (\uXXXX), and each byte that
/// is not valid UTF-8 becomes the six characters \\xNN (a literal backslash,
/// 'x' and two hex digits), so the report is always valid UTF-8 JSON. O(|s|).
std::string json_string(std::string_view s);

}  // namespace dewall::io
