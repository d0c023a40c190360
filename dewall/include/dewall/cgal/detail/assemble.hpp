// The part of the CGAL builders that does not depend on which CGAL
// triangulation is built: reading the caller's range (points, or points with
// info), converting to doubles, and wiring DeWall's simplices into a
// triangulation data structure through a small access policy.
#pragma once

#include <CGAL/number_utils.h>

#include <boost/tuple/tuple.hpp>

#ifdef __GLIBC__
#include <malloc.h>  // malloc_trim
#endif

#include <algorithm>
#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "dewall/cgal/detail/facet_matcher.hpp"
#include "dewall/cgal/detail/geom_traits.hpp"
#include "dewall/cgal/detail/graph_assembly.hpp"
#include "dewall/detail/common/assert.hpp"
#include "dewall/dewall.hpp"
#include "dewall/error.hpp"
#include "dewall/kernel/point.hpp"

namespace dewall::cgal::detail {

/// The Info of a CGAL vertex type, or void when its base carries none.
template <class Vertex>
struct Vertex_info {
  using type = void;
};
template <class Vertex>
  requires requires { typename Vertex::Info; }
struct Vertex_info<Vertex> {
  using type = typename Vertex::Info;
};

template <class>
inline constexpr bool dependent_false = false;

/// One value of the caller's range as the builders keep it: a Point, or
/// std::pair<Point, Info>. Accepted are the values CGAL's range insert takes
/// (Delaunay_triangulation_2/_3::insert(first, last)): anything convertible to
/// Point; with an Info, anything convertible to std::pair<Point, Info>, and a
/// boost::tuple of (point, info) as boost::zip_iterator yields (CGAL's
/// info_insert_with_zip_iterator examples). Iterators may be input iterators:
/// the range is read once.
template <class Point, class Info, class Value>
auto to_item(const Value& value) {
  if constexpr (std::is_convertible_v<const Value&, Point>) {
    return Point(value);
  } else if constexpr (!std::is_void_v<Info> && std::is_convertible_v<const Value&, std::pair<Point, Info>>) {
    return std::pair<Point, Info>(value);
  } else if constexpr (!std::is_void_v<Info> && requires {
                         requires boost::tuples::length<Value>::value == 2;
                         { boost::get<0>(value) } -> std::convertible_to<Point>;
                         { boost::get<1>(value) } -> std::convertible_to<Info>;
                       }) {
    return std::pair<Point, Info>(boost::get<0>(value), boost::get<1>(value));
  } else {
    static_assert(dependent_false<Value>,
                  "the range must hold the triangulation's Point or, when its vertices carry an Info, "
                  "std::pair<Point, Info> or boost::tuple<Point, Info> (a boost::zip_iterator), as CGAL's range "
                  "insert does");
  }
}

/// The range [first, last) as the items to_item makes of its values.
template <class Point, class Info, class InputIterator>
auto read_items(InputIterator first, InputIterator last) {
  using Item = decltype(to_item<Point, Info>(*first));
  std::vector<Item> items;
  if constexpr (std::forward_iterator<InputIterator>) items.reserve(static_cast<std::size_t>(std::distance(first, last)));
  for (; first != last; ++first) items.push_back(to_item<Point, Info>(*first));
  return items;
}

/// Access to an item's point and (when present) info.
template <class Item>
struct Item_traits {
  static constexpr bool has_info = false;
  static const Item& point(const Item& item) { return item; }
};
template <class Point, class Info>
struct Item_traits<std::pair<Point, Info>> {
  static constexpr bool has_info = true;
  static const Point& point(const std::pair<Point, Info>& item) { return item.first; }
};

/// The double nearest to x, and whether it equals x. For double FT the
/// conversion is the identity and the check compiles away.
template <class FT>
bool to_exact_double(const FT& x, double& out) {
  if constexpr (std::is_same_v<std::remove_cvref_t<FT>, double>) {
    out = x;
    return true;
  } else {
    out = CGAL::to_double(x);
    return FT(out) == x;
  }
}

/// Converts the caller's points to DeWall's points. Returns nullopt when some
/// coordinate is not a double (the builders then let CGAL insert the points:
/// triangulating rounded coordinates could give cells that are inverted or not
/// Delaunay for the true points). Throws Invalid_input on NaN or infinity.
/// `coord(p, i)` yields the i-th Cartesian coordinate of p.
template <int D, class Items, class Traits, class Coord>
std::optional<std::vector<kernel::Point_d<D>>> to_dewall_points(const Items& items, Coord&& coord) {
  std::vector<kernel::Point_d<D>> out(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    const auto& p = Traits::point(items[i]);
    for (int j = 0; j < D; ++j) {
      if (!to_exact_double(coord(p, j), out[i][j])) return std::nullopt;
    }
    if (!kernel::is_finite(out[i]))
      throw Invalid_input(i, "has a non-finite coordinate (NaN or infinity)");
  }
  return out;
}

/// DeWall's triangulation of `points`, or nullopt when DeWall cannot build
/// one because the points are not full-dimensional (too few distinct points,
/// or all in a hyperplane) or too many for 32-bit indices. Non-finite
/// coordinates were rejected before.
template <int D>
std::optional<std::vector<Simplex<D>>> dewall_simplices(const std::vector<kernel::Point_d<D>>& points,
                                                        const Options& options) {
  try {
    return dewall::triangulate<D>(points, options).simplices;
  } catch (const Invalid_input&) {
    return std::nullopt;
  }
}

/// Wires the simplices into a triangulation data structure through `tds`, an
/// access policy providing
///   Vertex_handle, Cell_handle,
///   Vertex_handle infinite_vertex(),
///   Vertex_handle create_vertex(std::size_t input_index),
///   Cell_handle create_cell(const std::array<Vertex_handle, D + 1>&)   (also sets each vertex's cell),
///   void set_neighbors(Cell_handle a, int i, Cell_handle b, int j)     (both directions),
///   optionally void reserve(std::size_t vertices, std::size_t cells).
/// Vertices are created in input order for the input points used by some
/// simplex (the first occurrence of each distinct point, DeWall's convention),
/// then the finite cells in DeWall's order with DeWall's (positive)
/// orientation, then one infinite cell per hull facet.
///
/// Infinite cells: the finite cell c with its vertex i replaced by the
/// infinite vertex, then two other vertices swapped. The odd permutation is
/// what makes the pair (c, infinite cell) consistently oriented, the
/// combinatorial condition every CGAL TDS checks across a shared facet; it
/// is also the geometric one, since the infinite vertex then stands where
/// CGAL expects (the infinite cell is "negatively oriented" with c's
/// opposite vertex in its place).
///
/// \pre the simplices form a triangulation of a full-dimensional point set
/// (each interior facet in exactly two simplices), as DeWall's output does.
/// Complexity: expected O(n + number of simplices).
template <int D, class Access>
void assemble(const std::vector<Simplex<D>>& simplices, std::size_t input_size, Access& tds) {
  using Vertex_handle = typename Access::Vertex_handle;
  using Cell_handle = typename Access::Cell_handle;
  constexpr std::uint32_t infinite_id = std::numeric_limits<std::uint32_t>::max();

  // One allocation for the storage of the cells and vertices where the TDS
  // allows it (Compact_container::reserve) instead of many growing blocks.
  if constexpr (requires { tds.reserve(std::size_t{}, std::size_t{}); })
    tds.reserve(input_size + 1, simplices.size() + simplices.size() / 8);

  std::vector<Vertex_handle> vertex(input_size);
  {
    std::vector<bool> used(input_size, false);
    for (const auto& s : simplices)
      for (std::uint32_t v : s) used[v] = true;
    for (std::size_t i = 0; i < input_size; ++i)
      if (used[i]) vertex[i] = tds.create_vertex(i);
  }
  const Vertex_handle infinite = tds.infinite_vertex();
  auto handle_of = [&](std::uint32_t id) { return id == infinite_id ? infinite : vertex[id]; };

  std::vector<Cell_handle> cells;
  cells.reserve(simplices.size() + simplices.size() / 4);
  for (const auto& s : simplices) {
    std::array<Vertex_handle, D + 1> w;
    for (int i = 0; i <= D; ++i) w[static_cast<std::size_t>(i)] = vertex[s[static_cast<std::size_t>(i)]];
    cells.push_back(tds.create_cell(w));
  }

  // Interior facets pair up here; what stays parked is the convex hull.
  using Matcher = Facet_matcher<D>;
  typename Matcher::Facet_ref partner{};
  Matcher interior(std::max<std::size_t>(1024, simplices.size() / 8));
  for (std::size_t c = 0; c < simplices.size(); ++c)
    for (int i = 0; i <= D; ++i)
      if (interior.match_or_park(Matcher::facet_key(simplices[c], i), {c, i}, partner))
        tds.set_neighbors(cells[c], i, cells[partner.cell], partner.index);

  // One infinite cell per hull facet; their facets through the infinite
  // vertex (one per hull ridge) pair up among themselves.
  std::vector<Simplex<D>> infinite_cells;
  infinite_cells.reserve(interior.size());
  const std::size_t first_infinite = cells.size();
  interior.for_each_parked([&](const typename Matcher::Key&, const typename Matcher::Facet_ref& hull) {
    Simplex<D> s = simplices[hull.cell];
    const int i = hull.index;
    s[static_cast<std::size_t>(i)] = infinite_id;
    std::swap(s[static_cast<std::size_t>((i + 1) % (D + 1))], s[static_cast<std::size_t>((i + 2) % (D + 1))]);
    std::array<Vertex_handle, D + 1> w;
    for (int j = 0; j <= D; ++j) w[static_cast<std::size_t>(j)] = handle_of(s[static_cast<std::size_t>(j)]);
    const Cell_handle inf_cell = tds.create_cell(w);
    tds.set_neighbors(inf_cell, i, cells[hull.cell], i);
    cells.push_back(inf_cell);
    infinite_cells.push_back(s);
  });
  Matcher hull_ridges(std::max<std::size_t>(1024, infinite_cells.size()));
  for (std::size_t c = 0; c < infinite_cells.size(); ++c)
    for (int i = 0; i <= D; ++i) {
      if (infinite_cells[c][static_cast<std::size_t>(i)] == infinite_id) continue;
      if (hull_ridges.match_or_park(Matcher::facet_key(infinite_cells[c], i), {c, i}, partner))
        tds.set_neighbors(cells[first_infinite + c], i, cells[first_infinite + partner.cell], partner.index);
    }
  DEWALL_ASSERT(hull_ridges.size() == 0);
}

/// Whether two items are one point for DeWall (equal `coords`) but differ as
/// points, as (6, 1, 1) and (6, 1, 7) under Projection_traits_xy_3. CGAL then
/// keeps one of them as the vertex, the first its spatial sort reaches (a
/// located VERTEX returns the existing vertex), which DeWall's "first
/// occurrence" does not reproduce. Complexity: O(n log n).
template <int D, class Items>
bool has_projected_twins(const std::vector<kernel::Point_d<D>>& coords, const Items& items) {
  using Traits = Item_traits<typename Items::value_type>;
  std::vector<std::uint32_t> order(coords.size());
  std::iota(order.begin(), order.end(), std::uint32_t{0});
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return coords[a].x < coords[b].x; });
  for (std::size_t k = 1; k < order.size(); ++k) {
    const std::uint32_t a = order[k - 1], b = order[k];
    // Equal neighbours in the order: a run of twins compares each to the next.
    if (coords[a].x == coords[b].x && !(Traits::point(items[a]) == Traits::point(items[b]))) return true;
  }
  return false;
}

