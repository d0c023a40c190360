// Reading and writing files safely (issue 11): every kind of output target
// (regular file, symbolic link, hard link, character device, FIFO, socket,
// /proc/self/fd), signals during writing, inputs that cannot seek, write
// errors on standard output, hostile tokens in messages, and the messages
// that used to state the wrong problem. Each case runs the real executable in
// its own temporary folder; device nodes are made there with mknod (a copy of
// null, 1:3, and of full, 1:7), never a system path, and skipped where mknod
// is not permitted.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include "dewall/io/quote.hpp"
#include "support/cli_runner.hpp"

namespace {

using dewall::test::Cli_in_directory;
using dewall::test::slurp;
namespace fs = std::filesystem;

const std::string square = "0 0\n1 0\n0 1\n1 1\n";
// The default engine leaves a problem this small to dewall's own incremental
// construction: its cell order. The set is CGAL's ({0, 1, 2}, {1, 2, 3}: the
// perturbation's diagonal of the cocircular square); the order may change
// with the engine.
const std::string square_simplices = "2 1 3\n2 0 1\n";

/// A fresh folder for one test case, with the unit square in p.txt.
Cli_in_directory fresh(const std::string& name) {
  fs::remove_all(name);
  Cli_in_directory cli(name);
  cli.write("p.txt", square);
  return cli;
}

/// Makes a character device node `name` in the test's folder; false where not permitted.
bool make_device(const Cli_in_directory& cli, const std::string& name, unsigned major_number, unsigned minor_number) {
  return ::mknod(cli.path(name).c_str(), S_IFCHR | 0666, makedev(major_number, minor_number)) == 0;
}

mode_t mode_of(const std::string& path) {
  struct stat st {};
  REQUIRE(::lstat(path.c_str(), &st) == 0);
  return st.st_mode;
}

/// The names in a folder other than those listed.
std::vector<std::string> others(const std::string& dir, const std::vector<std::string>& known) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const auto name = entry.path().filename().string();
    if (std::find(known.begin(), known.end(), name) == known.end()) names.push_back(name);
  }
  return names;
}

/// Strict UTF-8 (no overlong forms, surrogates or values past U+10FFFF).
bool valid_utf8(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto b = static_cast<unsigned char>(s[i]);
    const std::size_t n = b < 0x80 ? 1 : b >= 0xc2 && b <= 0xdf ? 2 : b >= 0xe0 && b <= 0xef ? 3 : b >= 0xf0 && b <= 0xf4 ? 4 : 0;
    if (n == 0 || i + n > s.size()) return false;
    std::uint32_t code = b & (0xff >> (n + 1));
    for (std::size_t k = 1; k < n; ++k) {
      if ((static_cast<unsigned char>(s[i + k]) & 0xc0) != 0x80) return false;
      code = (code << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3f);
    }
    if ((n == 3 && (code < 0x800 || (code >= 0xd800 && code <= 0xdfff))) || (n == 4 && (code < 0x10000 || code > 0x10ffff)))
      return false;
    i += n;
  }
  return true;
}

}  // namespace

TEST_CASE("files: a symlink planted at the old predictable temporary name is never followed", "[cli][files]") {
  const auto cli = fresh("files_test_planted");
  cli.write("victim", "precious\n");
  // exec keeps the shell's PID, so $$ is the PID the old code put in OUT.tmp.PID.
  const auto r = cli.shell("ln -s victim res.txt.tmp.$$ && exec $DEWALL triangulate p.txt -o res.txt");
  CHECK(r.status == 0);
  CHECK(slurp(cli.path("victim")) == "precious\n");
  CHECK(slurp(cli.path("res.txt")) == square_simplices);
  // The temporary was renamed into place: only the planted link is left over.
  CHECK(others(cli.dir, {"p.txt", "victim", "res.txt", "script.sh", "out.txt", "err.txt"}).size() == 1);
}

