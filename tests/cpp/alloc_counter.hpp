// Counts heap allocations (malloc, calloc, realloc, memalign, posix_memalign,
// aligned_alloc, and so operator new, which calls malloc) made between
// start() and stop(). Works by interposing glibc's allocation functions in the
// executable (alloc_counter.cpp), which catches Eigen's std::malloc as well as
// operator new.
#pragma once

namespace alloc_counter {
void start();
long stop();  // allocations since start()
}  // namespace alloc_counter
