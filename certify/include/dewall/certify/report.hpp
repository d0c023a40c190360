// The certifier's verdict: which rules a simplex list breaks, each with a witness.
//
// A violation names the rule, the simplex (its row in the input list), the
// facet or ridge (input indices) and the point that witness it. Topology only:
// nothing here knows the kernel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace dewall::certify {

inline constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();

/// The rules of certify(), in the order they are checked.
enum class Rule {
  non_finite_point,          // a coordinate is NaN or infinite
  index_out_of_range,        // a vertex index is not an input index
  repeated_vertex,           // a simplex names one vertex twice
  duplicate_point_used,      // a vertex is a later copy of an earlier input point
  degenerate_simplex,        // orientation ZERO: the vertices are affinely dependent
  point_not_a_vertex,        // a point (not a later duplicate) is missing from the triangulation
  facet_shared_by_many,      // a facet of more than two simplices
  duplicate_simplex,         // two rows with the same vertex set
  facet_same_side,           // the two simplices of a facet lie on the same side of it
  boundary_ridge_not_manifold,  // a boundary ridge in other than two boundary facets
  boundary_not_convex,       // two boundary facets meet in a reflex ridge
  boundary_facet_inward,     // the witness point is not strictly inside a boundary facet
  multiple_covering,         // a second simplex contains the witness point
  not_locally_delaunay,      // the opposite vertex is strictly inside the circumsphere
  not_canonical,             // cospherical facet resolved against the perturbation (not fatal)
};

/// A stable identifier for messages and JSON ("not_locally_delaunay", …).
inline const char* rule_name(Rule r) {
  switch (r) {
    case Rule::non_finite_point: return "non_finite_point";
    case Rule::index_out_of_range: return "index_out_of_range";
    case Rule::repeated_vertex: return "repeated_vertex";
    case Rule::duplicate_point_used: return "duplicate_point_used";
    case Rule::degenerate_simplex: return "degenerate_simplex";
    case Rule::point_not_a_vertex: return "point_not_a_vertex";
    case Rule::facet_shared_by_many: return "facet_shared_by_many";
    case Rule::duplicate_simplex: return "duplicate_simplex";
    case Rule::facet_same_side: return "facet_same_side";
    case Rule::boundary_ridge_not_manifold: return "boundary_ridge_not_manifold";
    case Rule::boundary_not_convex: return "boundary_not_convex";
    case Rule::boundary_facet_inward: return "boundary_facet_inward";
    case Rule::multiple_covering: return "multiple_covering";
    case Rule::not_locally_delaunay: return "not_locally_delaunay";
    case Rule::not_canonical: return "not_canonical";
  }
  return "unknown";
}

/// One broken rule with its witness. Unused fields hold npos / stay empty.
struct Violation {
  Rule rule;
  std::size_t simplex = npos;        // row in the simplex list
  std::size_t other_simplex = npos;  // the second simplex involved, if any
  std::vector<std::uint32_t> face = {};  // the facet or ridge (sorted input indices), if any
  std::size_t point = npos;          // the witness point (input index), if any
  /// Every rule but not_canonical means "not a Delaunay triangulation".
  bool fatal() const { return rule != Rule::not_canonical; }
};

/// What certify() found.
struct Report {
  int dimension = 0;
  bool delaunay = false;   // a Delaunay triangulation of the points (empty closed spheres)
  bool canonical = false;  // and the symbolically perturbed one (CGAL's, dewall's)
  std::size_t points = 0, distinct_points = 0, simplices = 0;
  std::size_t interior_facets = 0, boundary_facets = 0;
  std::size_t cospherical_facets = 0;  // interior facets whose d + 2 points are cospherical
  /// Fatal violations first (in checking order), then not_canonical notes.
  /// Without Options::all: at most one fatal violation and one note.
  std::vector<Violation> violations;

  const Violation* first_fatal() const {
    for (const auto& v : violations)
      if (v.fatal()) return &v;
    return nullptr;
  }
  const Violation* first_note() const {
    for (const auto& v : violations)
      if (!v.fatal()) return &v;
    return nullptr;
  }
};