TEST_CASE("files: devices, FIFOs, sockets and /proc/self/fd are written in place", "[cli][files]") {
  const auto cli = fresh("files_test_direct");
  SECTION("a character device stays a device") {
    if (!make_device(cli, "null", 1, 3)) {
      WARN("mknod not permitted: skipped");
      return;
    }
    CHECK(cli("triangulate p.txt -o null").status == 0);
    CHECK(cli("generate uniform 10 --dim 2 -o null").status == 0);
    CHECK(cli("draw p.txt --walls -o null").status == 0);
    CHECK(S_ISCHR(mode_of(cli.path("null"))));
    CHECK(others(cli.dir, {"p.txt", "null", "out.txt", "err.txt"}).empty());
  }
  SECTION("a FIFO's reader gets the output") {
    const auto r = cli.shell("mkfifo fifo; cat fifo > got.txt & $DEWALL triangulate p.txt -o fifo; s=$?; wait; exit $s");
    CHECK(r.status == 0);
    CHECK(S_ISFIFO(mode_of(cli.path("fifo"))));
    CHECK(slurp(cli.path("got.txt")) == square_simplices);
  }
  SECTION("a socket is connected to") {
    const int listener = ::socket(AF_UNIX, SOCK_STREAM, 0);
    REQUIRE(listener >= 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const auto socket_path = fs::absolute(cli.path("sock")).string();
    REQUIRE(socket_path.size() < sizeof address.sun_path);
    std::strcpy(address.sun_path, socket_path.c_str());
    REQUIRE(::bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0);
    REQUIRE(::listen(listener, 1) == 0);
    std::string received;
    std::thread reader([&] {
      pollfd ready{listener, POLLIN, 0};
      if (::poll(&ready, 1, 20000) != 1) return;  // never hang the tests
      const int connection = ::accept(listener, nullptr, nullptr);
      char buffer[4096];
      for (ssize_t n; connection >= 0 && (n = ::read(connection, buffer, sizeof buffer)) > 0;)
        received.append(buffer, static_cast<std::size_t>(n));
      if (connection >= 0) ::close(connection);
    });
    CHECK(cli("triangulate p.txt -o sock").status == 0);
    reader.join();
    ::close(listener);
    CHECK(received == square_simplices);
    CHECK(S_ISSOCK(mode_of(cli.path("sock"))));
  }
  SECTION("/proc/self/fd/1 is the command's standard output, whatever it is") {
    const auto r = cli("triangulate p.txt -o /proc/self/fd/1");
    CHECK(r.status == 0);
    CHECK(r.out == square_simplices);
    const auto piped = cli.shell("$DEWALL triangulate p.txt -o /proc/self/fd/1 | cat > piped.txt");
    CHECK(piped.status == 0);
    CHECK(slurp(cli.path("piped.txt")) == square_simplices);
  }
}

TEST_CASE("files: a symlink is written through, a dangling one creates its target", "[cli][files]") {
  const auto cli = fresh("files_test_symlink");
  fs::create_directory(cli.path("sub"));
  cli.write("sub/target.txt", "old\n");
  fs::create_symlink("sub/target.txt", cli.path("link.txt"));
  fs::create_symlink("link.txt", cli.path("link2.txt"));  // a chain of two
  CHECK(cli("triangulate p.txt -o link2.txt").status == 0);
  CHECK(fs::is_symlink(cli.path("link.txt")));
  CHECK(fs::is_symlink(cli.path("link2.txt")));
  CHECK(slurp(cli.path("sub/target.txt")) == square_simplices);
  CHECK(others(cli.dir + "/sub", {"target.txt"}).empty());  // the temporary went there and is gone

  fs::create_symlink("created.txt", cli.path("dangling.txt"));
  CHECK(cli("triangulate p.txt -o dangling.txt").status == 0);
  CHECK(fs::is_symlink(cli.path("dangling.txt")));
  CHECK(slurp(cli.path("created.txt")) == square_simplices);
}

TEST_CASE("files: a regular file keeps its mode, a hard link keeps the old contents", "[cli][files]") {
  const auto cli = fresh("files_test_mode");
  cli.write("secret.txt", "old\n");
  REQUIRE(::chmod(cli.path("secret.txt").c_str(), 0600) == 0);
  fs::create_hard_link(cli.path("secret.txt"), cli.path("hard.txt"));
  CHECK(cli("triangulate p.txt -o secret.txt").status == 0);
  CHECK((mode_of(cli.path("secret.txt")) & 07777) == 0600);
  CHECK(slurp(cli.path("secret.txt")) == square_simplices);
  // Documented: the name now points to a new file; the other link keeps the old one.
  CHECK(slurp(cli.path("hard.txt")) == "old\n");
  CHECK((mode_of(cli.path("hard.txt")) & 07777) == 0600);
  // A new file gets the umask's mode, not mkstemp's 0600.
  const auto r = cli.shell("umask 022 && $DEWALL generate uniform 10 --dim 2 -o new.txt");
  CHECK(r.status == 0);
  CHECK((mode_of(cli.path("new.txt")) & 07777) == 0644);
}

namespace {

/// Starts `dewall args…` in `dir` with default signal dispositions (and no
/// core dump), waits for its temporary (a name starting with ".OUTPUT.tmp.")
/// to receive data (the empty one of the check before the work does not
/// count), sends `signal_number`, and returns the wait status (or -1 when the
/// temporary never appeared).
int interrupt_while_writing(const std::string& dir, const std::string& output, std::vector<std::string> args,
                            int signal_number) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    for (int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1}) ::signal(s, SIG_DFL);
    const rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);
    if (::chdir(dir.c_str()) != 0) ::_exit(127);
    std::vector<char*> argv{const_cast<char*>(DEWALL_CLI_PATH)};
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(DEWALL_CLI_PATH, argv.data());
    ::_exit(127);
  }
  bool seen = false;
  for (int tries = 0; tries < 30000 && !seen; ++tries) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      std::error_code gone;  // (the temporary may vanish between the listing and its size)
      seen = seen || (entry.path().filename().string().rfind("." + output + ".tmp.", 0) == 0 &&
                      fs::file_size(entry.path(), gone) > 0 && !gone);
    }
    if (!seen) std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  ::kill(pid, signal_number);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return seen ? status : -1;
}

}  // namespace

