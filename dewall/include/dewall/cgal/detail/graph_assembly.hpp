// Graph_assembly: a triangulation data structure filled straight from the
// incremental engine's cells and their adjacency (cell_graph_output.hpp), in
// one pass over its slots: each cell created once, its neighbours translated
// by slot number, the infinite cells the engine's own. No facet is matched
// (assemble() in assemble.hpp does that for engines without adjacency), and
// the engine releases each block of slots once it has been read, so the TDS
// grows into the memory the engine gives back.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "dewall/detail/common/cell_graph_output.hpp"

namespace dewall::cgal::detail {

/// The engine's triangulation in a TDS through `Access` (assemble.hpp's
/// policy: Vertex_handle, Cell_handle, infinite_vertex(), create_vertex(input
/// index), create_cell(vertices) (which sets each vertex's cell),
/// set_neighbors(a, i, b, j); optionally vertices_made() (the input is read
/// no more), and create_bare_cell(vertices) with set_incident_cell(v, c),
/// which let each vertex's cell be set once, at the end). `make_access()`
/// prepares the empty TDS (the infinite vertex, the dimension) and returns
/// the policy; it is called when the engine's triangulation arrives, so an
/// engine that hands over simplices instead (DeWall) leaves the TDS
/// untouched.
/// Vertices are created in the engine's order (its insertion order, along a
/// Hilbert curve), cells in slot order with the engine's orientation
/// (positive; an infinite cell as if its infinite vertex were a point beyond
/// the hull facet, which is CGAL's convention).
/// Memory besides the TDS: a handle per vertex and per slot, 32 bits per vertex.
template <int D, class Access, class Make_access>
class Graph_assembly final : public dewall::detail::Cell_graph_output<D> {
 public:
  using Graph = dewall::detail::Cell_graph<D>;
  explicit Graph_assembly(Make_access make_access) : make_access_(std::move(make_access)) {}

  /// Whether the engine handed its triangulation here.
  bool assembled() const { return access_ != nullptr; }

  void vertices(std::span<const dewall::detail::Index> input_ids) override {
    access_.reset(new Access(make_access_()));
    vertex_.resize(input_ids.size());
    for (std::size_t v = 0; v < input_ids.size(); ++v) vertex_[v] = access_->create_vertex(input_ids[v]);
    if constexpr (requires { access_->vertices_made(); }) access_->vertices_made();
  }

  void begin_cells(std::size_t slots, std::size_t /*finite_cells*/) override {
    cell_.resize(slots);
    if constexpr (sets_incidence_once) incident_.resize(vertex_.size());
  }

  void cells(std::size_t first, std::span<const dewall::detail::Cell_record<D>> block) override {
    Access& access = *access_;
    const auto infinite = access.infinite_vertex();
    for (std::size_t k = 0; k < block.size(); ++k) {
      const auto& record = block[k];
      if (record.v[0] == Graph::free_slot) continue;
      const std::size_t slot = first + k;
      std::array<typename Access::Vertex_handle, D + 1> w;
      for (std::size_t i = 0; i <= D; ++i) w[i] = record.v[i] == Graph::infinite_vertex ? infinite : vertex_[record.v[i]];
      typename Access::Cell_handle cell;
      if constexpr (sets_incidence_once) {
        cell = access.create_bare_cell(w);
        for (std::size_t i = 0; i <= D; ++i) {
          if (record.v[i] != Graph::infinite_vertex) incident_[record.v[i]] = static_cast<std::uint32_t>(slot);
          else infinite_incident_ = cell;
        }
      } else {
        cell = access.create_cell(w);
      }
      cell_[slot] = cell;
      // Each pair of neighbours is joined once, by the later of the two.
      for (int i = 0; i <= D; ++i) {
        const std::uint32_t reference = record.n[static_cast<std::size_t>(i)];
        const std::size_t across = Graph::neighbor_slot(reference);
        if (across < slot) access.set_neighbors(cell, i, cell_[across], Graph::neighbor_facet(reference));
      }
    }
    if constexpr (sets_incidence_once) {
      if (first + block.size() != cell_.size()) return;
      // The last block: each vertex gets the last cell that held it, in one
      // pass in the vertices' order instead of a scattered write per cell.
      Access::set_incident_cell(infinite, infinite_incident_);
      for (std::size_t v = 0; v < vertex_.size(); ++v) Access::set_incident_cell(vertex_[v], cell_[incident_[v]]);
    }
  }

 private:
  static constexpr bool sets_incidence_once = requires(Access& a, const std::array<typename Access::Vertex_handle, D + 1>& w) {
    a.create_bare_cell(w);
  };
  Make_access make_access_;
  std::unique_ptr<Access> access_;
  std::vector<typename Access::Vertex_handle> vertex_;  // by the engine's vertex id
  std::vector<typename Access::Cell_handle> cell_;      // by slot
  std::vector<std::uint32_t> incident_;                 // by vertex id: the slot of a cell holding it
  typename Access::Cell_handle infinite_incident_{};
};

}  // namespace dewall::cgal::detail
