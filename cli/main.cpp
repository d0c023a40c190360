// dewall: the command-line front end. Each command lives in cli/command_<name>.cpp.
// Exit status: 0 on success, 1 when the input is valid but the answer is "no"
// (points that cannot be triangulated, a triangulation that fails certification),
// 2 for usage errors, unreadable input and output that could not be written.
#include <algorithm>
#include <cstdio>
#include <new>
#include <string>

#include "cli.hpp"
#include "dewall/io/huge_pages.hpp"
#include "dewall/io/output_file.hpp"
#include "dewall/io/quote.hpp"

namespace {

void print_usage(std::FILE* out) {
  std::fputs("usage: dewall <command> [options]   (dewall help: this text)\n\ncommands:\n", out);
  for (const auto& c : dewall::cli::commands()) std::fputs(c.usage, out);
}

/// True when the command's arguments ask for its help (before any "--").
bool asks_for_help(int argc, char** argv) {
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--") return false;
    if (a == "-h" || a == "--help") return true;
  }
  return false;
}

/// Runs the command named by argv[1]; what it printed on standard output is
/// checked to have been written (a full disk is an error, not a silent loss).
int run(int argc, char** argv) {
  if (argc < 2) throw dewall::cli::Usage_error("no command given");
  const std::string command = argv[1];
  int status = 0;
  if (command == "help" || command == "-h" || command == "--help") {
    print_usage(stdout);
  } else {
    const auto& all = dewall::cli::commands();
    const auto c = std::find_if(all.begin(), all.end(), [&](const auto& candidate) { return command == candidate.name; });
    if (c == all.end()) throw dewall::cli::Usage_error("unknown command " + dewall::io::quoted(command));
    if (asks_for_help(argc, argv)) std::printf("usage: dewall %s", c->usage + 2);
    else status = c->run(argc, argv);
  }
  dewall::io::finish_standard_output();
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  dewall::io::restart_with_huge_pages(argv);
  try {
    return run(argc, argv);
  } catch (const dewall::cli::Usage_error& e) {
    std::fprintf(stderr, "dewall: %s\n\n", e.what());
    print_usage(stderr);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "dewall: out of memory\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dewall: %s\n", e.what());
  }
  return 2;
}
