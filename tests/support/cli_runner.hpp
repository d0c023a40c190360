// Running the dewall command-line tool from a test: the one runner of the
// CLI tests (tests/dewall/test_*.cpp). DEWALL_CLI_PATH is set by CMake.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>

namespace dewall::test {

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Cli_result {
  int status;  // the exit status
  std::string out, err;
};

/// Runs `dewall ARGS` inside its own directory (ctest runs test cases in
/// parallel), relative paths in ARGS meaning files there, with standard
/// error not a terminal (so no progress line).
struct Cli_in_directory {
  std::string dir;
  explicit Cli_in_directory(std::string d) : dir(std::move(d)) { std::filesystem::create_directories(dir); }
  std::string path(const std::string& name) const { return dir + "/" + name; }
  void write(const std::string& name, const std::string& text) const { std::ofstream(path(name)) << text; }

  /// `before` is a shell prefix, e.g. "cat FILE | "; without one standard input is empty.
  Cli_result operator()(const std::string& args, const std::string& before = "") const {
    return run("cd " + dir + " && " + before + std::string(DEWALL_CLI_PATH) + " " + args + " > out.txt 2> err.txt" +
               (before.empty() ? " < /dev/null" : ""));
  }
  /// With `text` as standard input (a regular file, so seekable).
  Cli_result with_stdin(const std::string& args, const std::string& text) const {
    write("stdin.txt", text);
    return (*this)(args, "< stdin.txt ");
  }
  /// Runs the shell `script` (its own redirections allowed) in the directory,
  /// with $DEWALL naming the executable; what it leaves on standard output and
  /// error is captured. The status is the script's.
  Cli_result shell(const std::string& script) const {
    write("script.sh", script + "\n");
    return run("cd " + dir + " && DEWALL=" + std::string(DEWALL_CLI_PATH) + " sh script.sh > out.txt 2> err.txt < /dev/null");
  }

 private:
  Cli_result run(const std::string& command) const {
    const int raw = std::system(command.c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(path("out.txt")), slurp(path("err.txt"))};
  }
};

}  // namespace dewall::test