/// Returns the free memory at the top of the heap to the system: a large
/// copy freed there (glibc maps only blocks above a threshold it raises when
/// a mapped block is freed, as the caller's points may have been) would
/// otherwise stay resident while CGAL's containers grow elsewhere.
inline void give_back_freed_memory() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

/// The handle of a cell of Triangulation_data_structure_2 (a face) or _3.
template <int D, class Tds>
struct Tds_cell;
template <class Tds>
struct Tds_cell<2, Tds> {
  using type = typename Tds::Face_handle;
};
template <class Tds>
struct Tds_cell<3, Tds> {
  using type = typename Tds::Cell_handle;
};

/// Access (see assemble()) to the data structure of a CGAL::Delaunay_triangulation_2
/// (its faces are the cells) or _3.
template <int D, class DT, class Item, class Traits>
struct Tds_access {
  using Tds = typename DT::Triangulation_data_structure;
  using Vertex_handle = typename Tds::Vertex_handle;
  using Cell_handle = typename Tds_cell<D, Tds>::type;

  Tds& tds;
  Vertex_handle infinite;
  std::vector<Item>& items;  // by input index
  Vertex_handle infinite_vertex() const { return infinite; }
  Vertex_handle create_vertex(std::size_t i) {
    Vertex_handle v = tds.create_vertex();
    v->set_point(Traits::point(items[i]));
    if constexpr (Traits::has_info) v->info() = items[i].second;
    return v;
  }
  Cell_handle create_cell(const std::array<Vertex_handle, D + 1>& w) {
    if constexpr (D == 2) {
      Cell_handle c = tds.create_face(w[0], w[1], w[2]);
      for (const Vertex_handle& v : w) v->set_face(c);
      return c;
    } else {
      Cell_handle c = tds.create_cell(w[0], w[1], w[2], w[3]);
      for (const Vertex_handle& v : w) v->set_cell(c);
      return c;
    }
  }
  /// create_cell without setting the vertices' cells (Graph_assembly sets
  /// each vertex's once, set_incident_cell).
  Cell_handle create_bare_cell(const std::array<Vertex_handle, D + 1>& w) {
    if constexpr (D == 2) {
      Cell_handle c = tds.create_face();
      c->set_vertices(w[0], w[1], w[2]);
      return c;
    } else {
      Cell_handle c = tds.create_cell();
      c->set_vertices(w[0], w[1], w[2], w[3]);
      return c;
    }
  }
  static void set_incident_cell(Vertex_handle v, Cell_handle c) {
    if constexpr (D == 2) v->set_face(c);
    else v->set_cell(c);
  }
  /// Every vertex is made: the caller's items go (Graph_assembly).
  void vertices_made() {
    std::vector<Item>().swap(items);
    give_back_freed_memory();
  }
  void reserve(std::size_t vertices, std::size_t cells) {
    // 3D only (where it was measured); not in the concurrent container.
    if constexpr (D == 3 && requires { tds.cells().reserve(cells); }) {
      tds.vertices().reserve(vertices);
      tds.cells().reserve(cells);
    }
  }
  static void set_neighbors(Cell_handle a, int i, Cell_handle b, int j) {
    a->set_neighbor(i, b);
    b->set_neighbor(j, a);
  }
};

