// What `dewall certify` prints for a report (the text, not --json): shared
// with `dewall-mpi certify`, whose rank 0 prints the same words.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>

#include "dewall/certify/report.hpp"

namespace dewall::cli {

/// Names the rows and points of a report as the files number them (TetGen may
/// count from 1): "simplex R (FILE:LINE)".
struct Certify_names {
  std::string simplices;  // the simplex file's name, as messages give it
  std::size_t shift;      // the points' first index
  std::function<std::string(std::size_t)> where;  // "FILE:LINE" of row r (io::Simplex_list::where)
  std::string format;     // the simplex file's (io::Simplex_list::format)

  std::string operator()(std::size_t r) const { return "simplex " + std::to_string(r + shift) + " (" + where(r) + ")"; }
  certify::Violation shifted(certify::Violation v) const {
    for (auto& f : v.face) f = static_cast<std::uint32_t>(f + shift);
    if (v.point != certify::npos) v.point += shift;
    return v;
  }
};

/// Prints the verdict on standard output; returns the exit status (0: Delaunay,
/// and canonical when asked; 1 otherwise).
inline int print_certify_text(const certify::Report& report, const Certify_names& names, const std::string& points,
                              bool canonical, bool all) {
  const std::string& sname = names.simplices;
  const auto describe = [&](const certify::Violation& v) { return certify::describe(names.shifted(v), names); };
  const std::string what = std::to_string(report.simplices) + " simplices, " + std::to_string(report.points) +
                           " points (" + std::to_string(report.distinct_points) + " distinct)";
  if (report.canonical) {
    std::printf("delaunay canonical: %s is the canonical Delaunay triangulation of %s (%s)\n", sname.c_str(),
                points.c_str(), what.c_str());
  } else if (report.delaunay) {
    std::printf("delaunay not-canonical: %s is a Delaunay triangulation of %s but not the canonical one (%s)\n",
                sname.c_str(), points.c_str(), what.c_str());
  } else if (all) {  // the list below starts with the first violation: not printed twice
    std::printf("not delaunay: %s is not a Delaunay triangulation of %s (%zu violations):\n", sname.c_str(),
                points.c_str(), report.violations.size());
  } else {
    std::printf("not delaunay: %s is not a Delaunay triangulation of %s: %s\n", sname.c_str(), points.c_str(),
                describe(*report.first_fatal()).c_str());
  }
  if (!report.delaunay && names.format == "qhull" && report.first_fatal()->rule == certify::Rule::index_out_of_range)
    std::printf("  (Qhull numbers the centrum points it adds to non-simplicial facets past the input: run qdelaunay with Qt)\n");
  if (all) {
    for (const auto& v : report.violations) std::printf("  %s\n", describe(v).c_str());
  } else if (report.delaunay && !report.canonical) {
    std::printf("  %s\n", describe(*report.first_note()).c_str());
  }
  if (canonical && report.delaunay && !report.canonical) std::printf("--canonical: fails\n");
  return report.delaunay && (report.canonical || !canonical) ? 0 : 1;
}

}  // namespace dewall::cli