TEST_CASE("files: SIGINT, SIGTERM, SIGHUP, SIGQUIT and SIGUSR1 during writing leave nothing behind", "[cli][files][signals]") {
  const auto cli = fresh("files_test_signals");
  const std::string dir = cli.dir;
  // Outputs of about 100 to 200 MB: writing and fsync take long enough to be interrupted.
  const struct {
    int signal_number;
    std::string output, points;
  } cases[] = {{SIGINT, "big.txt", "2e6"}, {SIGTERM, "big.vtk", "4e6"}, {SIGHUP, "big.txt", "2e6"},
               {SIGQUIT, "big.txt", "1e6"}, {SIGUSR1, "big.txt", "1e6"}};  // (SIGQUIT, SIGUSR1: issue 27)
  for (const auto& c : cases) {
    CAPTURE(c.signal_number, c.output);
    const int status = interrupt_while_writing(
        dir, c.output, {"generate", "uniform", c.points, "--dim", c.output == "big.vtk" ? "3" : "6", "--seed", "1", "-q", "-o", c.output},
        c.signal_number);
    REQUIRE(status != -1);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == c.signal_number);
    CHECK(others(dir, {"p.txt"}).empty());
  }
}

TEST_CASE("files: inputs that cannot seek (pipes, FIFOs, /dev/stdin) are read in full", "[cli][files]") {
  const auto cli = fresh("files_test_pipes");
  REQUIRE(cli("generate bubbles 3000 --dim 2 --seed 4 -o q.txt").status == 0);  // about 120 KB: many pipe buffers
  REQUIRE(cli("generate bubbles 3000 --dim 2 --seed 4 -o q.dwpt").status == 0);
  REQUIRE(cli("generate bubbles 3000 --dim 2 --seed 4 -o q.vtk").status == 0);
  const auto expected = cli("triangulate q.txt");
  REQUIRE(expected.status == 0);
  cli.write("s.txt", expected.out);
  for (const std::string input : {"q.txt", "q.dwpt", "q.vtk"}) {
    CAPTURE(input);
    const auto piped = cli.shell("cat " + input + " | $DEWALL triangulate /dev/stdin");
    CHECK(piped.status == 0);
    CHECK(piped.out == expected.out);
    const auto fifo = cli.shell("rm -f fin && mkfifo fin && (cat " + input + " > fin &) && $DEWALL triangulate fin");
    CHECK(fifo.status == 0);
    CHECK(fifo.out == expected.out);
  }
  const auto substituted = cli.shell("bash -c '$DEWALL triangulate <(cat q.txt)'");  // a /dev/fd/N pipe
  CHECK(substituted.status == 0);
  CHECK(substituted.out == expected.out);
  const auto certify = cli.shell("rm -f fin && mkfifo fin && (cat q.txt > fin &) && cat s.txt | $DEWALL certify fin /dev/stdin");
  CHECK(certify.status == 0);
  CHECK(certify.out.find("delaunay canonical") != std::string::npos);
  const auto draw = cli.shell("cat q.txt | $DEWALL draw /dev/stdin s.txt");
  CHECK(draw.status == 0);
  CHECK(draw.out.rfind("<svg", 0) == 0);
}

