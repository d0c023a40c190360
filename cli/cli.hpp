// Shared pieces of the dewall command-line tool: the command table, usage
// errors, argument parsing, and the dimension dispatch from a file's point
// table to the triangulator. One command per cli/command_<name>.cpp file.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>

#include "dewall/io/point_reader.hpp"
#include "dewall/io/simplex_writer.hpp"
#include "dewall/options.hpp"

namespace dewall::cli {

/// A usage error: printed with the usage text, exit status 2.
struct Usage_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The value after option argv[i] (advancing i). \throws Usage_error when missing.
std::string next_arg(int& i, int argc, char** argv);
/// A non-negative integer argument. \throws Usage_error otherwise.
long parse_long(const std::string& s, const char* what);

/// A triangulation as the CLI handles it.
struct Run {
  io::Simplex_table simplices;
  Statistics stats;
  double seconds = 0;  // the triangulation alone
};

/// Triangulates a point table of any supported dimension.
/// \throws dewall::Invalid_input (points that cannot be triangulated), Usage_error (dimension).
Run triangulate_any(const io::Point_table& table);

/// Prints the paper's Table 1 counters and build_s=SECONDS.
void print_stats(std::FILE* out, const Run& run);

/// The commands: each returns the exit status; argv[1] is the command name.
int command_triangulate(int argc, char** argv);
int command_demo(int argc, char** argv);

}  // namespace dewall::cli
