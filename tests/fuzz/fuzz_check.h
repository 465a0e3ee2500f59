// The harnesses' assertion: prints what failed and aborts, which libFuzzer (and the replay driver's
// ctest) reports as a crash with the input that caused it. GoogleTest is not linked into fuzzers.
#ifndef TRIGRAV_TESTS_FUZZ_FUZZ_CHECK_H_
#define TRIGRAV_TESTS_FUZZ_FUZZ_CHECK_H_

#include <cstdio>
#include <cstdlib>

#define TRIGRAV_FUZZ_CHECK(condition, what)                                                       \
  do {                                                                                            \
    if (!(condition)) {                                                                           \
      std::fprintf(stderr, "%s:%d: fuzz check failed: %s (%s)\n", __FILE__, __LINE__, #condition, \
                   what);                                                                         \
      std::abort();                                                                               \
    }                                                                                             \
  } while (0)

#endif  // TRIGRAV_TESTS_FUZZ_FUZZ_CHECK_H_
