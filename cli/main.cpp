// dewall: the command-line front end. Each command lives in cli/command_<name>.cpp.
// Exit status: 0 on success, 1 when the input is valid but the answer is "no"
// (points that cannot be triangulated, a triangulation that fails certification),
// 2 for usage errors and unreadable input.
#include <cstdio>
#include <cstring>
#include <string>

#include "cli.hpp"

namespace {

constexpr const char* usage =
    "usage: dewall <command> [options]\n"
    "\n"
    "commands:\n"
    "  triangulate INPUT [-o OUTPUT] [--stats]\n"
    "      Delaunay triangulation of the points in INPUT ('-' = standard input):\n"
    "      plain text (one point per line, '#' comments), rbox output, or TetGen .node.\n"
    "      Writes one simplex per line (zero-based input indices) to OUTPUT\n"
    "      (default: standard output); TetGen .ele when OUTPUT ends in .ele.\n"
    "      --stats prints the paper's Table 1 counters and build_s=SECONDS on stderr.\n"
    "  demo [--points N] [--dim D] [--seed S]\n"
    "      Generates N uniform random points in the unit cube of E^D (default\n"
    "      100000 points, D = 3), triangulates them and prints a summary.\n"
    "  help\n";

struct Command {
  const char* name;
  int (*run)(int, char**);
};

constexpr Command commands[] = {
    {"triangulate", dewall::cli::command_triangulate},
    {"demo", dewall::cli::command_demo},
};

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string command = argc > 1 ? argv[1] : "help";
    if (command == "help" || command == "-h" || command == "--help") {
      std::fputs(usage, stdout);
      return 0;
    }
    for (int i = 2; i < argc; ++i)
      if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help")) {
        std::fputs(usage, stdout);
        return 0;
      }
    for (const Command& c : commands)
      if (command == c.name) return c.run(argc, argv);
    throw dewall::cli::Usage_error("unknown command '" + command + "'");
  } catch (const dewall::cli::Usage_error& e) {
    std::fprintf(stderr, "dewall: %s\n\n%s", e.what(), usage);
    return 2;
  } catch (const dewall::io::Parse_error& e) {
    std::fprintf(stderr, "dewall: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dewall: %s\n", e.what());
    return 2;
  }
}
