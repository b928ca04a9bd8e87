// Keeping freed memory in the process for the next allocation (a process-wide malloc setting).
//
// glibc serves every block above 32 MB with its own mmap and returns it with munmap on free, so a
// solver that allocates, fills and frees the same few hundred-MB matrices at every iteration pays a
// page fault per 4 kB page each time (the 39k-tet fit of bench_fit: 3.2M faults, a quarter of its CPU
// time in the kernel). With mmap off (M_MMAP_MAX 0) and the heap's top trimmed only above 2 GB
// (M_TRIM_THRESHOLD), freed blocks go back to the heap and are reused without faults; the price is that
// the process keeps most of its peak memory until it exits. Results do not change (only where blocks live).
#pragma once

namespace vesalius {

// Applies the setting once per process; later calls do nothing. A no-op outside glibc.
void reuseFreedMemory();

}  // namespace vesalius
