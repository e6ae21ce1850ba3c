// The FMU binary's glibc floor: glibc 2.28 (Debian 10, RHEL 8, Ubuntu 18.10).
//
// glibc 2.29 gave exp, log, pow (and 2.35 hypot) new symbol versions (the
// same functions without the SVID error handling's wrapper); a binary linked
// on a newer glibc takes the newest version and will not load on an older
// one. The FMU is linked with --wrap for each (CMakeLists.txt), so that
// every reference, the core's and the statically linked libstdc++'s
// included, comes here, and from here goes to the oldest version, which
// every x86-64 glibc has and which computes the same values (today's glibc
// keeps it as a wrapper of the same implementation).
//
// __libc_single_threaded (glibc 2.32), which libstdc++'s headers read to skip
// atomic reference counts in a single-threaded process, is wrapped as a
// constant 0: "maybe several threads", the behaviour before glibc 2.32
// (always atomic), correct in every process.
//
// libgcc stays shared (libgcc_s.so.1, GCC_ symbol versions): its static
// unwinder would need glibc 2.35's _dl_find_object.
//
// tests/test_fmi.py checks the binary's dynamic symbols (objdump -T): no
// GLIBC_ version above 2.28 and no GLIBCXX_ one.
#include <cstdlib>  // (defines __GLIBC__ on glibc)

#if defined(__linux__) && defined(__x86_64__) && defined(__GLIBC__)

#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

extern "C" {

double leadscrew_exp_2_2_5(double);
double leadscrew_log_2_2_5(double);
double leadscrew_pow_2_2_5(double, double);
double leadscrew_hypot_2_2_5(double, double);
__asm__(".symver leadscrew_exp_2_2_5, exp@GLIBC_2.2.5");
__asm__(".symver leadscrew_log_2_2_5, log@GLIBC_2.2.5");
__asm__(".symver leadscrew_pow_2_2_5, pow@GLIBC_2.2.5");
__asm__(".symver leadscrew_hypot_2_2_5, hypot@GLIBC_2.2.5");

__attribute__((visibility("hidden"))) double __wrap_exp(double x) {
  return leadscrew_exp_2_2_5(x);
}
__attribute__((visibility("hidden"))) double __wrap_log(double x) {
  return leadscrew_log_2_2_5(x);
}
__attribute__((visibility("hidden"))) double __wrap_pow(double x, double y) {
  return leadscrew_pow_2_2_5(x, y);
}
__attribute__((visibility("hidden"))) double __wrap_hypot(double x, double y) {
  return leadscrew_hypot_2_2_5(x, y);
}
__attribute__((visibility("hidden"))) char __wrap___libc_single_threaded = 0;

// What the static libstdc++ calls, versioned anew since 2.28: pthread_once
// and __pthread_key_create (2.34: moved from libpthread into libc, their old
// versions kept), fstat64 (2.33: a function of its own; before, __fxstat64
// with the stat structure's version, 1 on x86-64), arc4random (2.36, for
// std::random_device: getentropy, glibc 2.25, draws the same kernel bytes).
int leadscrew_pthread_once_2_2_5(pthread_once_t*, void (*)());
int leadscrew_pthread_key_create_2_2_5(pthread_key_t*, void (*)(void*));
int leadscrew_fxstat64_2_2_5(int, int, struct stat64*);
__asm__(".symver leadscrew_pthread_once_2_2_5, pthread_once@GLIBC_2.2.5");
__asm__(".symver leadscrew_pthread_key_create_2_2_5, __pthread_key_create@GLIBC_2.2.5");
__asm__(".symver leadscrew_fxstat64_2_2_5, __fxstat64@GLIBC_2.2.5");

__attribute__((visibility("hidden"))) int __wrap_pthread_once(pthread_once_t* once,
                                                               void (*init)()) {
  return leadscrew_pthread_once_2_2_5(once, init);
}
__attribute__((visibility("hidden"))) int __wrap___pthread_key_create(pthread_key_t* key,
                                                                       void (*done)(void*)) {
  return leadscrew_pthread_key_create_2_2_5(key, done);
}
__attribute__((visibility("hidden"))) int __wrap_fstat64(int fd, struct stat64* buffer) {
  return leadscrew_fxstat64_2_2_5(1, fd, buffer);
}
__attribute__((visibility("hidden"))) unsigned __wrap_arc4random() {
  unsigned value = 0;
  if (getentropy(&value, sizeof value) != 0) abort();
  return value;
}

}  // extern "C"

#endif
