// Interposes glibc's allocation functions. This file includes no C library
// header, so that its definitions do not clash with their declarations.
#include <cstddef>
#include <new>

#include "alloc_counter.hpp"

extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
void __libc_free(void* pointer);
}

namespace {
bool counting = false;
long allocations = 0;
inline void count() {
  if (counting) ++allocations;
}
}  // namespace

namespace alloc_counter {
void start() {
  allocations = 0;
  counting = true;
}
long stop() {
  counting = false;
  return allocations;
}
}  // namespace alloc_counter

extern "C" {
void* malloc(std::size_t size) {
  count();
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
  count();
  return __libc_calloc(n, size);
}
void* realloc(void* pointer, std::size_t size) {
  count();
  return __libc_realloc(pointer, size);
}
void* memalign(std::size_t alignment, std::size_t size) {
  count();
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  count();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** result, std::size_t alignment, std::size_t size) {
  count();
  *result = __libc_memalign(alignment, size);
  return *result ? 0 : 12;  // ENOMEM
}
void free(void* pointer) { __libc_free(pointer); }
}