TEST_CASE("files: writing to a full device is exit 2 with a write error, for every command", "[cli][files]") {
  const auto cli = fresh("files_test_full");
  if (!make_device(cli, "full", 1, 7)) {
    WARN("mknod not permitted: skipped");
    return;
  }
  cli.write("s.txt", square_simplices);
  for (const std::string command : {"help", "triangulate --help", "certify p.txt s.txt", "certify p.txt s.txt --json",
                                    "demo --points 50 --dim 2 --seed 1", "triangulate p.txt",
                                    "generate uniform 10 --dim 2 --seed 1", "draw p.txt s.txt"}) {
    CAPTURE(command);
    const auto to_stdout = cli.shell("$DEWALL " + command + " > full");
    CHECK(to_stdout.status == 2);
    CHECK(to_stdout.err.find("write error") != std::string::npos);
  }
  for (const std::string command : {"triangulate p.txt -o full", "generate uniform 10 --dim 2 -o full",
                                    "draw p.txt s.txt -o full"}) {
    CAPTURE(command);
    const auto r = cli(command);
    CHECK(r.status == 2);
    CHECK(r.err.find("full: write error: No space left on device") != std::string::npos);
  }
  CHECK(S_ISCHR(mode_of(cli.path("full"))));
}

TEST_CASE("files: hostile tokens are escaped and cut in messages, a BOM is skipped", "[cli][files]") {
  const auto cli = fresh("files_test_tokens");
  SECTION("escape sequences") {
    const auto r = cli.with_stdin("triangulate -", "0 0\n1 0\n\x1b[2J\x1b]0;owned\x07 1\n");
    CHECK(r.status == 2);
    CHECK(r.err.find('\x1b') == std::string::npos);
    CHECK(r.err.find('\x07') == std::string::npos);
    CHECK(r.err.find("<stdin>:3: '\\x1b[2J\\x1b]0;owned\\x07' is not a number") != std::string::npos);
  }
  SECTION("a megabyte-long token") {
    const auto r = cli.with_stdin("triangulate -", "0 0\n1 0\n" + std::string(1 << 20, '7') + "x 1\n");
    CHECK(r.status == 2);
    CHECK(r.err.size() < 200);
    CHECK(r.err.find("(1048577 bytes)") != std::string::npos);
  }
  SECTION("a NUL does not cut the message") {
    const auto r = cli.with_stdin("triangulate -", std::string("0 0\n1 0\n0\0x 1\n", 14));
    CHECK(r.status == 2);
    CHECK(r.err.find("'0\\x00x' is not a number") != std::string::npos);
  }
  SECTION("arguments and file names are escaped too") {
    const auto r = cli("triangulate p.txt '--\x1b[31mred'");
    CHECK(r.status == 2);
    CHECK(r.err.find("unknown option '--\\x1b[31mred'") != std::string::npos);
    const auto missing = cli("triangulate 'no\x1b[1msuch.txt'");
    CHECK(missing.status == 2);
    CHECK(missing.err.find("no\\x1b[1msuch.txt: cannot open file") != std::string::npos);
  }
  SECTION("a UTF-8 byte order mark is skipped, in points and in simplices") {
    cli.write("bom.txt", "\xEF\xBB\xBF" + square);
    cli.write("bom_s.txt", "\xEF\xBB\xBF" + square_simplices);
    const auto r = cli("triangulate bom.txt");
    CHECK(r.status == 0);
    CHECK(r.out == square_simplices);
    CHECK(cli("certify bom.txt bom_s.txt").status == 0);
  }
}

