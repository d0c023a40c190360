// One row of the benchmark suite (bench/suite, issue 10 item 4): one point set,
// CGAL and dewall (its own incremental engine, the default engine and forced
// DeWall) on the same points, one
// thread each, and ONE line of JSON with everything on standard output.
//
//   bench_suite_row --kind K --points N --dim D [--seed S] [--noise X] [--planes P]
//                   [--tools cgal,incremental,auto,dewall] [--repeat R] [--tool-limit SEC]
//                   [--floor-sample M] [--clock wall|cpu] [--repeat-budget SEC]
//
// Steps:
//  1. generate the points with dewall's generator (io/point_generators.hpp);
//  2. untimed: CGAL's triangulation as the reference (tests/support/cgal_delaunay.hpp)
//     and, on it, the "floor" of issue 10: the mean number of points within one
//     spacing h of the circumsphere of a sample of its cells (below);
//  3. timed, best of R (fewer once a tool's runs of the row have taken
//     --repeat-budget seconds: small rows repeat, large ones run once): CGAL (Delaunay_triangulation_2/_3 with Epick, dD
//     Delaunay_triangulation with Epick_d in 4D and 5D), then dewall with
//     Engine::incremental, Engine::automatic, then Engine::dewall, all with parallel_depth 0;
//     each dewall result is compared with the reference as a set of sorted
//     index tuples right after its run (untimed).
// A watchdog stops a tool that runs longer than --tool-limit: the line is then
// printed with that tool marked "stopped" and the row exits (status 0, or 1 if
// a result already differed). Exit status 1 also when a result differs from
// CGAL's, 2 for bad options.
//
// The floor: h is the mean nearest-neighbour distance (over up to 2,000 sampled
// points). Unlike (bounding-box volume / n)^(1/D) it is the point spacing on
// surfaces, layers and lattices too, so "within one spacing" means the same on
// every kind. For each sampled cell with circumcentre c and radius r, count the
// points p with | |p − c| − r | ≤ h (a uniform grid; whole grid cells inside the
// shell are counted without visiting their points). Large spheres (points on a
// sphere: every point is near every circumsphere) cost a lot, so the sample
// stops after a work budget of about 3 × 10^8 grid cells and points; the line
// gives the number of cells sampled.
#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Epick_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <mutex>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include "support/cgal_delaunay.hpp"
#include "dewall/dewall.hpp"
#include "dewall/io/point_generators.hpp"
#include "dewall/kernel/point_array.hpp"

namespace {

using Clock = std::chrono::steady_clock;

// ---- options ---------------------------------------------------------------

struct Row_options {
  dewall::io::Point_kind kind = dewall::io::Point_kind::uniform;
  std::uint64_t n = 10000, dim = 3, seed = 1, repeat = 1, floor_sample = 2000;
  double noise = 0, tool_limit = 0;
  // Repeats stop once a tool's runs have taken this long in total (the first
  // run of a small input pays one-time costs, TBB's threads and fresh pages,
  // that a best of 1 reports as the tool's: 2D 10^4 points 1.4x CGAL's time
  // after one run, 0.65x as the best of 5).
  double repeat_budget = HUGE_VAL;
  int planes = 0;
  bool cgal = true, incremental = true, automatic = true, forced = true;
  // cpu: the process's CPU time instead of wall time (a loaded, shared
  // machine: waiting for a core is not the tool's cost; the tools run on one thread).
  bool cpu_clock = false;
};

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr,
               "bench_suite_row: %s\n"
               "usage: bench_suite_row --kind K --points N --dim 2|3|4|5 [--seed S] [--noise X] [--planes P]\n"
               "                       [--tools cgal,incremental,auto,dewall] [--repeat R] [--tool-limit SEC]\n"
               "                       [--floor-sample M] [--clock wall|cpu] [--repeat-budget SEC]\nK: %s\n",
               why.c_str(), dewall::io::point_kind_names().c_str());
  std::exit(2);
}

std::uint64_t parse_count(const std::string& option, const char* text) {
  char* end = nullptr;
  errno = 0;
  // Also 1e6: the suite's counts are powers of ten.
  const double v = std::strtod(text, &end);
  if (*text < '0' || *text > '9' || *end != '\0' || errno == ERANGE || v != std::floor(v) || v > 1e12)
    usage(option + " needs a non-negative whole number, not " + text);
  return static_cast<std::uint64_t>(v);
}

