// Nanoseconds per predicate call: our filtered kernel, CGAL's Epick, and a
// plain (inexact) double determinant, in one run on the same inputs.
//
// Each benchmark cycles through 4096 pre-generated point tuples (one call per
// iteration, so the reported time is the time per call) and keeps every result
// alive with DoNotOptimize. Inputs:
//   random   uniform in [0, 1]^D: the filter decides almost always;
//   near     points rounded onto the unit sphere (and, for orientation, onto
//            the plane x_{D-1} = x_0 + … ): nearly degenerate, the static filter
//            often fails and the next stage decides;
//   ulp      exactly degenerate integer sets (cospherical, resp. on a
//            hyperplane) with one coordinate moved by one ulp: only exact
//            arithmetic decides.
// Run: ./build/bench/bench_predicates --benchmark_min_time=0.2 (see README.md).
#include <benchmark/benchmark.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/side_of_sphere.hpp"
#include "support/point_generators.hpp"

namespace {

using namespace dewall::kernel;
using dewall::test::Rng;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

constexpr std::size_t tuple_count = 4096;  // a power of two: the index wraps with a mask

enum class Input { random, near, ulp };

/// `tuple_count` tuples of N points in E^D, flat: tuple t is points[t*N … t*N+N-1].
template <int D, int N>
std::vector<Point_d<D>> make_tuples(Input input) {
  Rng rng(0xbe9c + static_cast<unsigned>(input) * 131 + D * 17 + N);
  std::vector<Point_d<D>> out;
  out.reserve(tuple_count * N);
  while (out.size() < tuple_count * N) {
    std::vector<Point_d<D>> t;
    switch (input) {
      case Input::random:
        t = dewall::test::uniform_points<D>(rng, N, 0, 1);
        break;
      case Input::near:
        t = dewall::test::uniform_points<D>(rng, N, -1, 1);
        for (auto& p : t) {
          double r2 = 0;
          for (int j = 0; j < D; ++j) r2 += p[j] * p[j];
          const double r = std::sqrt(r2);
          for (int j = 0; j < D; ++j) p[j] /= r;
          if (N == D + 1) {  // orientation: onto a hyperplane instead, rounded
            double s = 0;
            for (int j = 0; j + 1 < D; ++j) s += p[j] * (0.1 + 0.3 * j);
            p[D - 1] = s;
          }
        }
        break;
      case Input::ulp:
        t = N == D + 2 ? dewall::test::cospherical_integer_points<D>(rng, N)
                       : dewall::test::flat_integer_points<D>(rng, N, D - 1);
        dewall::test::nudge_ulps<D>(rng, t, 1);
        break;
    }
    if (t.size() == static_cast<std::size_t>(N)) out.insert(out.end(), t.begin(), t.end());
  }
  return out;
}

template <int D, int N>
const std::vector<Point_d<D>>& tuples(Input input) {
  static const std::array<std::vector<Point_d<D>>, 3> all = {make_tuples<D, N>(Input::random),
                                                             make_tuples<D, N>(Input::near),
                                                             make_tuples<D, N>(Input::ulp)};
  return all[static_cast<std::size_t>(input)];
}

template <int D>
auto to_epick(const Point_d<D>& p) {
  if constexpr (D == 2) return Epick::Point_2(p[0], p[1]);
  else return Epick::Point_3(p[0], p[1], p[2]);
}

template <int D, int N>
std::vector<decltype(to_epick<D>(Point_d<D>{}))> epick_tuples(Input input) {
  std::vector<decltype(to_epick<D>(Point_d<D>{}))> out;
  for (const auto& p : tuples<D, N>(input)) out.push_back(to_epick<D>(p));
  return out;
}

// ------------------------------------------------------------------ plain doubles

/// The same determinants as the kernel's, in double, no error control.
template <int D>
double plain_orientation(const Point_d<D>* p) {
  if constexpr (D == 2) {
    const double ax = p[1][0] - p[0][0], ay = p[1][1] - p[0][1];
    const double bx = p[2][0] - p[0][0], by = p[2][1] - p[0][1];
    return ax * by - ay * bx;
  } else {
    double m[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = p[i + 1][j] - p[0][j];
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
}

template <int D>
double plain_side_of_sphere(const Point_d<D>* p) {
  const Point_d<D>& q = p[D + 1];
  if constexpr (D == 2) {
    double m[3][3];
    for (int i = 0; i < 3; ++i) {
      m[i][0] = p[i][0] - q[0];
      m[i][1] = p[i][1] - q[1];
      m[i][2] = m[i][0] * m[i][0] + m[i][1] * m[i][1];
    }
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  } else {
    double m[4][4];
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 3; ++j) m[i][j] = p[i][j] - q[j];
      m[i][3] = m[i][0] * m[i][0] + m[i][1] * m[i][1] + m[i][2] * m[i][2];
    }
    // Laplace along the first two rows (2×2 minors), as in Shewchuk's insphere.
    const double a01 = m[0][0] * m[1][1] - m[0][1] * m[1][0], a02 = m[0][0] * m[1][2] - m[0][2] * m[1][0];
    const double a03 = m[0][0] * m[1][3] - m[0][3] * m[1][0], a12 = m[0][1] * m[1][2] - m[0][2] * m[1][1];
    const double a13 = m[0][1] * m[1][3] - m[0][3] * m[1][1], a23 = m[0][2] * m[1][3] - m[0][3] * m[1][2];
    const double b01 = m[2][0] * m[3][1] - m[2][1] * m[3][0], b02 = m[2][0] * m[3][2] - m[2][2] * m[3][0];
    const double b03 = m[2][0] * m[3][3] - m[2][3] * m[3][0], b12 = m[2][1] * m[3][2] - m[2][2] * m[3][1];
    const double b13 = m[2][1] * m[3][3] - m[2][3] * m[3][1], b23 = m[2][2] * m[3][3] - m[2][3] * m[3][2];
    return a01 * b23 - a02 * b13 + a03 * b12 + a12 * b03 - a13 * b02 + a23 * b01;
  }
}

// ------------------------------------------------------------------ benchmarks

template <int D>
void ours_orientation(benchmark::State& state, Input input) {
  const auto& pts = tuples<D, D + 1>(input);
  std::size_t t = 0;
  for (auto _ : state) {
    const Point_d<D>* p = &pts[t * (D + 1)];
    Orientation_points<D> refs;
    for (int i = 0; i <= D; ++i) refs[static_cast<std::size_t>(i)] = p + i;
    benchmark::DoNotOptimize(orientation_d<D>(refs));
    t = (t + 1) & (tuple_count - 1);
  }
}

template <int D>
void ours_side_of_sphere(benchmark::State& state, Input input) {
  const auto& pts = tuples<D, D + 2>(input);
  std::size_t t = 0;
  for (auto _ : state) {
    const Point_d<D>* p = &pts[t * (D + 2)];
    Sphere_points<D> refs;
    for (int i = 0; i <= D + 1; ++i) refs[static_cast<std::size_t>(i)] = p + i;
    benchmark::DoNotOptimize(side_of_oriented_sphere_d<D>(refs));
    t = (t + 1) & (tuple_count - 1);
  }
}

template <int D>
void cgal_orientation(benchmark::State& state, Input input) {
  const auto pts = epick_tuples<D, D + 1>(input);
  std::size_t t = 0;
  for (auto _ : state) {
    const auto* p = &pts[t * (D + 1)];
    if constexpr (D == 2) benchmark::DoNotOptimize(Epick().orientation_2_object()(p[0], p[1], p[2]));
    else benchmark::DoNotOptimize(Epick().orientation_3_object()(p[0], p[1], p[2], p[3]));
    t = (t + 1) & (tuple_count - 1);
  }
}

template <int D>
void cgal_side_of_sphere(benchmark::State& state, Input input) {
  const auto pts = epick_tuples<D, D + 2>(input);
  std::size_t t = 0;
  for (auto _ : state) {
    const auto* p = &pts[t * (D + 2)];
    if constexpr (D == 2) benchmark::DoNotOptimize(Epick().side_of_oriented_circle_2_object()(p[0], p[1], p[2], p[3]));
    else benchmark::DoNotOptimize(Epick().side_of_oriented_sphere_3_object()(p[0], p[1], p[2], p[3], p[4]));
    t = (t + 1) & (tuple_count - 1);
  }
}

template <int D>
void plain_orientation_bench(benchmark::State& state, Input input) {
  const auto& pts = tuples<D, D + 1>(input);
  std::size_t t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(plain_orientation<D>(&pts[t * (D + 1)]) > 0);
    t = (t + 1) & (tuple_count - 1);
  }
}