TEST_CASE("files: more rows than the header announces is exit 2 (.node, VTK, rbox, .ele, Qhull)", "[cli][files]") {
  const auto cli = fresh("files_test_rows");
  cli.write("x.node", "4 2 0 0\n0 0 0\n1 1 0\n2 0 1\n3 1 1\n4 2 2\n");
  cli.write("ok.node", "4 2 0 0\n0 0 0\n1 1 0\n2 0 1\n3 1 1\n# end\n\n");
  cli.write("x.vtk", "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n0 0 0 1 0 0\n0 1 0 1 1 0\n5 5 0\n");
  cli.write("y.vtk", "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n0 0 0 1 0 0\n0 1 0 1 1 0 5\n");
  cli.write("ok.vtk", "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n0 0 0 1 0 0\n0 1 0 1 1 0\n\nVERTICES 1 2\n1 0\n");
  cli.write("x.rbox", "2 rbox 4 D2\n4\n0 0\n1 0\n0 1\n1 1\n2 2\n");
  cli.write("x.ele", "2 3 0\n0 0 1 2\n1 1 3 2\n2 0 1 3\n");
  const auto node = cli("triangulate x.node");
  CHECK(node.status == 2);
  CHECK(node.err.find("x.node:6: more rows than the header announces (4 points)") != std::string::npos);
  CHECK(cli("triangulate ok.node").status == 0);
  const auto vtk = cli("triangulate x.vtk");
  CHECK(vtk.status == 2);
  CHECK(vtk.err.find("x.vtk:8: more coordinates than the POINTS header announces (4 points)") != std::string::npos);
  CHECK(cli("triangulate y.vtk").status == 2);
  CHECK(cli("triangulate ok.vtk").status == 0);
  const auto rbox = cli("triangulate x.rbox");
  CHECK(rbox.status == 2);
  CHECK(rbox.err.find("x.rbox:7: more rows than the header announces (4 points)") != std::string::npos);
  const auto ele = cli("certify p.txt x.ele");
  CHECK(ele.status == 2);
  CHECK(ele.err.find("x.ele:4: more rows than the header announces (2 simplices)") != std::string::npos);
  cli.write("x.qh", "2\n0 1 2\n1 3 2\n0 1 3\n");  // qdelaunay i: a count, then the facets
  const auto qhull = cli("certify p.txt x.qh");
  CHECK(qhull.status == 2);
  CHECK(qhull.err.find("x.qh:4: more rows than the header announces (2 facets)") != std::string::npos);
}