double parse_number(const std::string& option, const char* text) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text, &end);
  if (*text == '\0' || *end != '\0' || errno == ERANGE || !(v >= 0) || !std::isfinite(v))
    usage(option + " needs a non-negative number, not " + text);
  return v;
}

Row_options parse_options(int argc, char** argv) {
  Row_options o;
  bool have_kind = false, have_points = false, have_dim = false;
  for (int i = 1; i < argc; i += 2) {
    const std::string option = argv[i];
    if (i + 1 == argc) usage(option + " needs a value");
    const char* value = argv[i + 1];
    if (option == "--kind") {
      const auto parsed = dewall::io::parse_point_kind(value);
      if (!parsed) usage(std::string("unknown kind ") + value);
      o.kind = *parsed, have_kind = true;
    } else if (option == "--points") {
      o.n = parse_count(option, value), have_points = true;
    } else if (option == "--dim") {
      o.dim = parse_count(option, value), have_dim = true;
    } else if (option == "--seed") {
      o.seed = parse_count(option, value);
    } else if (option == "--repeat") {
      o.repeat = parse_count(option, value);
    } else if (option == "--floor-sample") {
      o.floor_sample = parse_count(option, value);
    } else if (option == "--noise") {
      o.noise = parse_number(option, value);
    } else if (option == "--planes") {
      o.planes = static_cast<int>(std::min<std::uint64_t>(parse_count(option, value), 1001));
    } else if (option == "--clock") {
      if (std::string(value) != "wall" && std::string(value) != "cpu") usage("--clock needs wall or cpu");
      o.cpu_clock = std::string(value) == "cpu";
    } else if (option == "--repeat-budget") {
      o.repeat_budget = parse_number(option, value);
    } else if (option == "--tool-limit") {
      o.tool_limit = parse_number(option, value);
    } else if (option == "--tools") {
      o.cgal = o.incremental = o.automatic = o.forced = false;
      std::stringstream list(value);
      for (std::string tool; std::getline(list, tool, ',');) {
        if (tool == "cgal") o.cgal = true;
        else if (tool == "incremental") o.incremental = true;
        else if (tool == "auto") o.automatic = true;
        else if (tool == "dewall") o.forced = true;
        else usage("unknown tool '" + tool + "' (cgal, incremental, auto, dewall)");
      }
    } else {
      usage("unknown option " + option);
    }
  }
  if (!have_kind || !have_points || !have_dim) usage("--kind, --points and --dim are required");
  if (o.dim < 2 || o.dim > 5) usage("--dim must be 2 … 5");
  if (o.repeat < 1 || o.repeat > 100) usage("--repeat must be 1 … 100");
  return o;
}

// ---- the JSON line and the watchdog -----------------------------------------

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

/// The row's results so far, as JSON members; shared with the watchdog, which
/// prints them if a tool overruns --tool-limit.
class Report {
 public:
  void add(const std::string& member) {
    std::lock_guard lock(mutex_);
    members_ += (members_.empty() ? "" : ",") + member;
  }
  void mismatch() {
    std::lock_guard lock(mutex_);
    differs_ = true;
  }
  /// Starts timing `tool` for the watchdog.
  void start(const std::string& tool) {
    std::lock_guard lock(mutex_);
    running_ = tool, started_ = Clock::now(), ++generation_;
    changed_.notify_all();
  }
  void stop() {
    std::lock_guard lock(mutex_);
    running_.clear(), ++generation_;
    changed_.notify_all();
  }
  /// Prints the line (unless `print` is false: the row failed) and returns
  /// the exit status; ends the watchdog.
  int finish(bool print = true) {
    std::lock_guard lock(mutex_);
    finished_ = true;
    changed_.notify_all();
    if (print) print_locked();
    return differs_ ? 1 : 0;
  }
  /// Watches the running tool; on overrun prints the line with that tool
  /// marked stopped and ends the process (the tool cannot be interrupted).
  void watch(double limit) {
    std::unique_lock lock(mutex_);
    while (!finished_) {
      if (running_.empty()) {
        changed_.wait(lock);
        continue;
      }
      const auto generation = generation_;
      const auto deadline = started_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit));
      if (changed_.wait_until(lock, deadline, [&] { return finished_ || generation_ != generation; })) continue;
      members_ += ",\"" + running_ + "\":{\"stopped\":" + json_number(limit) + "}";
      print_locked();
      std::_Exit(differs_ ? 1 : 0);
    }
  }

 private:
  void print_locked() {
    std::printf("{%s,\"all_equal\":%s}\n", members_.c_str(), differs_ ? "false" : "true");
    std::fflush(stdout);
  }
  std::mutex mutex_;
  std::condition_variable changed_;
  std::string members_, running_;
  Clock::time_point started_;
  std::uint64_t generation_ = 0;
  bool differs_ = false, finished_ = false;
};

