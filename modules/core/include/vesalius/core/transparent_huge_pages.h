// Large matrices in 2 MB pages (a process-wide malloc setting, chosen when the program starts).
//
// The first touch of fresh memory costs one page fault per 4 kB page, about 20 µs each on the project's
// virtual machine: filling 840 MB (the Z of bench_fit's 39k-tet fit) took 4.0 s, 1.5 s in 2 MB pages, and
// the search-direction benchmark's process faulted 866k times (7 s of system time) against 37k. The kernel
// gives 2 MB pages to memory that asks for them when transparent_hugepage is "madvise" (this machine's
// setting) and to all memory when it is "always". glibc asks for them on its heap and mmapped blocks
// when started with the tunable glibc.malloc.hugetlb=1, which it reads only at startup, so the program
// is executed again with it. Results do not change (only how memory is mapped).
#pragma once

namespace vesalius {

// Call first in main. Unless GLIBC_TUNABLES already names glibc.malloc.hugetlb (the user's choice is
// kept), adds glibc.malloc.hugetlb=1 to it and replaces the process by a new run of the same program with
// the same argv (/proc/self/exe); if that fails, returns and the program runs on as it is. A no-op
// outside glibc on Linux.
void restartWithTransparentHugePages(char** argv);

}  // namespace vesalius
