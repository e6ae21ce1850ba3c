// Counts heap allocations of the whole process (SUNDIALS' C code included):
// malloc, calloc and realloc defined in the executable take precedence over
// glibc's for every shared library, and forward to glibc's implementations.
#include "allocation_counter.hpp"

#include <cstddef>

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void __libc_free(void* p);
}

namespace {
unsigned long allocations = 0;
}

unsigned long allocation_count() { return allocations; }

extern "C" {
void* malloc(std::size_t size) {
  ++allocations;
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  ++allocations;
  return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) {
  ++allocations;
  return __libc_realloc(p, size);
}
void free(void* p) { __libc_free(p); }
}
