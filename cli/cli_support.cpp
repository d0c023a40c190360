#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include <unistd.h>

#include "cli.hpp"
#include "dewall/certify/certify.hpp"
#include "dewall/dewall.hpp"
#include "dewall/io/quote.hpp"
#include "dewall/kernel/predicate_stats.hpp"

namespace dewall::cli {
namespace {

template <int D>
Run triangulate_table(io::Point_table& table, const Options& options, const Simplex_rows_sink* stream,
                      bool keep_coordinates) {
  auto points = kernel_points<D>(table);
  if (stream || !keep_coordinates) std::vector<double>().swap(table.coordinates);
  Run run;
  auto& indices = run.simplices.indices;
  run.simplices.vertices_per_simplex = D + 1;
  static constexpr std::size_t rows_per_block = 1 << 15;
  const auto start = std::chrono::steady_clock::now();
  // Collecting, the library says how many simplices come (reserve): the list
  // is built once, without the copies of a growing vector (10^7 points: 1 GB).
  struct Rows {
    std::vector<std::uint32_t>& indices;
    const Simplex_rows_sink* stream;
    std::vector<kernel::Point_d<D>>& points;
    void reserve(std::size_t n) {
      if (!stream) indices.reserve(n * (D + 1));
    }
    // The engine has copied the points: ours go (what is written needs none,
    // or, for VTK, takes them from the table).
    void input_no_longer_read() { std::vector<kernel::Point_d<D>>().swap(points); }
    void operator()(const Simplex<D>& s) {
      indices.insert(indices.end(), s.begin(), s.end());
      if (stream && indices.size() == rows_per_block * (D + 1)) {
        (*stream)(indices);
        indices.clear();
      }
    }
  };
  run.stats = triangulate_to<kernel::Filtered_kernel_d<D>>(std::span<const kernel::Point_d<D>>(points),
                                                            Rows{indices, stream, points}, options);
  if (stream) {
    (*stream)(indices);
    std::vector<std::uint32_t>().swap(indices);
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

template <int D>
certify::Report certify_table(const io::Point_table& points, const io::Simplex_table& table,
                              const certify::Options& options) {
  // The rows as they were read, without a copy (10^7 points: 1 GB): an array
  // of D + 1 indices has their layout.
  static_assert(sizeof(certify::Simplex_indices<D>) == (D + 1) * sizeof(std::uint32_t) &&
                alignof(certify::Simplex_indices<D>) == alignof(std::uint32_t));
  const std::span<const certify::Simplex_indices<D>> s(
      reinterpret_cast<const certify::Simplex_indices<D>*>(table.indices.data()), table.size());
  // Likewise the coordinates: a Point_d<D> is D doubles.
  static_assert(sizeof(kernel::Point_d<D>) == D * sizeof(double) && alignof(kernel::Point_d<D>) == alignof(double));
  const std::span<const kernel::Point_d<D>> p(reinterpret_cast<const kernel::Point_d<D>*>(points.coordinates.data()),
                                              points.coordinates.size() / D);
  return certify::certify<kernel::Filtered_kernel_d<D>>(p, s, options);
}

/// A simplex file as the certifier reads it: rows straight into its blocks.
template <int D>
class File_source final : public certify::Simplex_source<D> {
 public:
  explicit File_source(io::Simplex_file_reader& reader) : reader_(reader) {}
  std::size_t read(std::span<certify::Simplex_indices<D>> rows) override {
    return reader_.read(std::span<std::uint32_t>(reinterpret_cast<std::uint32_t*>(rows.data()), rows.size() * (D + 1)));
  }
  std::size_t remaining() const override {
    const std::uint64_t m = reader_.remaining();
    return m == ~std::uint64_t{0} ? certify::npos : static_cast<std::size_t>(m);
  }

 private:
  io::Simplex_file_reader& reader_;
};

template <int D>
std::span<const kernel::Point_d<D>> point_span(const io::Point_table& points) {
  // A Point_d<D> is D doubles: the coordinates as they were read, without a copy.
  static_assert(sizeof(kernel::Point_d<D>) == D * sizeof(double) && alignof(kernel::Point_d<D>) == alignof(double));
  return {reinterpret_cast<const kernel::Point_d<D>*>(points.coordinates.data()), points.coordinates.size() / D};
}

}  // namespace

certify::Report certify_file(const io::Point_table& points, io::Simplex_file_reader& simplices,
                             const certify::Options& options) {
  static_assert(sizeof(certify::Simplex_indices<3>) == 4 * sizeof(std::uint32_t));
  return with_dimension(points.dimension, [&](auto d) {
    File_source<d()> source(simplices);
    return certify::certify<kernel::Filtered_kernel_d<d()>>(point_span<d()>(points), source, options);
  });
}

std::uint64_t physical_memory() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page_size > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size) : 0;
}

certify::Report certify_any(const io::Point_table& points, const io::Simplex_table& simplices,
                            const certify::Options& options) {
  return with_dimension(points.dimension, [&](auto d) { return certify_table<d()>(points, simplices, options); });
}

Run triangulate_any(io::Point_table& table, const Options& options, const Simplex_rows_sink* stream,
                    bool keep_coordinates) {
  return with_dimension(table.dimension,
                        [&](auto d) { return triangulate_table<d()>(table, options, stream, keep_coordinates); });
}

void print_stats(std::FILE* out, const Run& run) {
  const auto& s = run.stats;
  std::fprintf(out, "points=%zu distinct=%zu simplices=%zu engine=%s build_s=%.6f\n", s.input_points, s.distinct_points,
               s.simplices, engine_name(s.engine), run.seconds);
  // Which construction built how many simplices, then the counters of the
  // walls (the paper's Table 1) when walls ran: zeros would say nothing.
  const bool walls = s.engine == Engine::dewall || s.engine == Engine::hybrid;
  const std::size_t by_walls = walls ? s.simplices - s.region_simplices : 0;
  if (s.engine == Engine::dewall)
    std::fprintf(out, "built: walls %zu simplices\n", by_walls);
  else if (s.engine == Engine::hybrid)
    std::fprintf(out, "built: walls %zu simplices, regions (incremental construction) %zu\n", by_walls,
                 s.region_simplices);
  else if (s.searches_before_handover)
    std::fprintf(out, "built: %s incremental construction %zu simplices (auto handed over after %zu wall searches)\n",
                 s.engine == Engine::cgal ? "CGAL's" : "dewall's", s.simplices, s.searches_before_handover);
  else
    std::fprintf(out, "built: %s incremental construction %zu simplices (no walls)\n",
                 s.engine == Engine::cgal ? "CGAL's" : "dewall's", s.simplices);
  if (walls)
    std::fprintf(out,
                 "walls: first_wall_simplices=%zu recursion_depth=%zu tree_leaves=%zu mean_nodes_per_simplex=%.2f "
                 "candidates_per_search=%.2f\n",
                 s.first_wall_simplices, s.recursion_depth, s.tree_leaves, s.mean_nodes_per_simplex(),
                 s.simplex_searches ? double(s.candidates_tested) / double(s.simplex_searches) : 0.0);
  // The kernel's per-stage counters, in a build configured with
  // -DDEWALL_PREDICATE_STATS=ON (they cost a few per cent, so releases leave
  // them out): which stage decided each evaluation so far in this process.
  if constexpr (kernel::predicate_stats_enabled) {
    const auto& all = kernel::predicate_stats();
    for (int d = 2; d <= 6; ++d) {
      const std::pair<const char*, const kernel::Predicate_stats*> kinds[] = {
          {"orientation", &all.orientation[static_cast<std::size_t>(d)]},
          {"side_of_sphere", &all.side_of_sphere[static_cast<std::size_t>(d)]}};
      for (const auto& [name, p] : kinds)
        if (p->calls())
          std::fprintf(out, "predicate=%s dimension=%d filter=%llu permanent=%llu running_error=%llu interval=%llu exact=%llu "
                       "perturbed=%llu\n",
                       name, d, static_cast<unsigned long long>(p->filter), static_cast<unsigned long long>(p->permanent),
                       static_cast<unsigned long long>(p->running_error), static_cast<unsigned long long>(p->interval),
                       static_cast<unsigned long long>(p->exact), static_cast<unsigned long long>(p->perturbed));
    }
  }
}

namespace {
std::vector<Command>& registry() {
  static std::vector<Command> r;
  return r;
}
}  // namespace

bool register_command(const Command& c) {
  auto& r = registry();
  r.insert(std::upper_bound(r.begin(), r.end(), c,
                            [](const Command& a, const Command& b) { return std::string(a.name) < b.name; }),
           c);
  return true;
}

const std::vector<Command>& commands() { return registry(); }

std::size_t parse_point_count(const std::string& s) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  const bool number = !s.empty() && *end == '\0' && s.find_first_of("xXpP") == std::string::npos;  // no hexadecimal
  if (number && ((errno == ERANGE && v != 0) || (v > 1e12 && v == std::floor(v))))
    throw Usage_error("point count " + io::quoted(s) + " is too large (at most 1e12)");
  if (!number || errno == ERANGE || !(v >= 0) || v != std::floor(v))
    throw Usage_error("invalid point count " + io::quoted(s) + " (a whole number such as 1000 or 1e6)");
  return static_cast<std::size_t>(v);
}

