// What the tool says when something is wrong (issue 27): a long file name is
// cut like a token, a message blames the right line and says what is wrong,
// invisible characters are shown escaped, a usage error says where the help
// is instead of printing all of it, help goes where it is asked for and its
// write errors have a reason, and a file size limit is a write error, not a
// silent death by SIGXFSZ. Each case runs the real executable in its own folder.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <sys/sysmacros.h>

#include "dewall/options.hpp"
#include "support/cli_runner.hpp"

namespace {

using dewall::test::Cli_in_directory;
using dewall::test::slurp;
namespace fs = std::filesystem;

const std::string square = "0 0\n1 0\n0 1\n1 1\n";

Cli_in_directory fresh(const std::string& name) {
  fs::remove_all(name);
  Cli_in_directory cli(name);
  cli.write("p.txt", square);
  return cli;
}

std::size_t lines_of(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

TEST_CASE("messages: a long file name is cut, its start and end kept", "[cli][messages]") {
  const auto cli = fresh("messages_test_long_name");
  const std::string name = "start" + std::string(100000, 'n') + "end.txt";
  const auto input = cli("triangulate " + name);
  CHECK(input.status == 2);
  CHECK(input.err.size() < 400);
  CHECK(input.err.find("dewall: startnnn") == 0);
  CHECK(input.err.find("nnnend.txt (100012 bytes): cannot open file: File name too long") != std::string::npos);
  const auto output = cli("triangulate p.txt -o " + name);
  CHECK(output.status == 2);
  CHECK(output.err.size() < 400);
  CHECK(output.err.find("(100012 bytes): cannot open: File name too long") != std::string::npos);
}

TEST_CASE("messages: the right line, and what is wrong with it", "[cli][messages]") {
  const auto cli = fresh("messages_test_lines");
  SECTION("an rbox count line with trailing text") {
    const auto r = cli.with_stdin("triangulate -", "2 rbox 4 D2\n4 points\n0 0\n1 0\n0 1\n1 1\n");
    CHECK(r.status == 2);
    CHECK(r.err == "dewall: <stdin>:2: expected the point count alone on the line after rbox's dimension line, "
                   "found '4 points'\n");
  }
  SECTION("one column of numbers") {
    const auto r = cli.with_stdin("triangulate -", "5\n3\n1\n2\n3\n");
    CHECK(r.status == 2);
    CHECK(r.err.find("<stdin>:3: one value per line: points need 2 to 6 coordinates per line") != std::string::npos);
    CHECK(r.err.find("expected 5 coordinates") == std::string::npos);
  }
  SECTION("a second byte order mark is shown escaped") {
    cli.write("bom2.txt", "\xEF\xBB\xBF\xEF\xBB\xBF" + square);  // the first is skipped, the second is data
    const auto r = cli("triangulate bom2.txt");
    CHECK(r.status == 2);
    CHECK(r.err.find("bom2.txt:1: '\\xef\\xbb\\xbf0' is not a number") != std::string::npos);
    CHECK(r.err.find("\xEF\xBB\xBF") == std::string::npos);
  }
}

TEST_CASE("messages: a usage error says where the help is, help prints what is asked", "[cli][messages]") {
  const auto cli = fresh("messages_test_usage");
  const auto option = cli("triangulate p.txt --bogus");
  CHECK(option.status == 2);
  CHECK(option.out.empty());
  CHECK(option.err == "dewall: unknown option '--bogus'\n"
                      "run 'dewall triangulate --help' for its usage, 'dewall help' for every command\n");
  for (const std::string args : {"frobnicate", "", "help frobnicate"}) {
    CAPTURE(args);
    const auto r = cli(args);
    CHECK(r.status == 2);
    CHECK(lines_of(r.err) == 3);  // the error, the usage line with the commands, the hint
    CHECK(r.err.find("usage: dewall <command> [options], a command being one of certify, demo, draw, generate, "
                     "triangulate\nrun 'dewall help' for the details") != std::string::npos);
  }
  const auto general = cli("help");
  CHECK(general.status == 0);
  CHECK(general.out.find("commands:") != std::string::npos);
  const auto one = cli("help triangulate");
  CHECK(one.status == 0);
  CHECK(one.out.rfind("usage: dewall triangulate INPUT", 0) == 0);
  CHECK(one.out.find("generate KIND") == std::string::npos);
  CHECK(one.out == cli("triangulate --help").out);
}

TEST_CASE("messages: help to a full device says why, and a file size limit is a write error", "[cli][messages]") {
  const auto cli = fresh("messages_test_limits");
  SECTION("help > full") {
    if (::mknod(cli.path("full").c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0) {
      WARN("mknod not permitted: skipped");
      return;
    }
    for (const std::string args : {"help", "help generate", "generate --help"}) {
      CAPTURE(args);
      const auto r = cli.shell("$DEWALL " + args + " > full");
      CHECK(r.status == 2);
      CHECK(r.err == "dewall: <stdout>: write error: No space left on device\n");
    }
  }
  SECTION("ulimit -f: the old file is kept, no temporary is left, the exit status is 2") {
    cli.write("big.txt", "old\n");
    // 8 blocks (4 or 8 KB, by the shell); the points take about 1 MB.
    const auto file = cli.shell("ulimit -f 8 && $DEWALL generate uniform 20000 --seed 1 -q -o big.txt");
    CHECK(file.status == 2);  // not 128 + SIGXFSZ
    CHECK(file.err.find("dewall: big.txt: write error: File too large (a file size limit: ulimit -f)") != std::string::npos);
    CHECK(slurp(cli.path("big.txt")) == "old\n");
    const auto piped = cli.shell("ulimit -f 8 && $DEWALL generate uniform 20000 --seed 1 -q > big2.txt");
    CHECK(piped.status == 2);
    CHECK(piped.err.find("<stdout>: write error: File too large") != std::string::npos);
    for (const auto& entry : fs::directory_iterator(cli.dir))
      CHECK(entry.path().filename().string().find(".tmp.") == std::string::npos);
  }
}

TEST_CASE("messages: header integers are integers, an option is given once, counts read alike", "[cli][messages]") {
  const auto cli = fresh("messages_test_strict");
  SECTION("rbox's count and dimension, a .node header: decimal digits only") {
    const auto count = cli.with_stdin("triangulate -", "2 rbox 4 D2\n4e0\n0 0\n1 0\n0 1\n1 1\n");
    CHECK(count.status == 2);
    CHECK(count.err.find("<stdin>:2: invalid point count '4e0'") != std::string::npos);
    const auto dimension = cli.with_stdin("triangulate -", "0x2\n4\n0 0\n1 0\n0 1\n1 1\n");
    CHECK(dimension.status == 2);
    CHECK(dimension.err.find("<stdin>:1: invalid dimension '0x2'") != std::string::npos);
    cli.write("h.node", "4e0 2 0 0\n0 0 0\n1 1 0\n2 0 1\n3 1 1\n");
    const auto node = cli("triangulate h.node");
    CHECK(node.status == 2);
    CHECK(node.err.find("h.node:1: expected a .node header") != std::string::npos);
  }
  SECTION("an option with a value given twice is a usage error") {
    const auto engine = cli("triangulate p.txt --engine cgal --engine dewall");
    CHECK(engine.status == 2);
    CHECK(engine.out.empty());
    CHECK(engine.err.find("dewall: option --engine given twice ('cgal' and 'dewall')") == 0);
    const auto output = cli("triangulate p.txt -o a.txt --output b.txt");
    CHECK(output.status == 2);
    CHECK(output.err.find("option --output given twice ('a.txt' and 'b.txt')") != std::string::npos);
    CHECK(!fs::exists(cli.path("a.txt")));
    CHECK(!fs::exists(cli.path("b.txt")));
    CHECK(cli("generate uniform 10 --seed 1 --seed 2").status == 2);
    CHECK(cli("triangulate p.txt --stats --stats").status == 0);  // a flag repeated changes nothing
  }
  SECTION("demo reads --points and --seed as generate reads N and --seed") {
    const auto demo = cli("demo --points 1e2 --dim 2 --seed 18446744073709551615");
    CHECK(demo.status == 0);
    CHECK(demo.out.find("dewall demo: 100 uniform points in E^2, seed 18446744073709551615") == 0);
    const auto bad = cli("demo --points 2.5");
    CHECK(bad.status == 2);
    CHECK(bad.err.find("invalid point count '2.5'") != std::string::npos);
  }
}

TEST_CASE("the help and docs/cli.md state the region sizes of the code", "[cli][docs]") {
  // The help prints them from options.hpp; docs/cli.md is written by hand, so
  // it is checked here against the same constants.
  auto n = [](std::size_t v) { return std::to_string(v); };
  const std::vector<std::string> phrases{
      "regions of n/4 points (" + n(dewall::smallest_default_region) + " to " + n(dewall::largest_default_region) + ")",
      "regions of at most " + n(dewall::largest_default_streaming_region) + " points",
      "n/" + n(dewall::streaming_region_share) + " from " +
          n(dewall::streaming_region_share * dewall::largest_default_streaming_region) + " points on, at most " +
          n(dewall::largest_streaming_region_at_scale),
      "may differ above " + n(4 * dewall::largest_default_streaming_region) + " points",
      "inputs of up to " + n(dewall::largest_automatic_whole_input) + " points"};
  std::ifstream in(std::string(DEWALL_SOURCE_DIR) + "/docs/cli.md");
  REQUIRE(in);
  // Both wrap their lines: compare with single spaces.
  const auto flattened = [](const std::string& text) {
    std::string flat;
    for (char c : text) {
      if (c == '\n') c = ' ';
      if (!(c == ' ' && !flat.empty() && flat.back() == ' ')) flat += c;
    }
    return flat;
  };
  const std::string docs = flattened({std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()});
  const auto cli = fresh("messages_test_help_regions");
  const std::string flat = flattened(cli("triangulate --help").out);
  for (const std::string& phrase : phrases) {
    INFO(phrase);
    CHECK(docs.find(phrase) != std::string::npos);
    CHECK(flat.find(phrase) != std::string::npos);
  }
}
