// dewall._dewall: the compiled half of the Python package (python/dewall/ is
// the other). Thin: it checks array types, views NumPy memory as the library's
// points without copying, releases the GIL, and calls the library — the
// triangulator (dewall.hpp), the certifier, neighbors and locate, the point
// generators. No CGAL header here (the library holds the compiled CGAL engine).
//
// Arrays in: C-contiguous float64 of shape (n, D), exactly; the Python layer
// (python/dewall/_arrays.py) converts anything else once, exactly, or refuses.
// Arrays out: views of the library's own vectors (a capsule or the owning
// Python object keeps them alive), read-only where later calls rely on them.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <chrono>
#include <cstring>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "dewall/certify/certify.hpp"
#include "dewall/certify/neighbors.hpp"
#include "dewall/dewall.hpp"
#include "dewall/error.hpp"
#include "dewall/io/point_generators.hpp"
#include "dewall/kernel/dimension.hpp"
#include "dewall/kernel/first_occurrence.hpp"
#include "dewall/locate.hpp"
#include "convex_hull.hpp"
#include "high_dimension.hpp"
#include "voronoi.hpp"
#include "watched.hpp"

namespace py = pybind11;

namespace {

using dewall_python::Watch;
using dewall_python::watched;

/// Queries (locate) and simplices (the module's own loops) per block between
/// two polls of a watched call: a few milliseconds of work.
constexpr std::size_t poll_block = std::size_t{1} << 14;

using dewall::kernel::Point_d;
template <int D>
using Kernel = dewall::kernel::Filtered_kernel_d<D>;

// NumPy's int32 (scipy's index type) holds every index below 2^31.
constexpr std::size_t max_index = std::numeric_limits<std::int32_t>::max();

/// The element types the module takes: NumPy's kind character and item size.
struct Element_type {
  char kind;
  py::ssize_t size;
  const char* name;
};
constexpr Element_type float64{'f', 8, "float64"};
constexpr Element_type uint32{'u', 4, "uint32"};

/// `h` as a C-contiguous 2-D array of `type` with `columns` columns (any
/// number when columns < 0). \throws TypeError otherwise: the Python layer
/// converts, so this guards only direct callers of _dewall.
py::array checked(py::handle h, Element_type type, long columns, const char* what) {
  if (!py::isinstance<py::array>(h)) throw py::type_error(std::string(what) + " must be a NumPy array");
  auto a = py::reinterpret_borrow<py::array>(h);
  if (a.dtype().kind() != type.kind || a.dtype().itemsize() != type.size)
    throw py::type_error(std::string(what) + " must have dtype " + type.name);
  if (a.ndim() != 2 || (columns >= 0 && a.shape(1) != columns))
    throw py::type_error(std::string(what) + " must be a 2-D array" +
                         (columns >= 0 ? " with " + std::to_string(columns) + " columns" : std::string()));
  if (!(a.flags() & py::array::c_style)) throw py::type_error(std::string(what) + " must be C-contiguous");
  return a;
}

/// The rows of a checked float64 array as points, in place. Point_d<D> is D
/// doubles and nothing else (static_asserts), the layout of a C-contiguous row.
template <int D>
std::span<const Point_d<D>> as_points(const py::array& a) {
  static_assert(sizeof(Point_d<D>) == D * sizeof(double) && alignof(Point_d<D>) == alignof(double) &&
                std::is_standard_layout_v<Point_d<D>> && std::is_trivially_copyable_v<Point_d<D>>);
  return {reinterpret_cast<const Point_d<D>*>(a.data()), static_cast<std::size_t>(a.shape(0))};
}

/// A NumPy array over a vector's memory, the vector moved into the capsule
/// that owns it (no copy). `Element` is the NumPy element type: it may
/// reinterpret T's integers (uint32 → int32 when every value is below 2^31).
template <class Element, class T>
py::array adopt(std::vector<T>&& v, std::vector<py::ssize_t> shape) {
  static_assert(sizeof(T) % sizeof(Element) == 0);
  auto* owner = new std::vector<T>(std::move(v));
  py::capsule free_when_done(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<Element>(shape, reinterpret_cast<const Element*>(owner->data()), free_when_done);
}

/// A read-only int32 view of `data` whose base is `owner`.
template <class T>
py::array view_int32(const T* data, py::ssize_t rows, py::ssize_t columns, py::handle owner) {
  static_assert(sizeof(T) == static_cast<std::size_t>(sizeof(std::int32_t)) * T{}.size());
  py::array a = py::array_t<std::int32_t>({rows, columns}, reinterpret_cast<const std::int32_t*>(data), owner);
  a.attr("flags").attr("writeable") = false;
  return a;
}

py::dict statistics_dict(const dewall::Statistics& s, double seconds) {
  py::dict d;
  d["engine"] = dewall::engine_name(s.engine);
  d["input_points"] = s.input_points;
  d["distinct_points"] = s.distinct_points;
  d["simplices"] = s.simplices;
  d["first_wall_simplices"] = s.first_wall_simplices;
  d["recursion_depth"] = s.recursion_depth;
  d["simplex_searches"] = s.simplex_searches;
  d["candidates_tested"] = s.candidates_tested;
  d["tree_leaves"] = s.tree_leaves;
  d["searches_before_handover"] = s.searches_before_handover;
  d["region_simplices"] = s.region_simplices;
  d["build_seconds"] = seconds;
  return d;
}

/// One row of scipy's transform array; defined with barycentric_transforms below.
void transform_row(const double* x, const std::uint32_t* index, std::size_t width, double rcond_limit, double* o);

/// The rows of a compressed table (row r: values[start[r] .. start[r + 1])) as a list of lists
/// of ints, scipy's layout for Voronoi ridges and regions. Values are >= −1; each distinct
/// value's int object is made once and shared (ints are immutable): fewer allocations.
py::list nested_lists(const std::vector<std::size_t>& start, const std::vector<std::int32_t>& values) {
  const std::int32_t largest = values.empty() ? -1 : *std::max_element(values.begin(), values.end());
  std::vector<py::object> ints(static_cast<std::size_t>(largest) + 2);
  py::list out(start.size() - 1);
  for (std::size_t r = 0; r + 1 < start.size(); ++r) {
    PyObject* row = PyList_New(static_cast<py::ssize_t>(start[r + 1] - start[r]));
    if (!row) throw py::error_already_set();
    for (std::size_t k = start[r]; k < start[r + 1]; ++k) {
      py::object& value = ints[static_cast<std::size_t>(values[k] + 1)];
      if (!value) value = py::int_(values[k]);
      PyList_SET_ITEM(row, static_cast<py::ssize_t>(k - start[r]), value.inc_ref().ptr());
    }
    PyList_SET_ITEM(out.ptr(), static_cast<py::ssize_t>(r), row);
  }
  return out;
}

/// A triangulation of one dimension: simplices, and the neighbors once asked.
template <int D>
struct Cells {
  static constexpr int dimension = D;
  std::vector<dewall::Simplex<D>> simplices;
  std::vector<std::array<std::int32_t, D + 1>> neighbors;
  bool have_neighbors = false;
};

/// What dewall.Delaunay wraps: the points (the caller's array, not copied:
/// kept alive here), the simplices and, on demand, the neighbors.
class Triangulation {
 public:
  using Any_cells = std::variant<Cells<2>, Cells<3>, Cells<4>, Cells<5>, Cells<6>>;
  Triangulation(py::array points, Any_cells cells, dewall::Statistics stats, double seconds)
      : points_(std::move(points)), cells_(std::move(cells)), stats_(stats), seconds_(seconds) {}

  int dimension() const { return static_cast<int>(points_.shape(1)); }
  py::dict statistics() const { return statistics_dict(stats_, seconds_); }

  py::array simplices(py::handle self) const {
    return std::visit([&](const auto& c) {
      return view_int32(c.simplices.data(), static_cast<py::ssize_t>(c.simplices.size()),
                        static_cast<py::ssize_t>(dimension() + 1), self);
    }, cells_);
  }

  py::array neighbors(py::handle self) {
    return std::visit([&](auto& c) {
      compute_neighbors(c);
      return view_int32(c.neighbors.data(), static_cast<py::ssize_t>(c.neighbors.size()),
                        static_cast<py::ssize_t>(dimension() + 1), self);
    }, cells_);
  }

  /// The simplex containing each query row (exact), −1 outside.
  py::array locate(py::handle queries) {
    return std::visit([&](auto& c) {
      constexpr int D = std::decay_t<decltype(c)>::dimension;
      const py::array q = checked(queries, float64, D, "xi");
      compute_neighbors(c);
      py::array_t<std::int32_t> out(q.shape(0));
      std::span<std::int32_t> result(out.mutable_data(), static_cast<std::size_t>(q.shape(0)));
      const auto xi = as_points<D>(q);
      watched(xi.size(), py::none(), [&](Watch& watch) {
        watch.blocks(xi.size(), poll_block, [&](std::size_t first, std::size_t last) {
          dewall::locate_all<Kernel<D>>({}, as_points<D>(points_), std::span<const dewall::Simplex<D>>(c.simplices),
                                        std::span<const std::array<std::int32_t, D + 1>>(c.neighbors),
                                        xi.subspan(first, last - first), result.subspan(first, last - first));
        });
      });
      return py::array(out);
    }, cells_);
  }

  /// locate() and, in 2D and 3D, each query's barycentric coordinates in the simplex found,
  /// from that simplex's row of scipy's transform (transform_row: the same numbers as
  /// Delaunay.transform, without computing the rows no query needs): (simplices,
  /// weights (q, D + 1)); rows of −1 and NaN transforms get NaN weights.
  py::tuple locate_weights(py::handle queries, double rcond_limit) {
    return std::visit([&](auto& c) -> py::tuple {
      constexpr int D = std::decay_t<decltype(c)>::dimension;
      if constexpr (D > 3) {
        throw py::value_error("locate_weights: points of 2 or 3 dimensions");
      } else {
        const py::array q = checked(queries, float64, D, "xi");
        compute_neighbors(c);
        const auto count = static_cast<std::size_t>(q.shape(0));
        py::array_t<std::int32_t> found(q.shape(0));
        py::array_t<double> weights({q.shape(0), static_cast<py::ssize_t>(D + 1)});
        std::span<std::int32_t> result(found.mutable_data(), count);
        double* w = weights.mutable_data();
        const auto* x = static_cast<const double*>(points_.data());
        const auto* xi = static_cast<const double*>(q.data());
        watched(count, py::none(), [&](Watch& watch) {
          watch.blocks(count, poll_block, [&](std::size_t first, std::size_t last) {
            dewall::locate_all<Kernel<D>>({}, as_points<D>(points_), std::span<const dewall::Simplex<D>>(c.simplices),
                                          std::span<const std::array<std::int32_t, D + 1>>(c.neighbors),
                                          as_points<D>(q).subspan(first, last - first),
                                          result.subspan(first, last - first));
          });
          for (std::size_t i = 0; i < count; ++i, w += D + 1, xi += D) {
            if (i % poll_block == 0) watch.poll();
            if (result[i] < 0) {
              for (int j = 0; j <= D; ++j) w[j] = NAN;
              continue;
            }
            double t[(D + 1) * D];
            transform_row(x, c.simplices[static_cast<std::size_t>(result[i])].data(), D, rcond_limit, t);
            double total = 0;
            for (int j = 0; j < D; ++j) {  // c = T⁻¹ (x − r), c_D = 1 − Σ c, as _delaunay.barycentric
              double sum = 0;
              for (int k = 0; k < D; ++k) sum += t[j * D + k] * (xi[k] - t[D * D + k]);
              w[j] = sum;
              total += sum;
            }
            w[D] = 1 - total;
          }
        });
        return py::make_tuple(found, weights);
      }
    }, cells_);
  }

  /// The pairs (i, n), i < n, of neighbouring simplices with one circumsphere:
  /// the vertex of n opposite their shared facet lies exactly on the sphere of
  /// i (the unperturbed test is ZERO). Voronoi merges such simplices into one
  /// vertex, as the diagram of the unperturbed points has.
  py::array cospherical_neighbours() {
    return std::visit([&](auto& c) {
      constexpr int D = std::decay_t<decltype(c)>::dimension;
      compute_neighbors(c);
      std::vector<std::array<std::int32_t, 2>> pairs;
      watched(c.simplices.size(), py::none(), [&](Watch& watch) {
        const auto points = as_points<D>(points_);
        const auto sphere = Kernel<D>{}.side_of_oriented_sphere_unperturbed_d_object();
        for (std::size_t i = 0; i < c.simplices.size(); ++i) {
          if (i % poll_block == 0) watch.report(static_cast<double>(i) / static_cast<double>(c.simplices.size()));
          for (int j = 0; j <= D; ++j) {
            const std::int32_t n = c.neighbors[i][static_cast<std::size_t>(j)];
            if (n < 0 || static_cast<std::size_t>(n) < i) continue;
            // the vertex of n that is not in simplex i: the one whose neighbour is i
            std::size_t opposite = 0;
            for (int k = 0; k <= D; ++k)
              if (c.neighbors[static_cast<std::size_t>(n)][static_cast<std::size_t>(k)] == static_cast<std::int32_t>(i))
                opposite = c.simplices[static_cast<std::size_t>(n)][static_cast<std::size_t>(k)];
            std::array<const Point_d<D>*, D + 2> s;
            for (int k = 0; k <= D; ++k) s[static_cast<std::size_t>(k)] = &points[c.simplices[i][static_cast<std::size_t>(k)]];
            s[D + 1] = &points[opposite];
            if (sphere(s) == dewall::kernel::ON_ORIENTED_BOUNDARY) pairs.push_back({static_cast<std::int32_t>(i), n});
          }
        }
      });
      const auto rows = static_cast<py::ssize_t>(pairs.size());
      return adopt<std::int32_t>(std::move(pairs), {rows, 2});
    }, cells_);
  }

  /// Voronoi ridges and regions (voronoi.hpp) over `group`, one Voronoi vertex per simplex
  /// (int32, one per simplex): (ridge_points (r, 2) int32, ridge_vertices, regions), the
  /// last two lists of lists (regions: one per point, [] for a point in no simplex).
  py::tuple voronoi(py::handle group_in) {
    return std::visit([&](auto& c) {
      constexpr int D = std::decay_t<decltype(c)>::dimension;
      if (!py::isinstance<py::array>(group_in)) throw py::type_error("group must be a NumPy array");
      const auto group = py::reinterpret_borrow<py::array>(group_in);
      if (group.dtype().kind() != 'i' || group.dtype().itemsize() != 4 || group.ndim() != 1 ||
          !(group.flags() & py::array::c_style) || static_cast<std::size_t>(group.shape(0)) != c.simplices.size())
        throw py::type_error("group must be a C-contiguous int32 array with one entry per simplex");
      const std::span<const std::int32_t> groups(static_cast<const std::int32_t*>(group.data()), c.simplices.size());
      for (const std::int32_t g : groups)
        if (g < 0) throw py::value_error("group: negative index");
      compute_neighbors(c);
      dewall_python::Voronoi_topology t = watched(c.simplices.size(), py::none(), [&](Watch& watch) {
        return dewall_python::voronoi_topology<D>(static_cast<std::size_t>(points_.shape(0)),
                                                  std::span<const std::array<std::uint32_t, D + 1>>(c.simplices),
                                                  std::span<const std::array<std::int32_t, D + 1>>(c.neighbors), groups,
                                                  [&] { watch.poll(); });
      });
      const auto rows = static_cast<py::ssize_t>(t.ridge_points.size());
      py::list regions = nested_lists(t.region_start, t.region_vertices);
      py::list ridges = nested_lists(t.ridge_start, t.ridge_vertices);
      return py::make_tuple(adopt<std::int32_t>(std::move(t.ridge_points), {rows, 2}), ridges, regions);
    }, cells_);
  }

  /// For each input point, the input index of the vertex that stands for it
  /// (itself unless it duplicates an earlier point).
  py::array first_occurrences() const {
    return dewall::kernel::with_dimension(dimension(), [&](auto d) {
      std::vector<std::uint32_t> first;
      {
        py::gil_scoped_release release;  // comparisons are on the bits: no floating-point environment needed
        const Kernel<d()> k;
        first = dewall::kernel::first_occurrences(as_points<d()>(points_), k.compare_lexicographically_d_object(),
                                                  k.approximate_coordinates_object());
      }
      const auto n = static_cast<py::ssize_t>(first.size());
      return adopt<std::int32_t>(std::move(first), {n});
    });
  }

 private:
  template <int D>
  void compute_neighbors(Cells<D>& c) {
    if (c.simplices.size() > max_index) throw py::value_error("more than 2^31 - 1 simplices: neighbors need int64");
    // Two Python threads may ask at once. The GIL goes first (watched
    // releases it): waiting for the mutex while holding it would deadlock
    // with the thread that computes.
    watched(c.simplices.size(), py::none(), [&](Watch& watch) {
      const std::lock_guard lock(mutex_);
      if (c.have_neighbors) return;
      try {
        c.neighbors.resize(c.simplices.size());
        dewall::certify::neighbors<D, std::int32_t>(static_cast<std::size_t>(points_.shape(0)),
                                                    std::span<const dewall::Simplex<D>>(c.simplices),
                                                    std::span<std::array<std::int32_t, D + 1>>(c.neighbors),
                                                    [&](double fraction) { watch.report(fraction); });
      } catch (...) {
        std::vector<std::array<std::int32_t, D + 1>>().swap(c.neighbors);  // stopped: what was built goes
        throw;
      }
      c.have_neighbors = true;
    });
  }

  py::array points_;
  Any_cells cells_;
  dewall::Statistics stats_;
  double seconds_;
  std::mutex mutex_;
};

std::unique_ptr<Triangulation> triangulate(py::handle points_in, const std::string& engine,
                                           std::optional<int> threads, const py::object& progress) {
  py::array points = checked(points_in, float64, -1, "points");
  const auto e = dewall::parse_engine(engine);
  if (!e) throw py::value_error("unknown engine '" + engine + "' (" + dewall::engine_choices + ")");
  if (static_cast<std::size_t>(points.shape(0)) > max_index)
    throw py::value_error("more than 2^31 - 1 points (the indices are int32, as scipy's)");
  dewall::Options options;
  options.engine = *e;
  if (threads) {
    if (*threads < 1) throw py::value_error("threads must be at least 1, not " + std::to_string(*threads));
    options.threads = *threads;
  }
  return dewall::kernel::with_dimension(static_cast<int>(points.shape(1)), [&](auto d) {
    constexpr int D = d();
    const auto view = as_points<D>(points);
    dewall::Triangulation<D> t;
    double seconds = 0;
    watched(view.size(), progress, [&](Watch& watch) {  // other Python threads run meanwhile
      const auto start = std::chrono::steady_clock::now();
      dewall::Options watched_options = options;
      watched_options.progress = watch.library_hook();
      t = dewall::triangulate<Kernel<D>>(view, watched_options);
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    });
    Cells<D> cells;
    cells.simplices = std::move(t.simplices);
    return std::make_unique<Triangulation>(points, std::move(cells), t.statistics, seconds);
  });
}

/// A Triangulation over stored simplices (unpickling): no triangulation is
/// run. The rows must be a previous result for these points (dewall.Delaunay
/// pickles its own); indices are checked, the rest is trusted, as locate's
/// walk needs only valid indices to terminate (it falls back to a full scan).
std::unique_ptr<Triangulation> from_simplices(py::handle points_in, py::handle simplices_in) {
  py::array points = checked(points_in, float64, -1, "points");
  const long d = static_cast<long>(points.shape(1));
  const py::array simplices = checked(simplices_in, uint32, d + 1, "simplices");
  const auto n = static_cast<std::uint32_t>(points.shape(0));
  const auto* first = static_cast<const std::uint32_t*>(simplices.data());
  const auto count = static_cast<std::size_t>(simplices.shape(0));
  for (std::size_t i = 0; i < count * static_cast<std::size_t>(d + 1); ++i)
    if (first[i] >= n) throw py::value_error("simplices: index " + std::to_string(first[i]) + " is not a point index");
  return dewall::kernel::with_dimension(static_cast<int>(d), [&](auto dim) {
    constexpr int D = dim();
    Cells<D> cells;
    cells.simplices.resize(count);
    static_assert(sizeof(dewall::Simplex<D>) == (D + 1) * sizeof(std::uint32_t));
    std::memcpy(cells.simplices.data(), first, count * sizeof(dewall::Simplex<D>));
    return std::make_unique<Triangulation>(points, std::move(cells), dewall::Statistics{}, 0.0);
  });
}

/// One row of scipy's transform array (Delaunay.transform) in 2D and 3D: for the
/// simplex with vertex indices `index` (width + 1 of them) of the points `x`,
/// writes T⁻¹ (width × width) then r (width) to `o`; NaN throughout under
/// scipy's rule. The formulas of the Python fallback
/// (_delaunay.barycentric_transforms; its docstring has the layout and the rule).
void transform_row(const double* x, const std::uint32_t* index, std::size_t width, double rcond_limit, double* o) {
  const double* r = x + index[width] * width;
  double e[3][3] = {};  // e[j]: column j of T, vertex j − r
  for (std::size_t j = 0; j < width; ++j)
    for (std::size_t k = 0; k < width; ++k) e[j][k] = x[index[j] * width + k] - r[k];
  double inverse[3][3] = {}, det;
  if (width == 2) {  // T = [[a, b], [c, f]], columns (a, c) and (b, f)
    const double a = e[0][0], c = e[0][1], b = e[1][0], f = e[1][1];
    det = a * f - b * c;
    inverse[0][0] = f, inverse[0][1] = -b, inverse[1][0] = -c, inverse[1][1] = a;
  } else {  // row i of the adjugate: the cross product of the other two columns
    constexpr int other[3][2] = {{1, 2}, {2, 0}, {0, 1}};
    for (int i = 0; i < 3; ++i) {
      const double* u = e[other[i][0]];
      const double* v = e[other[i][1]];
      inverse[i][0] = u[1] * v[2] - u[2] * v[1];
      inverse[i][1] = u[2] * v[0] - u[0] * v[2];
      inverse[i][2] = u[0] * v[1] - u[1] * v[0];
    }
    det = e[0][0] * inverse[0][0] + e[0][1] * inverse[0][1] + e[0][2] * inverse[0][2];
  }
  // The reciprocal condition number in the 1-norm (largest column sum), as scipy's rule.
  double norm = 0, inverse_norm = 0;
  for (std::size_t j = 0; j < width; ++j) {
    double column = 0, inverse_column = 0;
    for (std::size_t k = 0; k < width; ++k) {
      column += std::fabs(e[j][k]);
      inverse[k][j] /= det;
      inverse_column += std::fabs(inverse[k][j]);
    }
    norm = std::max(norm, column);
    inverse_norm = std::max(inverse_norm, inverse_column);
  }
  const double rcond = 1 / (norm * inverse_norm);
  const bool bad = !(std::fabs(det) > 0) || !(rcond >= rcond_limit);
  for (std::size_t i = 0; i < width; ++i)
    for (std::size_t k = 0; k < width; ++k) o[i * width + k] = bad ? NAN : inverse[i][k];
  for (std::size_t k = 0; k < width; ++k) o[width * width + k] = bad ? NAN : r[k];
}

/// `simplices_in` as uint32 rows of d + 1 indices of `points`.
/// \throws ValueError for an index that is no point's.
py::array checked_simplices(py::handle simplices_in, const py::array& points, long d) {
  py::array simplices = checked(simplices_in, uint32, d + 1, "simplices");
  const auto n = static_cast<std::uint32_t>(points.shape(0));
  const auto* index = static_cast<const std::uint32_t*>(simplices.data());
  const auto size = static_cast<std::size_t>(simplices.shape(0)) * static_cast<std::size_t>(d + 1);
  for (std::size_t i = 0; i < size; ++i)
    if (index[i] >= n) throw py::value_error("simplices: index " + std::to_string(index[i]) + " is not a point index");
  return simplices;
}

/// scipy's transform array (Delaunay.transform) in 2D and 3D, in one pass
/// instead of a dozen NumPy temporaries (10^5 points in 3D: most of build +
/// neighbors + transform).
py::array barycentric_transforms(py::handle points_in, py::handle simplices_in, double rcond_limit) {
  const py::array points = checked(points_in, float64, -1, "points");
  const long d = static_cast<long>(points.shape(1));
  if (d != 2 && d != 3) throw py::value_error("barycentric_transforms: points of 2 or 3 dimensions");
  const py::array simplices = checked_simplices(simplices_in, points, d);
  const auto count = static_cast<std::size_t>(simplices.shape(0));
  const auto* index = static_cast<const std::uint32_t*>(simplices.data());
  const auto* x = static_cast<const double*>(points.data());
  py::array_t<double> out({static_cast<py::ssize_t>(count), static_cast<py::ssize_t>(d + 1), static_cast<py::ssize_t>(d)});
  double* o = out.mutable_data();
  const auto width = static_cast<std::size_t>(d);
  const auto rows = static_cast<std::size_t>(d + 1);
  watched(count, py::none(), [&](Watch& watch) {
    watch.blocks(count, poll_block, [&](std::size_t first, std::size_t last) {
      for (std::size_t s = first; s < last; ++s) transform_row(x, index + s * rows, width, rcond_limit, o + s * rows * width);
    });
  });
  return out;
}

/// voronoi.hpp's merge_groups over `pairs` ((k, 2) int32 simplex indices < count): int32 groups.
py::array merge_groups(std::size_t count, py::handle pairs_in) {
  const Element_type int32{'i', 4, "int32"};
  const py::array pairs = checked(pairs_in, int32, 2, "pairs");
  const auto* p = static_cast<const std::int32_t*>(pairs.data());
  const auto k = static_cast<std::size_t>(pairs.shape(0));
  if (count > max_index) throw py::value_error("more than 2^31 - 1 simplices");
  for (std::size_t i = 0; i < 2 * k; ++i)
    if (p[i] < 0 || static_cast<std::size_t>(p[i]) >= count) throw py::value_error("pairs: an index out of range");
  std::vector<std::int32_t> group;
  {
    py::gil_scoped_release release;
    group = dewall_python::merge_groups(count, std::span<const std::array<std::int32_t, 2>>(
                                                   reinterpret_cast<const std::array<std::int32_t, 2>*>(p), k));
  }
  const auto n = static_cast<py::ssize_t>(group.size());
  return adopt<std::int32_t>(std::move(group), {n});
}

/// The circumcentre of each row of `simplices` (uint32, ndim + 1 columns), floating point
/// (voronoi.hpp's circumcentres), for dewall.Voronoi's vertices; 2 … 6 dimensions.
py::array circumcentres(py::handle points_in, py::handle simplices_in) {
  const py::array points = checked(points_in, float64, -1, "points");
  const long d = static_cast<long>(points.shape(1));
  const py::array simplices = checked_simplices(simplices_in, points, d);
  const auto count = static_cast<std::size_t>(simplices.shape(0));
  const auto* index = static_cast<const std::uint32_t*>(simplices.data());
  py::array_t<double> out({static_cast<py::ssize_t>(count), static_cast<py::ssize_t>(d)});
  double* o = out.mutable_data();
  dewall::kernel::with_dimension(static_cast<int>(d), [&](auto dim) {
    constexpr int D = dim();
    const std::span<const std::array<std::uint32_t, D + 1>> rows(
        reinterpret_cast<const std::array<std::uint32_t, D + 1>*>(index), count);
    watched(count, py::none(), [&](Watch& watch) {
      watch.blocks(count, poll_block, [&](std::size_t first, std::size_t last) {
        dewall_python::circumcentres<D>(static_cast<const double*>(points.data()), rows.subspan(first, last - first),
                                        o + first * D);
      });
    });
  });
  return out;
}

/// The exact predicates on rows of point indices, for constructions the
/// Python layer makes from them (furthest-site triangulations). `kind` 0:
/// orientation of each row of D + 1 indices (sign of det[p1 - p0, …, pD - p0]);
/// 1: the side of the last of D + 2 indices with respect to the circumsphere of
/// the first D + 1 (+1 inside, 0 on, -1 outside; the simplex must be
/// positively oriented), unperturbed; 2: the same with CGAL's symbolic
/// perturbation (never 0; the query must not be a vertex of the simplex).
/// Above 6 dimensions, or with `cgal_dd` (the tests compare the two), CGAL's dD
/// predicates (high_dimension.hpp) with the same conventions.
py::array predicate_signs(py::handle points_in, py::handle rows_in, int kind, bool cgal_dd) {
  if (kind < 0 || kind > 2) throw py::value_error("kind must be 0, 1 or 2");
  const bool sphere = kind > 0;
  const py::array points = checked(points_in, float64, -1, "points");
  const long d = static_cast<long>(points.shape(1));
  const py::array rows = checked(rows_in, uint32, sphere ? d + 2 : d + 1, "rows");
  const auto n = static_cast<std::uint32_t>(points.shape(0));
  const auto* index = static_cast<const std::uint32_t*>(rows.data());
  const auto count = static_cast<std::size_t>(rows.shape(0));
  const auto width = static_cast<std::size_t>(rows.shape(1));
  for (std::size_t i = 0; i < count * width; ++i)
    if (index[i] >= n) throw py::value_error("rows: index " + std::to_string(index[i]) + " is not a point index");
  py::array_t<std::int8_t> out(static_cast<py::ssize_t>(count));
  std::int8_t* sign = out.mutable_data();
  if (cgal_dd || d > dewall::kernel::max_dimension) {
    if (d < 2) throw py::value_error("points of 2 dimensions or more");
    watched(count, py::none(), [&](Watch& watch) {
      watch.blocks(count, poll_block, [&](std::size_t first, std::size_t last) {
        dewall_python::high_dimension::predicate_signs(static_cast<const double*>(points.data()),
                                                       static_cast<std::size_t>(n), static_cast<int>(d),
                                                       index + first * width, last - first, kind, sign + first);
      });
    });
    return out;
  }
  dewall::kernel::with_dimension(static_cast<int>(d), [&](auto dim) {
    constexpr int D = dim();
    const auto p = as_points<D>(points);
    const Kernel<D> k;
    watched(count, py::none(), [&](Watch& watch) {
    for (std::size_t r = 0; r < count; ++r) {
      if (r % poll_block == 0) watch.poll();
      const std::uint32_t* row = index + r * width;
      if (sphere) {
        std::array<const Point_d<D>*, D + 2> s;
        for (std::size_t j = 0; j < std::size_t{D} + 2; ++j) s[j] = &p[row[j]];
        sign[r] = static_cast<std::int8_t>(kind == 2 ? k.side_of_oriented_sphere_d_object()(s)
                                                     : k.side_of_oriented_sphere_unperturbed_d_object()(s));
      } else {
        std::array<const Point_d<D>*, D + 1> s;
        for (std::size_t j = 0; j < std::size_t{D} + 1; ++j) s[j] = &p[row[j]];
        sign[r] = static_cast<std::int8_t>(k.orientation_d_object()(s));
      }
    }
    });
  });
  return out;
}

/// convex_hull(): (facets, neighbors, below, flat) as int32 arrays and a bool, or None when
/// convex_hull.hpp declines (non-finite, too few or nearly flat points: the caller falls back).
py::object convex_hull(py::handle points_in, const py::object& progress) {
  const py::array points = checked(points_in, float64, -1, "points");
  if (points.shape(1) > dewall::kernel::max_dimension) return py::none();  // the Delaunay route (CGAL dD)
  return dewall::kernel::with_dimension(static_cast<int>(points.shape(1)), [&](auto dim) -> py::object {
    constexpr int D = dim();
    if (points.shape(0) > static_cast<py::ssize_t>(max_index)) throw py::value_error("too many points");
    const auto view = as_points<D>(points);
    std::optional<dewall_python::Convex_hull<D>> hull = watched(view.size(), progress, [&](Watch& watch) {
      return dewall_python::convex_hull<D>(view, [&](double fraction) { watch.report(fraction); });
    });
    if (!hull) return py::none();
    const auto m = static_cast<py::ssize_t>(hull->facets.size());
    return py::make_tuple(adopt<std::int32_t>(std::move(hull->facets), {m, D}),
                          adopt<std::int32_t>(std::move(hull->neighbors), {m, D}),
                          adopt<std::int32_t>(std::move(hull->below), {m}), hull->flat,
                          adopt<double>(std::move(hull->normals), {m, D}));
  });
}

/// Above 6 dimensions: CGAL's dD Delaunay triangulation (high_dimension.hpp) as
/// (simplices, neighbors), int32 arrays of shape (m, d + 1) in the conventions
/// of Triangulation.simplices() and .neighbors().
py::tuple triangulate_dd(py::handle points_in, const py::object& progress) {
  const py::array points = checked(points_in, float64, -1, "points");
  if (static_cast<std::size_t>(points.shape(0)) > max_index)
    throw py::value_error("more than 2^31 - 1 points (the indices are int32, as scipy's)");
  const int d = static_cast<int>(points.shape(1));
  if (d < 2) throw py::value_error("points of 2 dimensions or more");
  // Watched from the first point: in 7 dimensions and up, thousands of points take seconds.
  dewall_python::high_dimension::Cells cells =
      watched(dewall_python::watched_size, progress, [&](Watch& watch) {
        return dewall_python::high_dimension::triangulate(static_cast<const double*>(points.data()),
                                                          static_cast<std::size_t>(points.shape(0)), d,
                                                          [&](double fraction) { watch.report(fraction); });
      });
  const auto rows = static_cast<py::ssize_t>(cells.count);
  return py::make_tuple(adopt<std::int32_t>(std::move(cells.simplices), {rows, d + 1}),
                        adopt<std::int32_t>(std::move(cells.neighbors), {rows, d + 1}));
}

/// Above 6 dimensions: Triangulation.locate() for triangulate_dd's arrays.
py::array locate_dd(py::handle points_in, py::handle simplices_in, py::handle neighbors_in, py::handle queries) {
  const py::array points = checked(points_in, float64, -1, "points");
  const long d = static_cast<long>(points.shape(1));
  const Element_type int32{'i', 4, "int32"};
  const py::array simplices = checked(simplices_in, int32, d + 1, "simplices");
  const py::array neighbors = checked(neighbors_in, int32, d + 1, "neighbors");
  const py::array q = checked(queries, float64, d, "xi");
  const auto count = static_cast<std::size_t>(simplices.shape(0));
  if (static_cast<std::size_t>(neighbors.shape(0)) != count) throw py::value_error("neighbors: one row per simplex");
  const auto* s = static_cast<const std::int32_t*>(simplices.data());
  const auto* nb = static_cast<const std::int32_t*>(neighbors.data());
  for (std::size_t i = 0; i < count * static_cast<std::size_t>(d + 1); ++i)
    if (s[i] < 0 || s[i] >= points.shape(0) || nb[i] < -1 || nb[i] >= static_cast<std::int64_t>(count))
      throw py::value_error("simplices, neighbors: an index out of range");
  py::array_t<std::int32_t> out(q.shape(0));
  std::int32_t* o = out.mutable_data();
  const auto queries_count = static_cast<std::size_t>(q.shape(0));
  watched(queries_count * 64, py::none(), [&](Watch& watch) {  // (a walk in 7-D and up: many queries' work)
    watch.blocks(queries_count, poll_block / 16, [&](std::size_t first, std::size_t last) {
      dewall_python::high_dimension::locate(static_cast<const double*>(points.data()),
                                            static_cast<std::size_t>(points.shape(0)), static_cast<int>(d), s, nb,
                                            count, static_cast<const double*>(q.data()) + first * static_cast<std::size_t>(d),
                                            last - first, o + first);
    });
  });
  return out;
}

py::dict violation_dict(const dewall::certify::Violation& v) {
  const auto index = [](std::size_t i) -> py::object {
    return i == dewall::certify::npos ? py::object(py::none()) : py::object(py::int_(i));
  };
  py::dict d;
  d["rule"] = dewall::certify::rule_name(v.rule);
  d["message"] = dewall::certify::describe(v);
  d["fatal"] = v.fatal();
  d["simplex"] = index(v.simplex);
  d["other_simplex"] = index(v.other_simplex);
  d["face"] = py::tuple(py::cast(v.face));
  d["point"] = index(v.point);
  return d;
}

/// certify(): the report as a dict (python/dewall/_certify.py makes it a class).
py::dict certify(py::handle points_in, py::handle simplices_in, bool all) {
  const py::array points = checked(points_in, float64, -1, "points");
  const long d = static_cast<long>(points.shape(1));
  const py::array simplices = checked(simplices_in, uint32, d + 1, "simplices");
  dewall::certify::Options options;
  options.all = all;
  const dewall::certify::Report r = dewall::kernel::with_dimension(static_cast<int>(d), [&](auto dim) {
    constexpr int D = dim();
    static_assert(sizeof(dewall::certify::Simplex_indices<D>) == (D + 1) * sizeof(std::uint32_t));
    const std::span<const dewall::certify::Simplex_indices<D>> rows(
        reinterpret_cast<const dewall::certify::Simplex_indices<D>*>(simplices.data()),
        static_cast<std::size_t>(simplices.shape(0)));
    py::gil_scoped_release release;
    return dewall::certify::certify<Kernel<D>>(as_points<D>(points), rows, options);
  });
  py::dict out;
  out["delaunay"] = r.delaunay;
  out["canonical"] = r.canonical;
  out["dimension"] = r.dimension;
  out["points"] = r.points;
  out["distinct_points"] = r.distinct_points;
  out["simplices"] = r.simplices;
  out["interior_facets"] = r.interior_facets;
  out["boundary_facets"] = r.boundary_facets;
  out["cospherical_facets"] = r.cospherical_facets;
  py::list violations;
  for (const auto& v : r.violations) violations.append(violation_dict(v));
  out["violations"] = violations;
  return out;
}

py::array generate(const std::string& kind_name, std::size_t n, int dimension, std::uint64_t seed) {
  const auto kind = dewall::io::parse_point_kind(kind_name);
  if (!kind)
    throw py::value_error("unknown kind '" + kind_name + "' (one of " + dewall::io::point_kind_names() + ")");
  dewall::io::Point_table table;
  {
    py::gil_scoped_release release;
    table = dewall::io::generate_points(*kind, n, dimension, seed);  // std::invalid_argument → ValueError
  }
  const auto rows = static_cast<py::ssize_t>(table.size());
  return adopt<double>(std::move(table.coordinates), {rows, static_cast<py::ssize_t>(dimension)});
}

}  // namespace

PYBIND11_MODULE(_dewall, m) {
  m.doc() = "The compiled part of dewall (use the dewall package, not this module).";

  // Points that cannot be triangulated: a ValueError subclass whose `point` is
  // the offending input index (None when the whole set is at fault).
  static py::exception<dewall::Invalid_input> invalid_input(m, "InvalidInput", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const dewall::Cancelled& e) {
      // Only when the work stopped without a Python exception to raise (none expected).
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const dewall::Invalid_input& e) {
      py::object error = py::handle(invalid_input.ptr())(e.what());
      error.attr("point") = e.point_index() == dewall::Invalid_input::npos ? py::object(py::none())
                                                                          : py::object(py::int_(e.point_index()));
      PyErr_SetObject(invalid_input.ptr(), error.ptr());
    }
  });

  py::class_<Triangulation>(m, "Triangulation")
      .def_property_readonly("dimension", &Triangulation::dimension)
      .def_property_readonly("statistics", &Triangulation::statistics)
      .def("simplices", [](py::object self) { return self.cast<Triangulation&>().simplices(self); })
      .def("neighbors", [](py::object self) { return self.cast<Triangulation&>().neighbors(self); })
      .def("locate", &Triangulation::locate, py::arg("xi"))
      .def("locate_weights", &Triangulation::locate_weights, py::arg("xi"), py::arg("rcond_limit"))
      .def("first_occurrences", &Triangulation::first_occurrences)
      .def("cospherical_neighbours", &Triangulation::cospherical_neighbours)
      .def("voronoi", &Triangulation::voronoi, py::arg("group"));

  m.def("triangulate", &triangulate, py::arg("points"), py::arg("engine") = "auto", py::arg("threads") = py::none(),
        py::arg("progress") = py::none());
  m.def("from_simplices", &from_simplices, py::arg("points"), py::arg("simplices"));
  m.def("barycentric_transforms", &barycentric_transforms, py::arg("points"), py::arg("simplices"),
        py::arg("rcond_limit"));
  m.def("circumcentres", &circumcentres, py::arg("points"), py::arg("simplices"));
  m.def("merge_groups", &merge_groups, py::arg("count"), py::arg("pairs"));
  m.def("predicate_signs", &predicate_signs, py::arg("points"), py::arg("rows"), py::arg("kind"),
        py::arg("cgal_dd") = false);
  m.def("triangulate_dd", &triangulate_dd, py::arg("points"), py::arg("progress") = py::none());
  m.def("locate_dd", &locate_dd, py::arg("points"), py::arg("simplices"), py::arg("neighbors"), py::arg("xi"));
  m.def("convex_hull", &convex_hull, py::arg("points"), py::arg("progress") = py::none());
  m.def("certify", &certify, py::arg("points"), py::arg("simplices"), py::arg("all") = false);
  m.attr("point_kinds") = py::tuple(py::str(dewall::io::point_kind_names()).attr("split")(", "));
  m.def("generate", &generate, py::arg("kind"), py::arg("n"), py::arg("dim"), py::arg("seed"));
}
