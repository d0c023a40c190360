// dewall generate KIND N [--dim D] [--seed S] [--noise X] [--planes P] [-o FILE] [--quiet|-q]
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <vector>

#include "cli.hpp"
#include "dewall/io/format_names.hpp"
#include "dewall/io/output_file.hpp"
#include "dewall/io/point_generators.hpp"
#include "dewall/io/progress.hpp"
#include "dewall/io/quote.hpp"

namespace dewall::cli {
namespace {

/// The relative noise of --noise: a finite number in [0, 1].
double parse_noise(const std::string& s) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || errno == ERANGE || !(v >= 0 && v <= 1))
    throw Usage_error("invalid noise " + io::quoted(s) + " (a number from 0 to 1, e.g. 0.05)");
  return v;
}

}  // namespace

int command_generate(int argc, char** argv) {
  std::string output = "-";
  long dim = 3;
  std::uint64_t seed = 0;
  bool seeded = false, quiet = false;
  io::Generator_options shape;
  const auto operands = parse_arguments(
      argc, argv, 2,
      [&](const std::string& a, int& i) {
        if (a == "-o" || a == "--output") output = next_arg(i, argc, argv);
        else if (a == "--dim") dim = parse_long(next_arg(i, argc, argv), "--dim value");
        else if (a == "--seed") seed = parse_seed(next_arg(i, argc, argv)), seeded = true;
        else if (a == "--noise") shape.noise = parse_noise(next_arg(i, argc, argv));
        else if (a == "--planes") shape.planes = static_cast<int>(std::min(parse_long(next_arg(i, argc, argv), "--planes value"), 1001L));
        else if (a == "--quiet" || a == "-q") quiet = true;
        else return false;
        return true;
      });
  if (operands.size() != 2) throw Usage_error("generate needs a KIND and a point count N");
  const auto kind = io::parse_point_kind(operands[0]);
  if (!kind) throw Usage_error("unknown kind " + io::quoted(operands[0]) + " (one of " + io::point_kind_names() + ")");
  const std::size_t n = parse_point_count(operands[1]);
  if (shape.noise != 0 && *kind != io::Point_kind::sphere && *kind != io::Point_kind::torus)
    throw Usage_error(std::string("--noise applies to sphere and torus only, not ") + io::point_kind_name(*kind));
  if (shape.planes != 0 && *kind != io::Point_kind::planes)
    throw Usage_error(std::string("--planes applies to kind planes only, not ") + io::point_kind_name(*kind));
  if (shape.planes != 0 && (shape.planes < 2 || shape.planes > 1000))
    throw Usage_error("--planes must be 2 to 1000, not " + std::to_string(shape.planes) + (shape.planes > 1000 ? " or more" : ""));
  check_dim_option(dim);
  if (io::is_3d_only(*kind) && dim != 3)
    throw Usage_error(std::string("kind ") + io::point_kind_name(*kind) + " is 3D only, not --dim " + std::to_string(dim));
  check_fits_in_memory(n, dim);
  if (io::is_vtk_path(output) && dim > 3)
    throw Usage_error("VTK output supports 2D and 3D only (--dim " + std::to_string(dim) + "); use .dwpt or text");
  io::check_points_output_name(output);  // a name that says another format fails now, not after the work
  io::Output_file::probe(output);
  if (!seeded) {
    // Two draws: random_device yields 32 bits on common platforms.
    std::random_device device;
    seed = (static_cast<std::uint64_t>(device()) << 32) ^ device();
  }
  // The seed is what makes a run reproducible: print it unless the user both
  // chose it and asked for silence.
  if (!(quiet && seeded)) {
    char extra[64] = "";
    if (shape.noise != 0) std::snprintf(extra, sizeof extra, ", noise %g", shape.noise);
    std::fprintf(stderr, "dewall generate: %s, %zu points asked, E^%ld, seed %llu%s\n", io::point_kind_name(*kind), n,
                 dim, static_cast<unsigned long long>(seed), extra);
  }

  io::Progress progress(!quiet && io::stderr_is_terminal());
  io::Point_table table;
  try {
    table = io::generate_points(*kind, n, static_cast<int>(dim), seed, shape, &progress);
  } catch (const std::invalid_argument& e) {
    throw Usage_error(e.what());
  }
  io::write_points_file(output, table, &progress);
  progress.finish();
  if (table.size() != n && !quiet)
    std::fprintf(stderr, "dewall generate: %s made %zu points\n", io::point_kind_name(*kind), table.size());
  return 0;
}

namespace {
const bool registered = register_command({"generate", command_generate,
    "  generate KIND N [--dim D] [--seed S] [--noise X] [--planes P] [-o FILE] [--quiet|-q]\n"
    "      Writes a point set of E^D (D = 2 to 6, default 3): KIND is uniform (unit\n"
    "      cube), ball, sphere (on the unit sphere), bubbles (Gaussian clusters),\n"
    "      grid (integer lattice, about N points), lattice-sphere (integer points on\n"
    "      one sphere, about N, exactly cospherical), planes (on 2 to 8 parallel\n"
    "      hyperplanes), torus (on a torus surface), scan (a simulated range\n"
    "      scan of objects on a table), depth (a depth-camera frame: a few hundred\n"
    "      planes z = c, each a near-regular grid), lidar (an airborne laser scan\n"
    "      in UTM coordinates on a 0.5 m grid, 4% repeated points) or indoor (the\n"
    "      scan's points each repeated 2 to 4 times); the last four are 3D only.\n"
    "      N may be written 1e6.\n"
    "      --noise X (0 to 1, sphere and torus only) moves each point along the\n"
    "      surface normal by X times the radius (sphere: 1, torus: the tube\n"
    "      radius 0.3) times a standard normal deviate.\n"
    "      --planes P (2 to 1000, kind planes only) sets the number of planes\n"
    "      (default about log2(N) / 2, 2 to 8).\n"
    "      The seed (default: random) is printed on stderr. FILE:\n"
    "      plain text (default: standard output), binary when it ends in .dwpt,\n"
    "      TetGen's format when it ends in .node, VTK when it ends in .vtk (2D and\n"
    "      3D); extensions in any case. A name that says a simplex format (.dwsx,\n"
    "      .ele) or one dewall does not write (.ply, .msh, ...) is refused.\n"});
}  // namespace

}  // namespace dewall::cli