// ---- simplex sets -------------------------------------------------------------

/// Simplices as a sorted vector of sorted index tuples (a set, in a tenth of
/// std::set's memory: 10^6 points in 3D give 6.7 × 10^6 tetrahedra).
template <int D>
std::vector<dewall::Simplex<D>> canonical(std::vector<dewall::Simplex<D>> simplices) {
  for (auto& s : simplices) std::sort(s.begin(), s.end());
  std::sort(simplices.begin(), simplices.end());
  return simplices;
}

// ---- the floor: points within h of sampled circumspheres ------------------------

/// A uniform grid over the points' bounding box, about two points per cell on
/// volume data, points stored cell by cell.
template <int D>
class Grid {
 public:
  explicit Grid(const std::vector<dewall::kernel::Point_d<D>>& points) {
    lo_.fill(1e300);
    std::array<double, D> hi;
    hi.fill(-1e300);
    for (const auto& p : points)
      for (int j = 0; j < D; ++j) lo_[j] = std::min(lo_[j], p[j]), hi[j] = std::max(hi[j], p[j]);
    double volume = 1;
    for (int j = 0; j < D; ++j) volume *= std::max(hi[j] - lo_[j], 1e-300);
    const double cells = std::max(1.0, static_cast<double>(points.size()) / 2);
    side_ = std::pow(volume / cells, 1.0 / D);
    std::size_t total = 1;
    for (int j = 0; j < D; ++j) {
      // Flat extents (never all of them: the points span E^D) get one cell.
      size_[j] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((hi[j] - lo_[j]) / side_)));
      total *= static_cast<std::size_t>(size_[j]);
    }
    start_.assign(total + 1, 0);
    std::vector<std::size_t> cell_of(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) ++start_[(cell_of[i] = cell(points[i])) + 1];
    for (std::size_t c = 0; c < total; ++c) start_[c + 1] += start_[c];
    points_.resize(points.size());
    auto next = start_;
    for (std::size_t i = 0; i < points.size(); ++i) points_[next[cell_of[i]]++] = points[i];
  }

  /// The distance from `q` to its nearest other point (0 for a duplicate).
  double nearest(const dewall::kernel::Point_d<D>& q) const {
    const auto home = coordinates(q);
    double best = 1e300;
    bool skipped_self = false;
    for (std::int64_t ring = 0;; ++ring) {
      // Points beyond ring k are at least k · side away (q lies in its home cell).
      if (ring > 0 && best <= static_cast<double>(ring - 1) * side_) return best;
      bool inside = false;
      std::array<std::int64_t, D> a, b;
      for (int j = 0; j < D; ++j) a[j] = home[j] - ring, b[j] = home[j] + ring;
      for_cells(a, b, [&](const std::array<std::int64_t, D>& c) {
        bool on_ring = false;
        for (int j = 0; j < D; ++j) on_ring |= c[j] == home[j] - ring || c[j] == home[j] + ring;
        if (!on_ring) return;
        inside = true;
        const auto k = index(c);
        for (std::size_t i = start_[k]; i < start_[k + 1]; ++i) {
          const double d = distance(points_[i], q);
          if (d == 0 && !skipped_self) skipped_self = true;  // q itself
          else best = std::min(best, d);
        }
      });
      if (!inside) return best;  // the rings have left the grid
    }
  }

  /// The number of points p with | |p − c| − r | ≤ h; adds the grid cells and
  /// points visited to `work`.
  std::size_t count_near_sphere(const std::array<double, D>& c, double r, double h, std::size_t& work) const {
    const double inner = std::max(0.0, r - h), outer = r + h;
    std::array<std::int64_t, D> a, b;
    for (int j = 0; j < D; ++j) {
      a[j] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((c[j] - outer - lo_[j]) / side_)), 0, size_[j] - 1);
      b[j] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((c[j] + outer - lo_[j]) / side_)), 0, size_[j] - 1);
    }
    std::size_t count = 0;
    for_cells(a, b, [&](const std::array<std::int64_t, D>& cell) {
      ++work;
      // The nearest and farthest points of the cell's box from c.
      double near2 = 0, far2 = 0;
      for (int j = 0; j < D; ++j) {
        const double x0 = lo_[j] + static_cast<double>(cell[j]) * side_, x1 = x0 + side_;
        const double dn = c[j] < x0 ? x0 - c[j] : c[j] > x1 ? c[j] - x1 : 0;
        const double df = std::max(std::abs(c[j] - x0), std::abs(c[j] - x1));
        near2 += dn * dn, far2 += df * df;
      }
      if (near2 > outer * outer || far2 < inner * inner) return;
      const auto k = index(cell);
      if (near2 >= inner * inner && far2 <= outer * outer) {  // the whole box is in the shell
        count += start_[k + 1] - start_[k];
        return;
      }
      for (std::size_t i = start_[k]; i < start_[k + 1]; ++i) {
        ++work;
        count += std::abs(distance(points_[i], c) - r) <= h;
      }
    });
    return count;
  }

 private:
  template <class P, class Q>
  static double distance(const P& p, const Q& q) {
    double s = 0;
    for (int j = 0; j < D; ++j) s += (p[j] - q[j]) * (p[j] - q[j]);
    return std::sqrt(s);
  }
  std::array<std::int64_t, D> coordinates(const dewall::kernel::Point_d<D>& p) const {
    std::array<std::int64_t, D> c;
    for (int j = 0; j < D; ++j)
      c[j] = std::clamp<std::int64_t>(static_cast<std::int64_t>((p[j] - lo_[j]) / side_), 0, size_[j] - 1);
    return c;
  }
  std::size_t index(const std::array<std::int64_t, D>& c) const {
    std::size_t k = 0;
    for (int j = D - 1; j >= 0; --j) k = k * static_cast<std::size_t>(size_[j]) + static_cast<std::size_t>(c[j]);
    return k;
  }
  std::size_t cell(const dewall::kernel::Point_d<D>& p) const { return index(coordinates(p)); }
  /// Calls f for every cell of the box [a, b] clipped to the grid.
  template <class F>
  void for_cells(std::array<std::int64_t, D> a, std::array<std::int64_t, D> b, F&& f) const {
    for (int j = 0; j < D; ++j) {
      a[j] = std::max<std::int64_t>(a[j], 0), b[j] = std::min<std::int64_t>(b[j], size_[j] - 1);
      if (a[j] > b[j]) return;
    }
    auto c = a;
    for (;;) {
      f(c);
      int j = 0;
      while (j < D && c[j] == b[j]) c[j] = a[j], ++j;
      if (j == D) return;
      ++c[j];
    }
  }

  std::array<double, D> lo_;
  std::array<std::int64_t, D> size_;
  double side_ = 1;
  std::vector<std::size_t> start_;
  std::vector<dewall::kernel::Point_d<D>> points_;
};