/// How the builders built the triangulation, if it did.
enum class Assembly {
  none,            // DeWall did not apply: dt is untouched
  from_adjacency,  // from the incremental engine's cells and neighbours (Graph_assembly)
  from_simplices   // from the engine's simplices (assemble())
};

/// Where the engine's output goes: its triangulation with adjacency to a
/// Graph_assembly (the project's incremental engine), else its simplices to
/// a list assemble() wires afterwards (DeWall's walls, Engine::cgal). The
/// caller's coordinates go once the engine has copied them.
template <int D, class Receiver>
struct Builder_sink {
  Receiver& assembly;
  std::vector<Simplex<D>>& simplices;
  std::vector<kernel::Point_d<D>>& coords;
  dewall::detail::Cell_graph_output<D>* cell_graph() { return &assembly; }
  void reserve(std::size_t n) { simplices.reserve(n); }
  void operator()(const Simplex<D>& s) { simplices.push_back(s); }
  void input_no_longer_read() {
    std::vector<kernel::Point_d<D>>().swap(coords);
    give_back_freed_memory();
  }
};

/// Triangulates `coords` (freed once the engine has copied them) into the
/// data structure that `make_access()` prepares and returns the access
/// policy of (see assemble()): from the incremental engine's adjacency when
/// that engine builds the triangulation (Engine::automatic does below 2^25
/// points, Engine::incremental always), else from the simplices. Returns
/// Assembly::none, with make_access never called, when the points do not
/// span E^D (or are more than 32-bit indices hold).
template <int D, class Access, class Make_access>
Assembly triangulate_into(std::vector<kernel::Point_d<D>>& coords, const Options& options, Make_access make_access) {
  Graph_assembly<D, Access, Make_access> assembly(make_access);
  std::vector<Simplex<D>> simplices;
  const std::size_t input_size = coords.size();
  try {
    dewall::triangulate_to<kernel::Filtered_kernel_d<D>>(std::span<const kernel::Point_d<D>>(coords),
                                                         Builder_sink<D, decltype(assembly)>{assembly, simplices, coords},
                                                         options);
  } catch (const Invalid_input&) {
    DEWALL_ASSERT(!assembly.assembled());  // the input is checked before anything is built
    return Assembly::none;
  }
  if (assembly.assembled()) return Assembly::from_adjacency;
  Access access = make_access();
  assemble<D>(simplices, input_size, access);
  return Assembly::from_simplices;
}

