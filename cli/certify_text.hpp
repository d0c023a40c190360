// What `dewall certify` prints for a report (the text, or --json's object),
// and its --memory sizes: shared with `dewall-mpi certify`, whose rank 0
// prints the same words.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>

#include "dewall/certify/report.hpp"
#include "dewall/io/quote.hpp"

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

/// The report as one JSON object (--json), with a newline. `line(r)`: the
/// text file's line of row r, or certify::npos (binary files have none);
/// `seconds`: the certification's.
inline std::string certify_json(const certify::Report& report, const Certify_names& names,
                                const std::function<std::size_t(std::size_t)>& line, double seconds) {
  const std::size_t shift = names.shift;
  const auto line_member = [&](const char* key, std::size_t r) {
    const std::size_t l = line(r);
    return l == certify::npos ? std::string() : ",\"" + std::string(key) + "\":" + std::to_string(l);
  };
  std::string out = "{\"delaunay\":" + std::string(report.delaunay ? "true" : "false") +
                    ",\"canonical\":" + (report.canonical ? "true" : "false") +
                    ",\"dimension\":" + std::to_string(report.dimension) +
                    ",\"points\":" + std::to_string(report.points) +
                    ",\"distinct_points\":" + std::to_string(report.distinct_points) +
                    ",\"simplices\":" + std::to_string(report.simplices) +
                    ",\"interior_facets\":" + std::to_string(report.interior_facets) +
                    ",\"boundary_facets\":" + std::to_string(report.boundary_facets) +
                    ",\"cospherical_facets\":" + std::to_string(report.cospherical_facets) +
                    ",\"format\":" + io::json_string(names.format) + ",\"seconds\":" + std::to_string(seconds) +
                    ",\"violations\":[";
  for (std::size_t i = 0; i < report.violations.size(); ++i) {
    const auto v = names.shifted(report.violations[i]);
    out += i ? "," : "";
    out += "{\"rule\":" + io::json_string(certify::rule_name(v.rule)) + ",\"fatal\":" + (v.fatal() ? "true" : "false");
    if (v.simplex != certify::npos) out += ",\"simplex\":" + std::to_string(v.simplex + shift) + line_member("line", v.simplex);
    if (v.other_simplex != certify::npos)
      out += ",\"other_simplex\":" + std::to_string(v.other_simplex + shift) + line_member("other_line", v.other_simplex);
    if (!v.face.empty()) {
      out += ",\"face\":[";
      for (std::size_t j = 0; j < v.face.size(); ++j) {
        if (j) out += ',';
        out += std::to_string(v.face[j]);
      }
      out += "]";
    }
    if (v.point != certify::npos) out += ",\"point\":" + std::to_string(v.point);
    out += ",\"message\":" + io::json_string(certify::describe(v, names)) + "}";
  }
  out += "]}\n";
  return out;
}

/// A --memory size: "512M", "4G", "65536" (K, M, G: powers of 1024), at most
/// 2^50 bytes; nothing when `digits` is not a positive whole number.
inline std::optional<std::size_t> memory_size(std::string digits) {
  std::size_t unit = 1;
  if (!digits.empty() && std::string("kKmMgG").find(digits.back()) != std::string::npos) {
    const char u = digits.back();
    unit = u == 'k' || u == 'K' ? std::size_t{1} << 10 : u == 'm' || u == 'M' ? std::size_t{1} << 20 : std::size_t{1} << 30;
    digits.pop_back();
  }
  if (digits.empty() || digits.size() > 16 || digits.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  const std::size_t n = std::stoull(digits);
  if (n < 1 || n > (std::size_t{1} << 50) / unit) return std::nullopt;
  return n * unit;
}

}  // namespace dewall::cli
