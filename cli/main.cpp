// dewall: the command-line front end. Each command lives in cli/command_<name>.cpp.
// Exit status: 0 on success, 1 when the input is valid but the answer is "no"
// (points that cannot be triangulated, a triangulation that fails certification),
// 2 for usage errors, unreadable input and output that could not be written.
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "cli.hpp"
#include "dewall/io/output_file.hpp"
#include "dewall/io/quote.hpp"

namespace {

using dewall::cli::Command;

/// The general help: the usage line and every command's paragraph.
std::string general_help() {
  std::string text = "usage: dewall <command> [options]   (dewall help: this text)\n\ncommands:\n";
  for (const auto& c : dewall::cli::commands()) text += c.usage;
  return text;
}

/// One command's help: its paragraph, as a usage line.
std::string command_help(const Command& c) { return std::string("usage: dewall ") + (c.usage + 2); }

/// The registered command named `name`, or null.
const Command* find_command(const std::string& name) {
  const auto& all = dewall::cli::commands();
  const auto c = std::find_if(all.begin(), all.end(), [&](const auto& candidate) { return name == candidate.name; });
  return c == all.end() ? nullptr : &*c;
}

/// Writes `text` to standard output now, so that a failure is reported with
/// its reason (a full device), which a later fflush no longer knows once
/// stdio's buffer has overflowed into a failed write.
/// \throws dewall::io::Write_error
void print(const std::string& text) {
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), stdout) == text.size() && std::fflush(stdout) == 0) return;
  const int error = errno;
  std::clearerr(stdout);
  throw dewall::io::Write_error(std::string("<stdout>: write error") + (error ? std::string(": ") + std::strerror(error) : ""));
}

/// What a usage error adds to its message: where the help is, not the help.
std::string usage_hint(int argc, char** argv) {
  if (argc >= 2 && find_command(argv[1]))
    return std::string("run 'dewall ") + argv[1] + " --help' for its usage, 'dewall help' for every command\n";
  std::string names;
  for (const auto& c : dewall::cli::commands()) names += std::string(names.empty() ? "" : ", ") + c.name;
  return "usage: dewall <command> [options], a command being one of " + names +
         "\nrun 'dewall help' for the details, 'dewall COMMAND --help' for one command\n";
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
    // dewall help [COMMAND]
    if (argc > 3) throw dewall::cli::Usage_error("unexpected argument " + dewall::io::quoted(argv[3]));
    if (argc == 3) {
      const Command* c = find_command(argv[2]);
      if (!c) throw dewall::cli::Usage_error("unknown command " + dewall::io::quoted(argv[2]));
      print(command_help(*c));
    } else {
      print(general_help());
    }
  } else {
    const Command* c = find_command(command);
    if (!c) throw dewall::cli::Usage_error("unknown command " + dewall::io::quoted(command));
    if (asks_for_help(argc, argv)) print(command_help(*c));
    else status = c->run(argc, argv);
  }
  dewall::io::finish_standard_output();
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  // Past a file size limit (ulimit -f) a write fails with EFBIG, reported
  // like any write error (the old output kept), instead of SIGXFSZ killing
  // the process without a word and leaving the temporary behind.
  std::signal(SIGXFSZ, SIG_IGN);
  // GNU's --name=VALUE is --name VALUE (before "--", which ends the options):
  // split here once, so that no command parses two forms.
  std::vector<std::string> words;
  bool options_ended = false;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    const auto equals = a.find('=');
    options_ended = options_ended || a == "--";
    if (i >= 2 && !options_ended && a.rfind("--", 0) == 0 && equals != std::string::npos && equals > 2) {
      words.push_back(a.substr(0, equals));
      words.push_back(a.substr(equals + 1));
    } else {
      words.push_back(a);
    }
  }
  std::vector<char*> args;
  for (auto& w : words) args.push_back(w.data());
  args.push_back(nullptr);
  argc = static_cast<int>(words.size());
  argv = args.data();
  try {
    return run(argc, argv);
  } catch (const dewall::cli::Usage_error& e) {
    std::fprintf(stderr, "dewall: %s\n%s", e.what(), usage_hint(argc, argv).c_str());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "dewall: out of memory\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dewall: %s\n", e.what());
  }
  return 2;
}
