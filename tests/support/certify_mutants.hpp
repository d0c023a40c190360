// The certifier tests' mutants: a triangulation changed in the ways that break
// each kind of check (rows dropped, repeated, a vertex replaced, an index out of
// range, a repeated vertex, an overlapping row, a point left out, the rows
// reordered and reoriented).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace dewall::test {

/// Calls f(name, rows) for each mutant of the triangulation `t` of
/// `point_count` points (at least two rows), drawing from `rng` in a fixed order.
template <int D, class F>
void for_each_mutant(std::size_t point_count, const std::vector<std::array<std::uint32_t, D + 1>>& t, std::mt19937_64& rng,
                     F&& f) {
  using Rows = std::vector<std::array<std::uint32_t, D + 1>>;
  const auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
  const auto mutant = [&](const std::string& name, auto change) {
    Rows m = t;
    change(m);
    f(name, static_cast<const Rows&>(m));
  };
  mutant("a row dropped", [&](Rows& m) { m.erase(m.begin() + static_cast<std::ptrdiff_t>(pick(m.size()))); });
  mutant("the first row dropped", [&](Rows& m) { m.erase(m.begin()); });
  mutant("a row repeated, reordered", [&](Rows& m) {
    auto row = m[pick(m.size())];
    std::reverse(row.begin(), row.end());
    m.push_back(row);
  });
  mutant("a vertex replaced", [&](Rows& m) { m[pick(m.size())][pick(D + 1)] = static_cast<std::uint32_t>(pick(point_count)); });
  mutant("three vertices replaced", [&](Rows& m) {
    for (int k = 0; k < 3; ++k) m[pick(m.size())][pick(D + 1)] = static_cast<std::uint32_t>(pick(point_count));
  });
  mutant("an index out of range", [&](Rows& m) { m[pick(m.size())][pick(D + 1)] = static_cast<std::uint32_t>(point_count + 2); });
  mutant("a repeated vertex", [&](Rows& m) {
    auto& row = m[pick(m.size())];
    row[1] = row[0];
  });
  mutant("a row of the first simplex's neighbourhood added", [&](Rows& m) {
    auto row = m[0];
    row[0] = m[1][0] == row[1] ? m[1][1] : m[1][0];
    m.push_back(row);
  });
  mutant("every row of a point removed", [&](Rows& m) {
    const std::uint32_t v = m[pick(m.size())][0];
    std::erase_if(m, [&](const auto& row) { return std::find(row.begin(), row.end(), v) != row.end(); });
  });
  mutant("rows shuffled and reoriented", [&](Rows& m) {
    std::shuffle(m.begin(), m.end(), rng);
    for (auto& row : m) std::shuffle(row.begin(), row.end(), rng);
  });
  mutant("rows reversed and two swapped vertices in the first", [&](Rows& m) {
    std::reverse(m.begin(), m.end());
    std::swap(m[0][0], m[0][D]);
  });
}

}  // namespace dewall::test