std::uint64_t parse_seed(const std::string& s) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || errno == ERANGE || s[0] == '-' || s[0] == '+')
    throw Usage_error("invalid seed " + io::quoted(s) + " (an integer from 0 to 2^64 - 1)");
  return v;
}

int parse_thread_count(const std::string& text) {
  const long n = parse_long(text, "--threads value");
  if (n < 1 || n > 4096) throw Usage_error("--threads must be 1 to 4096, not " + text);
  return static_cast<int>(n);
}

std::string next_arg(int& i, int argc, char** argv) {
  if (i + 1 >= argc) throw Usage_error(std::string("option ") + argv[i] + " needs a value");
  return argv[++i];
}

long parse_long(const std::string& s, const char* what) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (!s.empty() && *end == '\0' && errno == ERANGE && v > 0)
    throw Usage_error(std::string(what) + " " + io::quoted(s) + " is too large");
  if (s.empty() || *end != '\0' || v < 0 || errno == ERANGE)
    throw Usage_error(std::string("invalid ") + what + ": " + io::quoted(s));
  return v;
}

bool is_option(const std::string& a) {
  return a.size() > 1 && a[0] == '-' && !std::isdigit(static_cast<unsigned char>(a[1])) && a[1] != '.';
}

std::vector<std::string> parse_arguments(int argc, char** argv, std::size_t max_operands,
                                         const std::function<bool(const std::string&, int&)>& option) {
  std::vector<std::string> operands;
  // An option with a value given twice is refused rather than the last one
  // silently winning ("--engine cgal ... --engine dewall"); -o is --output.
  std::map<std::string, std::string> values;
  const auto long_name = [](const std::string& a) { return a == "-o" ? std::string("--output") : a; };
  bool options_ended = false;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (!options_ended && is_option(a)) {
      const int at = i;
      if (a == "--") options_ended = true;
      else if (!option(a, i)) throw Usage_error("unknown option " + io::quoted(a));
      else if (i != at && !values.emplace(long_name(a), argv[i]).second)
        throw Usage_error("option " + long_name(a) + " given twice (" + io::quoted(values[long_name(a)]) + " and " +
                          io::quoted(argv[i]) + ")");
    } else if (operands.size() == max_operands) {
      throw Usage_error("unexpected argument " + io::quoted(a));
    } else {
      operands.push_back(a);
    }
  }
  return operands;
}

std::string input_name(const std::string& path) { return path == "-" ? std::string("<stdin>") : io::file_name(path); }

int report_invalid_input(const std::string& name, const Invalid_input& e, std::size_t first_index) {
  // The point as the file numbers it (the library counts from 0).
  const auto index = e.point_index();
  const std::string message =
      index == Invalid_input::npos ? e.what() : "point " + std::to_string(index + first_index) + " " + e.reason();
  std::fprintf(stderr, "dewall: %s: %s\n", name.c_str(), message.c_str());
  return 1;
}

void check_fits_in_memory(std::size_t n, long dimension) {
  const double bytes = static_cast<double>(n) * static_cast<double>(dimension) * sizeof(double);
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  const double memory = static_cast<double>(pages) * static_cast<double>(page_size);
  if (pages > 0 && page_size > 0 && bytes > memory) {
    char text[160];
    std::snprintf(text, sizeof text, "%zu points in E^%ld need %.1f GB for their coordinates alone; this machine has %.1f GB",
                  n, dimension, bytes / 1e9, memory / 1e9);
    throw std::runtime_error(text);
  }
}

}  // namespace dewall::cli