/// The circumcentre of simplex s (2 (p_i − p_0) · x = |p_i − p_0|², Gaussian
/// elimination with partial pivoting, in double: a statistic, not a predicate),
/// or nothing when the system is numerically singular.
template <int D>
std::optional<std::array<double, D>> circumcentre(const std::vector<dewall::kernel::Point_d<D>>& points,
                                                  const dewall::Simplex<D>& s) {
  std::array<std::array<double, D + 1>, D> m;
  const auto& p0 = points[s[0]];
  for (int i = 0; i < D; ++i) {
    const auto& p = points[s[i + 1]];
    double rhs = 0;
    for (int j = 0; j < D; ++j) m[i][j] = p[j] - p0[j], rhs += m[i][j] * m[i][j];
    m[i][D] = rhs / 2;
  }
  for (int col = 0; col < D; ++col) {
    int pivot = col;
    for (int i = col + 1; i < D; ++i)
      if (std::abs(m[i][col]) > std::abs(m[pivot][col])) pivot = i;
    if (m[pivot][col] == 0) return std::nullopt;
    std::swap(m[pivot], m[col]);
    for (int i = col + 1; i < D; ++i) {
      const double f = m[i][col] / m[col][col];
      for (int j = col; j <= D; ++j) m[i][j] -= f * m[col][j];
    }
  }
  std::array<double, D> x;
  for (int i = D - 1; i >= 0; --i) {
    double v = m[i][D];
    for (int j = i + 1; j < D; ++j) v -= m[i][j] * x[j];
    x[i] = v / m[i][i];
  }
  for (int j = 0; j < D; ++j) x[j] += p0[j];
  if (!std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); })) return std::nullopt;
  return x;
}