/// Prepares dt's freshly constructed, empty data structure for assembly: a
/// fresh infinite vertex (clear() drops the one DT's constructor made),
/// dimension D; returns the Tds_access over it.
template <int D, class DT, class Item, class Traits>
Tds_access<D, DT, Item, Traits> prepared_tds(DT& dt, std::vector<Item>& items) {
  auto& tds = dt.tds();
  tds.clear();
  Tds_access<D, DT, Item, Traits> access{tds, tds.create_vertex(), items};
  dt.set_infinite_vertex(access.infinite);
  tds.set_dimension(D);
  return access;
}

/// Builds dt (freshly constructed) from items (emptied once the
/// triangulation's vertices hold their points) with dewall::triangulate: from
/// the incremental engine's adjacency (Graph_assembly) when that engine
/// builds it, as Engine::automatic does below 2^25 points, else from the
/// simplices (assemble()); Assembly::none when DeWall does not apply and dt
/// is untouched: DT's geometric traits
/// are not known to decide as DeWall does (Dewall_axes), a coordinate is not
/// exactly a double, points equal under the projection differ as points
/// (has_projected_twins), or the points do not span E^D (or are more than
/// 32-bit indices hold).
template <int D, class DT, class Item>
Assembly build_with_dewall(DT& dt, std::vector<Item>& items, const Options& options) {
  using Axes = Dewall_axes<typename DT::Geom_traits, D>;
  if constexpr (!Axes::known) {
    return Assembly::none;
  } else {
    using Traits = Item_traits<Item>;
    using Access = Tds_access<D, DT, Item, Traits>;
    auto coords = to_dewall_points<D, std::vector<Item>, Traits>(
        items, [](const typename DT::Point& p, int j) { return p.cartesian(Axes::axes[static_cast<std::size_t>(j)]); });
    if (!coords) return Assembly::none;
    if constexpr (Axes::projects)
      if (has_projected_twins<D>(*coords, items)) return Assembly::none;

    return triangulate_into<D, Access>(*coords, options, [&] { return prepared_tds<D, DT, Item, Traits>(dt, items); });
  }
}

