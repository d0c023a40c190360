#include <algorithm>
#include <chrono>
#include <span>
#include <vector>

#include "cli.hpp"
#include "dewall/certify/certify.hpp"
#include "dewall/dewall.hpp"

namespace dewall::cli {
namespace {

template <int D>
Run triangulate_table(const io::Point_table& table) {
  const auto points = kernel_points<D>(table);
  Run run;
  run.simplices.vertices_per_simplex = D + 1;
  const auto start = std::chrono::steady_clock::now();
  run.stats = triangulate_to<kernel::Filtered_kernel_d<D>>(
      std::span<const kernel::Point_d<D>>(points),
      [&](const Simplex<D>& s) { run.simplices.indices.insert(run.simplices.indices.end(), s.begin(), s.end()); });
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

template <int D>
certify::Report certify_table(const io::Point_table& points, const io::Simplex_table& table,
                              const certify::Options& options) {
  std::vector<certify::Simplex_indices<D>> s(table.size());
  for (std::size_t r = 0; r < s.size(); ++r)
    for (int j = 0; j <= D; ++j) s[r][static_cast<std::size_t>(j)] = table.indices[r * (D + 1) + static_cast<std::size_t>(j)];
  return certify::certify<kernel::Filtered_kernel_d<D>>(kernel_points<D>(points), s, options);
}

}  // namespace

certify::Report certify_any(const io::Point_table& points, const io::Simplex_table& simplices,
                            const certify::Options& options) {
  return with_dimension(points.dimension, [&](auto d) { return certify_table<d()>(points, simplices, options); });
}

Run triangulate_any(const io::Point_table& table) {
  return with_dimension(table.dimension, [&](auto d) { return triangulate_table<d()>(table); });
}

void print_stats(std::FILE* out, const Run& run) {
  const auto& s = run.stats;
  std::fprintf(out,
               "points=%zu distinct=%zu simplices=%zu first_wall_simplices=%zu recursion_depth=%zu\n"
               "grid_cells=%zu max_points_in_cell=%zu mean_cells_per_simplex=%.2f candidates_per_search=%.2f\n"
               "build_s=%.6f\n",
               s.input_points, s.distinct_points, s.simplices, s.first_wall_simplices, s.recursion_depth,
               s.grid_cells, s.max_points_in_cell, s.mean_cells_per_simplex(),
               s.simplex_searches ? double(s.candidates_tested) / double(s.simplex_searches) : 0.0, run.seconds);
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

std::string next_arg(int& i, int argc, char** argv) {
  if (i + 1 >= argc) throw Usage_error(std::string("option ") + argv[i] + " needs a value");
  return argv[++i];
}

long parse_long(const std::string& s, const char* what) {
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || v < 0) throw Usage_error(std::string("invalid ") + what + ": '" + s + "'");
  return v;
}

}  // namespace dewall::cli
