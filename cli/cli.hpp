// Shared pieces of the dewall command-line tool: the command table, usage
// errors, argument parsing, and the dimension dispatch from a file's point
// table to the triangulator. One command per cli/command_<name>.cpp file.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "dewall/io/dimensions.hpp"
#include "dewall/io/point_reader.hpp"
#include "dewall/io/simplex_reader.hpp"
#include "dewall/io/simplex_writer.hpp"
#include "dewall/certify/report.hpp"
#include "dewall/error.hpp"
#include "dewall/kernel/dimension.hpp"
#include "dewall/kernel/point_array.hpp"
#include "dewall/options.hpp"

namespace dewall::cli {

/// A usage error: printed with where the help is (main.cpp), exit status 2.
struct Usage_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The value after option argv[i] (advancing i). \throws Usage_error when missing.
std::string next_arg(int& i, int argc, char** argv);
/// A non-negative integer argument; `what` names it in the message ("--dim value"),
/// which must say which option is wrong on its own. \throws Usage_error otherwise.
long parse_long(const std::string& s, const char* what);
/// A point count (generate N, demo --points N): an integer, also in the forms
/// 1e6 or 2.5e5 (large counts are easier to type so) when the value is a
/// whole number, at most 10^12. \throws Usage_error otherwise.
std::size_t parse_point_count(const std::string& s);
/// A seed: an integer from 0 to 2^64 - 1. \throws Usage_error otherwise.
std::uint64_t parse_seed(const std::string& s);
/// --threads N: 1 to 4096. \throws Usage_error otherwise.
int parse_thread_count(const std::string& text);

/// True when argument `a` is an option: it starts with '-' and is neither "-"
/// (standard input or output) nor a negative number ("-1" is an operand, which
/// the command then rejects with a message about its value).
bool is_option(const std::string& a);

/// Walks a command's arguments argv[2 …] and returns its operands: each option
/// goes to `option(argument, i)`, which returns false for an option it does
/// not know (a Usage_error then names it) and may consume a value with
/// next_arg; every other argument, and every argument after "--", is an
/// operand. \throws Usage_error ("unexpected argument") past `max_operands`,
/// and for an option that takes a value given twice (-o and --output are one).
std::vector<std::string> parse_arguments(int argc, char** argv, std::size_t max_operands,
                                         const std::function<bool(const std::string&, int&)>& option);

/// How messages name an input path: "<stdin>" for "-", else the path made
/// printable (io/quote.hpp).
std::string input_name(const std::string& path);

/// Prints "dewall: NAME: MESSAGE" for points that cannot be triangulated, the
/// offending point numbered as in the file (TetGen's may count from 1), and
/// returns the exit status 1.
int report_invalid_input(const std::string& name, const Invalid_input& e, std::size_t first_index);

/// \throws Usage_error when `n` points of `dimension` coordinates would not fit
/// in this machine's memory (before a generator tries to allocate them).
void check_fits_in_memory(std::size_t n, long dimension);

/// A triangulation as the CLI handles it.
struct Run {
  io::Simplex_table simplices;
  Statistics stats;
  double seconds = 0;  // the triangulation alone
};

/// Receives a run's simplices as whole rows of indices, a block at a time.
using Simplex_rows_sink = std::function<void(std::span<const std::uint32_t>)>;

/// Triangulates a point table of any supported dimension with the engine of
/// `options` (default: automatic). The simplices go to Run::simplices, or,
/// when `stream` is given, to it as they are built (options.stream); a
/// streamed run writes no points, so the table's coordinates are then
/// released once converted (10^8 points: 2.4 GB), and so they are when
/// `keep_coordinates` is false (a caller that writes no points either).
/// \throws dewall::Invalid_input (points that cannot be triangulated), Usage_error (dimension).
Run triangulate_any(io::Point_table& table, const Options& options = {}, const Simplex_rows_sink* stream = nullptr,
                    bool keep_coordinates = true);

static_assert(io::min_dimension == kernel::min_dimension && io::max_dimension == kernel::max_dimension,
              "the file formats accept the dimensions the library is compiled for");

/// The range of --dim ("2 to 6") checked; \throws Usage_error otherwise.
inline void check_dim_option(long dim) {
  if (!io::is_supported_dimension(dim))
    throw Usage_error("--dim must be " + io::dimension_range() + ", not " + std::to_string(dim));
}

/// Calls f(std::integral_constant<int, D>{}) for a dimension D = 2 … 6 known at
/// run time. \throws Usage_error for any other dimension.
template <class F>
decltype(auto) with_dimension(int dimension, F&& f) {
  if (dimension < kernel::min_dimension || dimension > kernel::max_dimension)
    throw Usage_error(kernel::unsupported_dimension_message(dimension));
  return kernel::with_dimension(dimension, std::forward<F>(f));
}

/// The points of a table as kernel points. \pre table.dimension == D.
template <int D>
std::vector<kernel::Point_d<D>> kernel_points(const io::Point_table& table) {
  return kernel::points_from_coordinates<D>(table.coordinates);
}

/// Certifies `simplices` against `points` (any supported dimension) with the
/// project's kernel. \throws Usage_error for an unsupported dimension.
certify::Report certify_any(const io::Point_table& points, const io::Simplex_table& simplices,
                            const certify::Options& options);
/// certify() of the rows `simplices` reads (a block at a time).
certify::Report certify_file(const io::Point_table& points, io::Simplex_file_reader& simplices,
                             const certify::Options& options);
/// This machine's physical memory in bytes (0 when unknown).
std::uint64_t physical_memory();

/// Prints the counts, the engine, build_s=SECONDS, which construction built
/// how many simplices, and the paper's Table 1 counters when walls ran.
void print_stats(std::FILE* out, const Run& run);

/// A subcommand: `run` returns the exit status (argv[1] is the command name);
/// `usage` is its paragraph of the help text.
struct Command {
  const char* name;
  int (*run)(int argc, char** argv);
  const char* usage;
};

/// Registers a command; each cli/command_<name>.cpp holds one
///   static const bool registered = dewall::cli::register_command({...});
/// so adding a command touches no shared file.
bool register_command(const Command& c);
/// The registered commands, sorted by name.
const std::vector<Command>& commands();

}  // namespace dewall::cli