TEST_CASE("files: a VTK POINTS count that does not match its data is exit 2 (binary and ASCII)", "[cli][files]") {
  const auto cli = fresh("files_test_vtk_count");
  REQUIRE(cli("generate uniform 50 --dim 3 --seed 1 -o b.vtk").status == 0);  // binary, with a CELLS section
  const std::string file = slurp(cli.path("b.vtk"));
  const auto at = file.find("POINTS 50 double");
  REQUIRE(at != std::string::npos);
  CHECK(cli("triangulate b.vtk").status == 0);
  // 60 used to read 10 "points" out of the CELLS section, 40 to ignore the last ten: exit 0 both.
  for (const std::string count : {"60", "40"}) {
    CAPTURE(count);
    std::string changed = file;
    changed.replace(at + 7, 2, count);
    cli.write("c.vtk", changed);
    const auto r = cli("triangulate c.vtk");
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.find("c.vtk:5: count mismatch: the POINTS section announces " + count + " points") != std::string::npos);
  }
  cli.write("a.vtk", "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n"
                     "0 0 0\n1 0 0\n0 1 0\n1 1 0\nCELLS 1 5\n4 0 1 2 3\n");
  const auto ascii = cli("triangulate a.vtk");
  CHECK(ascii.status == 2);
  CHECK(ascii.err.find("a.vtk:5: truncated: the POINTS section announces 5 points (15 coordinates), the file has 12 "
                       "before 'CELLS' on line 10") != std::string::npos);
  CHECK(ascii.err.find("not a number") == std::string::npos);
}

TEST_CASE("files: an output that cannot be written fails before the work, leaving nothing", "[cli][files]") {
  const auto cli = fresh("files_test_output_first");
  fs::create_directory(cli.path("dir"));
  cli.write("line.txt", "0 0\n1 1\n2 2\n");  // collinear: triangulating it is exit 1, not 2
  cli.write("old.txt", "old\n");
  struct Target {
    std::string path, message;
  };
  std::vector<Target> targets = {{"nodir/out.txt", "nodir/out.txt: cannot create a temporary file in nodir/"},
                                 {"dir", "dir: cannot open: Is a directory"},
                                 {"''", "'': cannot open: No such file or directory"}};
  if (::geteuid() != 0) {  // root may write a read-only file
    REQUIRE(::chmod(cli.path("old.txt").c_str(), 0444) == 0);
    targets.push_back({"old.txt", "old.txt: cannot write: Permission denied"});
  } else {
    WARN("running as root: the read-only file case is skipped");
  }
  for (const auto& [target, message] : targets) {
    CAPTURE(target);
    for (const std::string command : {"triangulate line.txt", "triangulate line.txt --stream", "draw line.txt --walls",
                                      "triangulate no-such-input.txt", "generate uniform 1000 --dim 2"}) {
      CAPTURE(command);
      const auto r = cli(command + " -o " + target);
      CHECK(r.status == 2);
      CHECK(r.err.find(message) != std::string::npos);
      CHECK(r.err.find("collinear") == std::string::npos);      // not triangulated
      CHECK(r.err.find("no-such-input") == std::string::npos);  // not even read
      CHECK(r.err.find("seed") == std::string::npos);           // not generated
    }
  }
  CHECK(slurp(cli.path("old.txt")) == "old\n");
  CHECK(fs::is_empty(cli.path("dir")));
  CHECK(others(cli.dir, {"p.txt", "line.txt", "old.txt", "dir", "out.txt", "err.txt"}).empty());
  // (A FIFO is not opened by the check: "a FIFO's reader gets the output" above.)
}

TEST_CASE("files: draw scales coordinates near the double range safely, refuses non-finite ones", "[cli][files]") {
  const auto cli = fresh("files_test_draw_range");
  cli.write("big.txt", "1e308 1e308\n-1e308 -1e308\n1.7e308 -1.7e308\n-1e308 1.5e308\n0 0\n");
  const auto r = cli("draw big.txt --walls --width 400");
  CHECK(r.status == 0);
  CHECK(r.out.find("nan") == std::string::npos);
  CHECK(r.out.find("inf") == std::string::npos);
  CHECK(r.out.find("<polygon") != std::string::npos);
  cli.write("s.txt", "0 1 2\n");
  cli.write("inf.txt", "0 0\n1 0\ninf 1\n");
  const auto refused = cli("draw inf.txt s.txt");
  CHECK(refused.status == 1);
  CHECK(refused.err.find("inf.txt: point 2 has a non-finite coordinate") != std::string::npos);
}