template <int D>
std::string floor_members(const std::vector<dewall::kernel::Point_d<D>>& points,
                          const std::vector<dewall::Simplex<D>>& reference, std::size_t sample) {
  const Grid<D> grid(points);
  std::mt19937_64 rng(12345);  // fixed: the sample does not depend on the row's seed
  // h: the mean nearest-neighbour distance over a sample of points.
  const std::size_t point_sample = std::min<std::size_t>(points.size(), 2000);
  double sum = 0;
  for (std::size_t i = 0; i < point_sample; ++i) sum += grid.nearest(points[rng() % points.size()]);
  const double h = sum / static_cast<double>(point_sample);

  constexpr std::size_t work_budget = 300'000'000;
  std::size_t work = 0, cells = 0;
  double near_sum = 0;
  std::vector<double> radius_in_h;
  for (std::size_t i = 0; i < sample && !reference.empty() && work < work_budget; ++i) {
    const auto& s = reference[rng() % reference.size()];
    const auto c = circumcentre<D>(points, s);
    if (!c) continue;
    double r2 = 0;
    for (int j = 0; j < D; ++j) r2 += (points[s[0]][j] - (*c)[j]) * (points[s[0]][j] - (*c)[j]);
    const double r = std::sqrt(r2);
    near_sum += static_cast<double>(grid.count_near_sphere(*c, r, h, work));
    radius_in_h.push_back(r / h);
    ++cells;
  }
  double median = 0;
  if (!radius_in_h.empty()) {
    auto middle = radius_in_h.begin() + static_cast<std::ptrdiff_t>(radius_in_h.size() / 2);
    std::nth_element(radius_in_h.begin(), middle, radius_in_h.end());
    median = *middle;
  }
  return "\"h\":" + json_number(h) + ",\"h_is\":\"mean nearest-neighbour distance\"" +
         ",\"near_sphere_mean\":" + json_number(cells ? near_sum / static_cast<double>(cells) : NAN) +
         ",\"near_sphere_cells\":" + std::to_string(cells) + ",\"median_circumradius_h\":" + json_number(median);
}

// ---- timing ----------------------------------------------------------------------

bool cpu_clock = false;  // --clock cpu

