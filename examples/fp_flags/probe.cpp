// A user's program built with the user's own floating-point flags (-ffast-math,
// -Ofast, -march=native with contraction, ...) against the installed package:
// it must still get exactly CGAL's cells, or fail to compile with a message
// naming the flag (examples/fp_flags/run.cmake drives it; CI runs every row).
//
//   probe write DIR   writes the degenerate point sets as DIR/NAME.xyz
//   probe check DIR   triangulates each set, writes DIR/NAME.TAG.simplices and
//                     compares them, as sets, with DIR/NAME.cgal.txt (CGAL's cells,
//                     computed by the dewall CLI built with safe flags)
// Built with -DPROBE_USER_KERNEL it triangulates through a user-defined kernel:
// the header-only path, which must refuse unsafe flags at compile time.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "dewall/certify/certify.hpp"
#include "dewall/dewall.hpp"
#include "dewall/kernel/orientation.hpp"

#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace {

template <int D>
using Points = std::vector<dewall::kernel::Point_d<D>>;

#ifdef PROBE_USER_KERNEL
// A kernel of the user's own: a distinct type, so the algorithm is compiled here.
template <int D>
struct User_kernel : dewall::kernel::Filtered_kernel_d<D> {};
constexpr const char* tag = "user";
#else
constexpr const char* tag = "dewall";
#endif

template <int D>
dewall::Triangulation<D> triangulate(const Points<D>& points) {
#ifdef PROBE_USER_KERNEL
  return dewall::triangulate<User_kernel<D>>(std::span<const dewall::kernel::Point_d<D>>(points));
#else
  return dewall::triangulate<D>(points);
#endif
}

/// An n^D integer lattice; every fifth point has one coordinate moved up by one
/// ulp (0 becomes the smallest subnormal), then everything is scaled by 2^scale
/// and shifted by `offset` (both exact for these values).
template <int D>
Points<D> nudged_lattice(int n, int scale, double offset) {
  Points<D> points;
  std::array<int, D> c{};
  for (int k = 0;; ++k) {
    dewall::kernel::Point_d<D> p;
    for (int j = 0; j < D; ++j) p[j] = std::ldexp(c[j], scale) + offset;
    if (k % 5 == 0) p[k % D] = std::nextafter(p[k % D], 1e300);
    points.push_back(p);
    int j = 0;
    for (; j < D && ++c[j] == n; ++j) c[j] = 0;
    if (j == D) return points;
  }
}

/// Integer points on the spheres x²+y²+z² = 25 and 50, and the centre:
/// every sphere test among them is a tie the perturbation decides.
Points<3> cospherical_integers() {
  Points<3> points{{{0, 0, 0}}};
  for (int x = -8; x <= 8; ++x)
    for (int y = -8; y <= 8; ++y)
      for (int z = -8; z <= 8; ++z)
        if (x * x + y * y + z * z == 25 || x * x + y * y + z * z == 50) points.push_back({{double(x), double(y), double(z)}});
  return points;
}

template <int D>
std::string to_text(const Points<D>& points) {
  std::string s;
  char buffer[40];
  for (const auto& p : points) {
    for (int j = 0; j < D; ++j) {
      std::snprintf(buffer, sizeof buffer, j ? " %.17g" : "%.17g", p[j]);
      s += buffer;
    }
    s += '\n';
  }
  return s;
}

template <int D>
Points<D> from_text(const std::string& path) {
  std::ifstream in(path);
  Points<D> points;
  dewall::kernel::Point_d<D> p;
  std::string token;
  for (int j = 0; in >> token; j = (j + 1) % D) {
    p[j] = std::strtod(token.c_str(), nullptr);  // libc: exact, whatever the flags
    if (j == D - 1) points.push_back(p);
  }
  return points;
}

/// Simplices as sorted index tuples, sorted: the set, comparable across tools.
std::vector<std::vector<std::uint32_t>> read_simplices(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::uint32_t>> set;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::vector<std::uint32_t> s;
    for (std::uint32_t v; fields >> v;) s.push_back(v);
    std::sort(s.begin(), s.end());
    set.push_back(s);
  }
  std::sort(set.begin(), set.end());
  return set;
}