TEST_CASE("files: certify --json stays valid UTF-8 with a file name that is not", "[cli][files]") {
  const auto cli = fresh("files_test_json");
  const std::string points = "p\xff\xfe.txt", simplices = "s\xc3(.txt";  // invalid bytes, a broken sequence
  cli.write(points, square);
  cli.write(simplices, "0 1 2\n1 3 2\n0 1 7\n");  // index 7 out of range: the message names the file
  const auto r = cli("certify --json '" + points + "' '" + simplices + "'");
  CHECK(r.status == 1);
  CHECK(valid_utf8(r.out));
  CHECK(r.out.find("s\\\\xc3(.txt") != std::string::npos);  // the escaped byte, its backslash escaped for JSON
  CHECK(r.out.rfind("{\"delaunay\":false", 0) == 0);
}

TEST_CASE("files: no arguments is a usage error, -- ends the options", "[cli][files]") {
  const auto cli = fresh("files_test_arguments");
  const auto none = cli("");
  CHECK(none.status == 2);
  CHECK(none.out.empty());
  CHECK(none.err.find("usage: dewall") != std::string::npos);
  cli.write("-p.txt", square);
  cli.write("--help", square);
  const auto dashed = cli("triangulate -- -p.txt");
  CHECK(dashed.status == 0);
  CHECK(dashed.out == square_simplices);
  CHECK(cli("triangulate -- --help").out == square_simplices);
  CHECK(cli("triangulate -o out.txt -- -p.txt").status == 0);
  CHECK(slurp(cli.path("out.txt")) == square_simplices);
  CHECK(cli("triangulate -p.txt").status == 2);  // without --, an unknown option
}

TEST_CASE("files: messages name the real problem", "[cli][files]") {
  const auto cli = fresh("files_test_messages");
  SECTION("an rbox count line of -4 or 4.5") {
    for (const std::string count : {"-4", "4.5"}) {
      const auto r = cli.with_stdin("triangulate -", "2 rbox 4 D2\n" + count + "\n0 0\n1 0\n0 1\n1 1\n");
      CHECK(r.status == 2);
      CHECK(r.err.find("<stdin>:2: invalid point count '" + count + "'") != std::string::npos);
      CHECK(r.err.find("dimension") == std::string::npos);
    }
    const auto lone = cli.with_stdin("triangulate -", "2\n" + std::string("-4") + "\n0 0\n");
    CHECK(lone.err.find("invalid point count '-4'") != std::string::npos);
    const auto one_d = cli.with_stdin("triangulate -", "1\n2\n3\n");
    CHECK(one_d.err.find("dimension 1 is not supported") != std::string::npos);
  }
  SECTION("CR-only line endings are line endings") {
    const auto r = cli.with_stdin("triangulate -", "0 0\r1 0\r0 1\r1 1\r");
    CHECK(r.status == 0);
    CHECK(r.out == square_simplices);
    const auto bad = cli.with_stdin("triangulate -", "0 0\r1 0\r0 y\r");
    CHECK(bad.err.find("<stdin>:3: 'y' is not a number") != std::string::npos);
  }
  SECTION("generate uniform -1 and 1e10") {
    const auto negative = cli("generate uniform -1");
    CHECK(negative.status == 2);
    CHECK(negative.err.find("invalid point count '-1'") != std::string::npos);
    for (const std::string n : {"1e10", "1e12"}) {  // 240 GB and 24 TB of coordinates
      const auto huge = cli("generate uniform " + n);
      CHECK(huge.status == 2);
      CHECK(huge.err.find("GB for their coordinates alone") != std::string::npos);
      CHECK(huge.err.find("bad_alloc") == std::string::npos);
    }
  }
  SECTION("generate --noise: a number in [0, 1], sphere and torus only") {
    CHECK(cli("generate torus 100 --noise 0.05 --seed 1 -o t.txt").status == 0);
    for (const std::string x : {"-0.1", "2", "nan", "x", "0.1.2"}) {
      const auto bad = cli("generate torus 100 --noise " + x);
      CHECK(bad.status == 2);
      CHECK(bad.err.find("invalid noise") != std::string::npos);
    }
    const auto cube = cli("generate uniform 100 --noise 0.1");
    CHECK(cube.status == 2);
    CHECK(cube.err.find("sphere and torus only") != std::string::npos);
  }
  SECTION("generate --planes: 2 to 1000, kind planes only") {
    CHECK(cli("generate planes 100 --planes 2 --seed 1 -o p.txt").status == 0);
    for (const std::string p : {"1", "1001", "99999999999999999999", "-2", "x"}) {
      const auto bad = cli("generate planes 100 --planes " + p);
      CHECK(bad.status == 2);
    }
    CHECK(cli("generate uniform 100 --planes 2").err.find("kind planes only") != std::string::npos);
  }
  SECTION("a non-finite point is named once, as the file numbers it") {
    const auto r = cli.with_stdin("triangulate -", "0 0\n1 0\nnan 1\n1 1\n");
    CHECK(r.status == 1);
    CHECK(r.err == "dewall: <stdin>: point 2 has a non-finite coordinate (NaN or infinity)\n");
    cli.write("n.node", "4 2 0 0\n1 nan 0\n2 1 0\n3 0 1\n4 1 1\n");
    const auto node = cli("triangulate n.node");
    CHECK(node.status == 1);
    CHECK(node.err == "dewall: n.node: point 1 has a non-finite coordinate (NaN or infinity)\n");
  }
}