double now_seconds() {
  if (!cpu_clock) return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// The best time of up to `repeat` runs of f, no more once they have taken
/// `budget` seconds together.
template <class F>
double best_of(std::uint64_t repeat, double budget, F&& f) {
  double best = 1e300, total = 0;
  for (std::uint64_t r = 0; r < repeat && total < budget; ++r) {
    const double start = now_seconds();
    f();
    const double t = now_seconds() - start;
    best = std::min(best, t);
    total += t;
  }
  return best;
}

/// The points as CGAL's point type: converted before timing, as dewall is
/// handed a Point_d array it does not convert.
template <int D>
auto cgal_points(const std::vector<dewall::kernel::Point_d<D>>& points) {
  if constexpr (D == 2) {
    std::vector<CGAL::Epick::Point_2> p;
    for (const auto& q : points) p.emplace_back(q[0], q[1]);
    return p;
  } else if constexpr (D == 3) {
    std::vector<CGAL::Epick::Point_3> p;
    for (const auto& q : points) p.emplace_back(q[0], q[1], q[2]);
    return p;
  } else {
    std::vector<typename CGAL::Epick_d<CGAL::Dimension_tag<D>>::Point_d> p;
    for (const auto& q : points) p.emplace_back(q.x.begin(), q.x.end());
    return p;
  }
}

/// CGAL's construction (the timed part); returns the number of finite cells.
template <int D, class Points>
std::size_t cgal_build(const Points& p) {
  if constexpr (D == 2) {
    CGAL::Delaunay_triangulation_2<CGAL::Epick> dt(p.begin(), p.end());
    return dt.number_of_faces();
  } else if constexpr (D == 3) {
    CGAL::Delaunay_triangulation_3<CGAL::Epick> dt(p.begin(), p.end());
    return dt.number_of_finite_cells();
  } else {
    CGAL::Delaunay_triangulation<CGAL::Epick_d<CGAL::Dimension_tag<D>>> dt(D);
    dt.insert(p.begin(), p.end());
    return dt.number_of_finite_full_cells();
  }
}

template <int D>
int run(const Row_options& o, Report& report) {
  dewall::io::Generator_options shape;
  shape.noise = o.noise;
  shape.planes = o.planes;
  const auto table = dewall::io::generate_points(o.kind, o.n, D, o.seed, shape);
  const auto points = dewall::kernel::points_from_coordinates<D>(table.coordinates);
  const double n = static_cast<double>(points.size());
  report.add(std::string("\"kind\":\"") + dewall::io::point_kind_name(o.kind) + "\",\"d\":" + std::to_string(D) +
             ",\"n\":" + std::to_string(points.size()) + ",\"n_asked\":" + std::to_string(o.n) +
             ",\"seed\":" + std::to_string(o.seed) + ",\"noise\":" + json_number(o.noise) + ",\"planes\":" + std::to_string(o.planes) +
             ",\"repeat\":" + std::to_string(o.repeat));

  // The reference, untimed (CGAL's own, through the project's test helper).
  std::vector<dewall::Simplex<D>> reference;
  {
    const auto set = dewall::cgal::cgal_delaunay<D>(points);
    reference.assign(set.begin(), set.end());  // sorted tuples, sorted: canonical already
  }
  report.add("\"simplices\":" + std::to_string(reference.size()) +
             ",\"simplices_per_point\":" + json_number(static_cast<double>(reference.size()) / n));
  if (o.floor_sample > 0) report.add(floor_members<D>(points, reference, o.floor_sample));

  if (o.cgal) {
    std::size_t cells = 0;
    const auto p = cgal_points<D>(points);
    report.start("cgal");
    const double t = best_of(o.repeat, o.repeat_budget, [&] { cells = cgal_build<D>(p); });
    report.stop();
    report.add("\"cgal\":{\"seconds\":" + json_number(t) + ",\"simplices\":" + std::to_string(cells) + "}");
  }
  auto run_dewall = [&](const char* name, dewall::Engine engine) {
    const dewall::Options options{.parallel_depth = 0, .engine = engine};
    dewall::Triangulation<D> result;
    report.start(name);
    const double t = best_of(o.repeat, o.repeat_budget, [&] { result = dewall::triangulate<D>(points, options); });
    report.stop();
    const auto& st = result.statistics;
    const bool equal = canonical<D>(std::move(result.simplices)) == reference;
    if (!equal) report.mismatch();
    report.add(std::string("\"") + name + "\":{\"seconds\":" + json_number(t) +
               ",\"engine\":\"" + dewall::engine_name(st.engine) + "\"" +
               ",\"searches\":" + std::to_string(st.simplex_searches) +
               ",\"candidates_per_search\":" +
               json_number(st.simplex_searches ? static_cast<double>(st.candidates_tested) /
                                                     static_cast<double>(st.simplex_searches)
                                               : NAN) +
               ",\"searches_before_handover\":" + std::to_string(st.searches_before_handover) +
               ",\"equal_to_cgal\":" + (equal ? "true" : "false") + "}");
  };
  if (o.incremental) run_dewall("incremental", dewall::Engine::incremental);
  if (o.automatic) run_dewall("auto", dewall::Engine::automatic);
  if (o.forced) run_dewall("dewall", dewall::Engine::dewall);
  return report.finish();
}

}  // namespace

int main(int argc, char** argv) {
  const Row_options o = parse_options(argc, argv);
  cpu_clock = o.cpu_clock;
  Report report;
  std::thread watchdog;
  if (o.tool_limit > 0) {
    watchdog = std::thread([&] { report.watch(o.tool_limit); });
  }
  int status = 1;
  try {
    status = o.dim == 2   ? run<2>(o, report)
             : o.dim == 3 ? run<3>(o, report)
             : o.dim == 4 ? run<4>(o, report)
                          : run<5>(o, report);
  } catch (const std::invalid_argument& e) {  // from the generator: bad noise for the kind, too few points
    std::fprintf(stderr, "bench_suite_row: %s\n", e.what());
    status = 2;
    report.finish(false);
  } catch (const std::exception& e) {  // points not spanning E^D, …
    std::fprintf(stderr, "bench_suite_row: %s\n", e.what());
    status = 1;
    report.finish(false);
  }
  if (watchdog.joinable()) watchdog.join();
  return status;
}
