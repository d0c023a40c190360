// The one way every command opens an input (points for triangulate, certify
// and draw; simplex lists for certify and draw): a file, standard input ("-"),
// a pipe, a FIFO or a process substitution (/dev/fd/N) alike. The input is
// read strictly forward, never seeked: the format is sniffed from a buffered
// prefix that is then read again by the parser, so a pipe loses nothing.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>

namespace dewall::io {

/// An open input. A UTF-8 byte order mark at its start is skipped (editors on
/// Windows write one; no format here starts with it).
class Input_file {
 public:
  /// Opens `path`; "-" is standard input.
  /// \throws Parse_error ("PATH: cannot open file: …") when it cannot be
  /// opened or is a directory.
  explicit Input_file(const std::string& path);
  ~Input_file();
  Input_file(const Input_file&) = delete;
  Input_file& operator=(const Input_file&) = delete;

  /// The stream to parse. A read error throws Parse_error out of the parser
  /// ("PATH: read error: …"); it is never taken for the end of the input.
  std::istream& stream();
  /// The input's first bytes not yet read, up to `n` (≤ 4096; fewer when the
  /// input is shorter), without consuming them.
  std::string_view prefix(std::size_t n);
  /// The name for messages: "<stdin>", or the path made printable (quote.hpp).
  const std::string& name() const;
  /// The size in bytes of a regular file, 0 when unknown (pipes, devices).
  std::uint64_t size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dewall::io