/// How certify() works.
struct Options {
  /// Report every violation (true), or stop at the first fatal one (false).
  bool all = false;
  /// At most this many threads (0: all cores). The report is the same for every value.
  unsigned threads = 0;
  /// Renumber the points along a Z-order curve inside the certifier, the rows
  /// as they are read: the points of neighbouring simplices then sit side by
  /// side in memory (it takes a copy of the points). Reports are in the
  /// input's numbers, and the same either way. Not used when streaming.
  bool spatial_order = true;
  /// Stream: keep the rows in temporary files, one per range of vertices,
  /// instead of memory, and match the facets range by range. Memory: the
  /// points, a few bytes per point, and `working_memory`.
  bool stream = false;
  /// Bytes for the facet records of one window of vertices (and, streaming,
  /// the file buffers); 0: 256 KiB per thread in memory (a core's cache), or
  /// 512 MiB streaming. A window holds one vertex (streaming: one range of
  /// vertices) at least.
  std::size_t working_memory = 0;
  /// Where streaming writes its temporary files (empty: $TMPDIR, else /tmp);
  /// they are unlinked as soon as they are open.
  std::string temp_directory = {};
};

/// A one-line English description of `v`; `name` turns a simplex row into
/// words (default "simplex R"; the CLI adds the file line).
inline std::string describe(const Violation& v, const std::function<std::string(std::size_t)>& name = {}) {
  const auto simplex = [&](std::size_t r) { return name ? name(r) : "simplex " + std::to_string(r); };
  std::string face = "{";
  for (std::size_t i = 0; i < v.face.size(); ++i) {
    if (i) face += ' ';
    face += std::to_string(v.face[i]);
  }
  face += "}";
  const std::string p = v.point == npos ? std::string() : "point " + std::to_string(v.point);
  std::string s;
  switch (v.rule) {
    case Rule::non_finite_point: s = p + " has a non-finite coordinate"; break;
    case Rule::index_out_of_range: s = simplex(v.simplex) + ": vertex index " + std::to_string(v.point) + " is not an input index"; break;
    case Rule::repeated_vertex: s = simplex(v.simplex) + ": vertex " + std::to_string(v.point) + " appears twice"; break;
    case Rule::duplicate_point_used:
      s = simplex(v.simplex) + ": vertex " + std::to_string(v.point) + " duplicates an earlier point; the first occurrence must be used";
      break;
    case Rule::degenerate_simplex: s = simplex(v.simplex) + " is degenerate (its vertices are affinely dependent)"; break;
    case Rule::point_not_a_vertex: s = p + " is not a vertex of any simplex"; break;
    case Rule::facet_shared_by_many: s = "facet " + face + " is shared by more than two simplices, e.g. " + simplex(v.simplex) + " and " + simplex(v.other_simplex); break;
    case Rule::duplicate_simplex: s = simplex(v.simplex) + " and " + simplex(v.other_simplex) + " have the same vertices"; break;
    case Rule::facet_same_side:
      s = simplex(v.simplex) + " and " + simplex(v.other_simplex) + " lie on the same side of their common facet " + face + " (they overlap)";
      break;
    case Rule::boundary_ridge_not_manifold: s = "boundary ridge " + face + " is not in exactly two boundary facets (near " + simplex(v.simplex) + ")"; break;
    case Rule::boundary_not_convex:
      s = "the boundary is not convex at ridge " + face + ": " + p + " of " + simplex(v.other_simplex) + " lies outside the boundary facet of " + simplex(v.simplex);
      break;
    case Rule::boundary_facet_inward:
      s = "boundary facet " + face + " of " + simplex(v.simplex) + " does not face away from the witness point inside " + simplex(v.other_simplex) + " (the boundary is not the hull)";
      break;
    case Rule::multiple_covering:
      s = simplex(v.simplex) + " overlaps " + simplex(v.other_simplex) + ": it contains a point interior to it (near its vertex " + std::to_string(v.point) + ")";
      break;
    case Rule::not_locally_delaunay:
      s = "facet " + face + " is not locally Delaunay: " + p + " of " + simplex(v.other_simplex) + " lies strictly inside the circumsphere of " + simplex(v.simplex);
      break;
    case Rule::not_canonical:
      s = "facet " + face + " is cospherical and resolved against the symbolic perturbation: " + p + " of " + simplex(v.other_simplex) + " is inside the perturbed circumsphere of " + simplex(v.simplex);
      break;
  }
  return s + " [" + rule_name(v.rule) + "]";
}

}  // namespace dewall::certify
