#pragma once
// A warm heap for the frame-graph benchmarks: memory a run frees stays in the process for the
// next run, so that repeated runs time the code rather than the kernel mapping pages again.
//
// glibc adjusts its thresholds as a program frees large blocks: the first free of a block that
// was mapped on its own raises the size from which blocks are mapped and the free space above
// which the heap's top is given back. What a run then pays for page faults depends on which
// benchmarks ran before it (measured: loading the 10,000-pass JSON graph took 28 ms run alone and
// 87-93 ms after the 100- and 1,000-pass runs, with three times the page faults). Fixed
// thresholds make every benchmark of the process see the same heap, loom's and the peers'.
//
// LOOM_BENCH_DEFAULT_HEAP=1 in the environment leaves glibc's defaults.

#include <cstdlib>
#include <cstring>

#include <malloc.h>

namespace loom::bench {

inline void keep_heap_warm() {
    const char* keep_default = std::getenv("LOOM_BENCH_DEFAULT_HEAP");
    if (keep_default && std::strcmp(keep_default, "0") != 0) return;
    // Blocks up to glibc's largest mapping threshold (32 MiB on 64-bit) come from the heap, and
    // the heap's top is kept up to 1 GiB.
    mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
    mallopt(M_TRIM_THRESHOLD, 1024 * 1024 * 1024);
}

}  // namespace loom::bench
