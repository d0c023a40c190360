// dewall: the command-line front end. Each command lives in cli/command_<name>.cpp.
// Exit status: 0 on success, 1 when the input is valid but the answer is "no"
// (points that cannot be triangulated, a triangulation that fails certification),
// 2 for usage errors and unreadable input.
#include <cstdio>
#include <cstring>
#include <string>

#include "cli.hpp"

namespace {

void print_usage(std::FILE* out) {
  std::fputs("usage: dewall <command> [options]   (dewall help: this text)\n\ncommands:\n", out);
  for (const auto& c : dewall::cli::commands()) std::fputs(c.usage, out);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string command = argc > 1 ? argv[1] : "help";
    if (command == "help" || command == "-h" || command == "--help") {
      print_usage(stdout);
      return 0;
    }
    for (const auto& c : dewall::cli::commands()) {
      if (command != c.name) continue;
      for (int i = 2; i < argc; ++i)
        if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help")) {
          std::printf("usage: dewall %s", c.usage + 2);
          return 0;
        }
      return c.run(argc, argv);
    }
    throw dewall::cli::Usage_error("unknown command '" + command + "'");
  } catch (const dewall::cli::Usage_error& e) {
    std::fprintf(stderr, "dewall: %s\n\n", e.what());
    print_usage(stderr);
    return 2;
  } catch (const dewall::io::Parse_error& e) {
    std::fprintf(stderr, "dewall: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dewall: %s\n", e.what());
    return 2;
  }
}