struct Set {
  const char* name;
  int dimension;
};
constexpr Set sets[] = {{"lattice_ulp", 3}, {"lattice_ulp_2d", 2}, {"cospherical", 3},
                        {"tiny", 3},        {"huge", 3},           {"offset", 3}};

void write_sets(const std::string& dir) {
  const auto write = [&](const char* name, const std::string& text) { std::ofstream(dir + "/" + name + ".xyz") << text; };
  write("lattice_ulp", to_text<3>(nudged_lattice<3>(7, 0, 0)));
  write("lattice_ulp_2d", to_text<2>(nudged_lattice<2>(20, 0, 0)));
  write("cospherical", to_text<3>(cospherical_integers()));
  write("tiny", to_text<3>(nudged_lattice<3>(6, -500, 0)));
  write("huge", to_text<3>(nudged_lattice<3>(6, 400, 0)));
  write("offset", to_text<3>(nudged_lattice<3>(6, 0, 0x1p30)));
}

/// Triangulates DIR/NAME.xyz, writes the simplices, compares with CGAL's.
template <int D>
bool check_set(const std::string& dir, const char* name) {
  const std::string base = dir + "/" + name;
  const Points<D> points = from_text<D>(base + ".xyz");
  const auto t = triangulate<D>(points);
  const std::string out = base + "." + tag + ".simplices";
  {
    std::ofstream file(out);
    for (const auto& s : t.simplices) {
      for (int i = 0; i <= D; ++i) file << (i ? " " : "") << s[i];
      file << '\n';
    }
  }
  const bool same = read_simplices(out) == read_simplices(base + ".cgal.txt");
  // The certifier, called from this file too: compiled in the library.
  const auto report = dewall::certify::certify<dewall::kernel::Filtered_kernel_d<D>>(points, t.simplices);
  std::printf("%-15s %zu points, %zu simplices: %s CGAL's cells; in-process certify: %s\n", name, points.size(),
              t.simplices.size(), same ? "equal to" : "DIFFERENT FROM",
              report.canonical ? "canonical" : report.delaunay ? "Delaunay, NOT canonical" : "NOT DELAUNAY");
  return same && report.canonical;
}

/// A predicate called directly: orientation of (0,0,0), (2^-1074,0,0), (0,1,0),
/// (0,0,1) is POSITIVE; with subnormals flushed to zero it would look ZERO.
bool check_predicate() {
  using P = dewall::kernel::Point_d<3>;
  const P a{{0, 0, 0}}, b{{0x1p-1074, 0, 0}}, c{{0, 1, 0}}, d{{0, 0, 1}};
  const auto s = dewall::kernel::orientation_d<3>(a, b, c, d);
  std::printf("orientation with a subnormal coordinate: %d (expected 1)\n", static_cast<int>(s));
  return s == dewall::kernel::POSITIVE;
}

}  // namespace

/// What the process's floating-point environment is at start: a program linked
/// with -ffast-math, -Ofast or -funsafe-math-optimizations starts with
/// flush-to-zero and denormals-are-zero on (crtfastmath.o), which is what the
/// libraries must withstand (run.cmake checks the line).
void report_environment() {
#if defined(__x86_64__)
  const unsigned csr = _mm_getcsr();
  std::printf("environment at start: FTZ/DAZ %s\n", (csr & 0x8040u) == 0x8040u ? "on" : "off");
#endif
}

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: probe write|check DIR\n");
    return 2;
  }
  const std::string mode = argv[1], dir = argv[2];
  if (mode == "write") {
    write_sets(dir);
    for (const auto& s : sets) std::printf("%s\n", s.name);  // the list run.cmake iterates over
    return 0;
  }
  report_environment();
  bool ok = check_predicate();
  for (const auto& s : sets) ok &= s.dimension == 2 ? check_set<2>(dir, s.name) : check_set<3>(dir, s.name);
  std::printf("%s\n", ok ? "all equal to CGAL" : "FAILED");
  return ok ? 0 : 1;
}
