// restart_with_huge_pages (huge_pages.hpp).
#include "dewall/io/huge_pages.hpp"

#include <gnu/libc-version.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace dewall::io {
namespace {

/// glibc reads the hugetlb tunable from 2.35 on.
bool glibc_reads_hugetlb() {
  int major = 0, minor = 0;
  if (std::sscanf(gnu_get_libc_version(), "%d.%d", &major, &minor) != 2) return false;
  return major > 2 || (major == 2 && minor >= 35);
}

/// "always" or "madvise" chosen in /sys/kernel/mm/transparent_hugepage/enabled
/// (the choice is in brackets: "always [madvise] never").
bool kernel_offers_huge_pages() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!std::getline(f, line)) return false;
  return line.find("[always]") != std::string::npos || line.find("[madvise]") != std::string::npos;
}

}  // namespace

void restart_with_huge_pages(char** argv) {
  const char* given = std::getenv("GLIBC_TUNABLES");
  std::string tunables = given ? given : "";
  // Set already: the user's choice, or this is the restarted program.
  if (tunables.find("glibc.malloc.hugetlb") != std::string::npos) return;
  if (!glibc_reads_hugetlb() || !kernel_offers_huge_pages()) return;
  const std::string with = tunables + (tunables.empty() ? "" : ":") + "glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", with.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Not restarted (no /proc): go on as we are, leaving the environment as it was.
  if (given) setenv("GLIBC_TUNABLES", given, 1);
  else unsetenv("GLIBC_TUNABLES");
}

}  // namespace dewall::io
