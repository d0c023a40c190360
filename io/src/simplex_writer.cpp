#include "dewall/io/simplex_writer.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <unistd.h>

namespace dewall::io {

void write_plain(std::ostream& out, const Simplex_table& t) {
  const auto k = static_cast<std::size_t>(t.vertices_per_simplex);
  std::string line;
  for (std::size_t s = 0; s < t.size(); ++s) {
    line.clear();
    for (std::size_t i = 0; i < k; ++i) {
      if (i) line += ' ';
      line += std::to_string(t.indices[s * k + i]);
    }
    line += '\n';
    out << line;
  }
}

void write_ele(std::ostream& out, const Simplex_table& t, std::size_t first_index) {
  const auto k = static_cast<std::size_t>(t.vertices_per_simplex);
  out << t.size() << ' ' << k << " 0\n";
  for (std::size_t s = 0; s < t.size(); ++s) {
    out << s + first_index;
    for (std::size_t i = 0; i < k; ++i) out << ' ' << t.indices[s * k + i] + first_index;
    out << '\n';
  }
}

void write_simplices_file(const std::string& path, const Simplex_table& t, std::size_t first_index) {
  const bool ele = path.size() > 4 && path.compare(path.size() - 4, 4, ".ele") == 0;
  if (path == "-") {
    std::ios::sync_with_stdio(false);
    ele ? write_ele(std::cout, t, first_index) : write_plain(std::cout, t);
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("<stdout>: write error");
    return;
  }
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temporary);
    if (!out) throw std::runtime_error(path + ": cannot create file");
    ele ? write_ele(out, t, first_index) : write_plain(out, t);
    out.flush();
    if (!out) {
      out.close();
      std::remove(temporary.c_str());
      throw std::runtime_error(path + ": write error");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::remove(temporary.c_str());
    throw std::runtime_error(path + ": " + ec.message());
  }
}

}  // namespace dewall::io