template <int D>
void plain_side_of_sphere_bench(benchmark::State& state, Input input) {
  const auto& pts = tuples<D, D + 2>(input);
  std::size_t t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(plain_side_of_sphere<D>(&pts[t * (D + 2)]) > 0);
    t = (t + 1) & (tuple_count - 1);
  }
}

using Bench = void (*)(benchmark::State&, Input);

/// Registers fn on the three inputs as "<name>/<input>".
void register_all_inputs(const std::string& name, Bench fn) {
  const std::pair<const char*, Input> inputs[] = {{"random", Input::random}, {"near", Input::near}, {"ulp", Input::ulp}};
  for (const auto& [input_name, input] : inputs)
    benchmark::RegisterBenchmark((name + "/" + input_name).c_str(), fn, input);
}

}  // namespace

int main(int argc, char** argv) {
  register_all_inputs("orientation_2d/ours", ours_orientation<2>);
  register_all_inputs("orientation_2d/epick", cgal_orientation<2>);
  register_all_inputs("orientation_2d/plain_double", plain_orientation_bench<2>);
  register_all_inputs("side_of_sphere_2d/ours", ours_side_of_sphere<2>);
  register_all_inputs("side_of_sphere_2d/epick", cgal_side_of_sphere<2>);
  register_all_inputs("side_of_sphere_2d/plain_double", plain_side_of_sphere_bench<2>);
  register_all_inputs("orientation_3d/ours", ours_orientation<3>);
  register_all_inputs("orientation_3d/epick", cgal_orientation<3>);
  register_all_inputs("orientation_3d/plain_double", plain_orientation_bench<3>);
  register_all_inputs("side_of_sphere_3d/ours", ours_side_of_sphere<3>);
  register_all_inputs("side_of_sphere_3d/epick", cgal_side_of_sphere<3>);
  register_all_inputs("side_of_sphere_3d/plain_double", plain_side_of_sphere_bench<3>);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