TEST_CASE("quoting: printable, quoted and json_string", "[io][files]") {
  using dewall::io::json_string;
  using dewall::io::printable;
  using dewall::io::quoted;
  CHECK(printable("plain text") == "plain text");
  CHECK(printable("caf\xC3\xA9 \xE5\x9C\x96") == "caf\xC3\xA9 \xE5\x9C\x96");  // valid UTF-8 kept
  CHECK(printable("a\tb\nc\\") == "a\\tb\\nc\\\\");
  CHECK(printable("\x1b[0m\x7f") == "\\x1b[0m\\x7f");
  CHECK(printable("\xC2\x9B" "31m") == "\\xc2\\x9b31m");                // C1 CSI
  CHECK(printable("\xE2\x80\xAE" "txt") == "\\xe2\\x80\\xaetxt");      // right-to-left override
  CHECK(printable("\xC0\xAF\xED\xA0\x80") == "\\xc0\\xaf\\xed\\xa0\\x80");  // overlong, surrogate
  CHECK(printable(std::string(100, 'a'), 10) == "aaaaaaaaaa… (100 bytes)");
  CHECK(printable("\xEF\xBB\xBF" "1\xE2\x80\x8B") == "\\xef\\xbb\\xbf1\\xe2\\x80\\x8b");  // a BOM, a zero-width space
  CHECK(dewall::io::file_name("dir/file.txt") == "dir/file.txt");
  const std::string long_name = "/a/" + std::string(300, 'x') + "/caf\xC3\xA9\x1b.txt";
  const std::string shown = dewall::io::file_name(long_name);
  CHECK(shown.rfind("/a/xxx", 0) == 0);
  CHECK(shown.find("xxx…xxx") != std::string::npos);
  CHECK(shown.find("/caf\xC3\xA9\\x1b.txt (314 bytes)") != std::string::npos);
  CHECK(shown.size() < 220);
  std::string accents;
  for (int i = 0; i < 150; ++i) accents += "\xC3\xA9";
  CHECK(valid_utf8(dewall::io::file_name(accents)));  // cut between characters, never inside one
  const std::string controls(60, '\x01');  // 60 bytes, 240 once escaped
  const std::string escaped24 = printable(controls.substr(36));  // 96 bytes
  CHECK(dewall::io::file_name(controls) == escaped24 + "…" + escaped24 + " (60 bytes)");
  CHECK(quoted("x") == "'x'");
  CHECK(json_string("a\"b\\c\n\xff") == "\"a\\\"b\\\\c\\u000a\\\\xff\"");
  CHECK(valid_utf8(json_string("\xff\xfe\xc3(\xE2\x80\xAE")));
}