/// The body of make_delaunay_triangulation_2/_3: the empty DT `make_empty()`
/// returns (with the caller's traits, and lock data structure in 3D) built by
/// `build_with_dewall` (build_with_dewall_2/_3) from the items of
/// [first, last), or by CGAL's own range insertion where DeWall does not apply.
template <class DT, class Make_empty, class InputIterator, class Build>
DT make_triangulation(Make_empty&& make_empty, InputIterator first, InputIterator last, const Options& options,
                      Build&& build_with_dewall) {
  DT dt = make_empty();
  using Info = typename Vertex_info<typename DT::Vertex>::type;
  auto items = read_items<typename DT::Point, Info>(first, last);
  if (build_with_dewall(dt, items, options) == Assembly::none) dt.insert(items.begin(), items.end());
  return dt;
}

/// True when T is, or derives from, Tpl<A...> for some arguments: what the
/// builders' static_asserts check DT against (CGAL::Delaunay_triangulation_2 …).
template <template <class...> class Tpl>
struct Template_match {
  template <class... A>
  static std::true_type test(const Tpl<A...>*);
  static std::false_type test(...);
};
template <class T, template <class...> class Tpl>
inline constexpr bool derives_from_template = decltype(Template_match<Tpl>::test(static_cast<const T*>(nullptr)))::value;

}  // namespace dewall::cgal::detail
