// restart_with_huge_pages (huge_pages.hpp).
#include "dewall/io/huge_pages.hpp"

#include <gnu/libc-version.h>
#include <sys/auxv.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace dewall::io {
namespace {

/// Set in the restarted program: one restart at most, whatever glibc makes
/// of the tunable (it drops tunables for set-user-ID programs, for one).
constexpr const char* restarted_marker = "DEWALL_RESTARTED_FOR_HUGE_PAGES";

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

/// Whether /proc/self/exe is the file this code was loaded from: not when
/// the program was started through the dynamic loader (ld.so PROGRAM …),
/// where /proc/self/exe is the loader and argv[0] is not what it would run.
bool proc_self_exe_is_this_program() {
  struct stat exe;
  if (stat("/proc/self/exe", &exe) != 0) return false;
  const auto here = reinterpret_cast<std::uintptr_t>(&proc_self_exe_is_this_program);
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    // start-end perms offset major:minor inode path
    std::istringstream fields(line);
    std::uintptr_t start = 0, end = 0;
    char dash = 0;
    std::string perms, offset, device;
    unsigned long inode = 0;
    if (!(fields >> std::hex >> start >> dash >> end >> perms >> offset >> device >> std::dec >> inode)) continue;
    if (here < start || here >= end) continue;
    return inode == exe.st_ino && inode != 0;
  }
  return false;
}

}  // namespace

void restart_with_huge_pages(char** argv) {
  if (std::getenv(restarted_marker)) {
    unsetenv(restarted_marker);  // not passed on to the programs we start
    return;
  }
  const char* given = std::getenv("GLIBC_TUNABLES");
  std::string tunables = given ? given : "";
  // The user's choice (=0 turns it off).
  if (tunables.find("glibc.malloc.hugetlb") != std::string::npos) return;
  // Secure execution (set-user-ID and the like): glibc ignores the tunable.
  if (getauxval(AT_SECURE) != 0) return;
  if (!glibc_reads_hugetlb() || !kernel_offers_huge_pages() || !proc_self_exe_is_this_program()) return;
  const std::string with = tunables + (tunables.empty() ? "" : ":") + "glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", with.c_str(), 1) != 0 || setenv(restarted_marker, "1", 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Not restarted: go on as we are, leaving the environment as it was.
  if (given) setenv("GLIBC_TUNABLES", given, 1);
  else unsetenv("GLIBC_TUNABLES");
  unsetenv(restarted_marker);
}

}  // namespace dewall::io
