// Transparent huge pages for the program's heap.
#pragma once

namespace dewall::io {

/// Restarts the running program (same arguments, same open files) with
/// glibc's malloc asking the kernel for transparent huge pages for its heap
/// (GLIBC_TUNABLES=glibc.malloc.hugetlb=1, glibc 2.35 and later), when the
/// kernel offers them and the environment says nothing about it yet. A
/// triangulation chases pointers through hundreds of megabytes: with 2 MB
/// pages it faults about thirty times fewer pages and runs faster
/// (docs/engines.md has the figures). Call first thing in main; returns when not
/// restarted. GLIBC_TUNABLES=glibc.malloc.hugetlb=0 turns it off (for tools
/// that do not follow exec, such as valgrind without --trace-children=yes).
/// Not restarted: set-user-ID programs, and a program started through the
/// dynamic loader (ld.so PROGRAM).
void restart_with_huge_pages(char** argv);

}  // namespace dewall::io
