#ifndef TRIGRAV_EXAMPLES_COMMON_REQUIRE_FLAG_H_
#define TRIGRAV_EXAMPLES_COMMON_REQUIRE_FLAG_H_

// Flag validation for the example tools (header only). A bad flag value is misuse, not a bug: the
// tool prints "error: <message>" on stderr and exits with status 2 (no abort, no stack trace), so
// that scripts and tests can tell misuse from a crash. glog's CHECK stays for internal invariants.

#include <cstdlib>
#include <iostream>
#include <string>

namespace trigrav::examples {

inline constexpr int kBadFlagExitCode = 2;

// Exits with kBadFlagExitCode after printing the message when `ok` is false. Write conditions so
// that NaN fails them (`x > 0.0`, not `!(x <= 0.0)`).
inline void RequireFlag(bool ok, const std::string& message) {
  if (ok) return;
  std::cerr << "error: " << message << std::endl;
  std::exit(kBadFlagExitCode);
}

}  // namespace trigrav::examples

#endif  // TRIGRAV_EXAMPLES_COMMON_REQUIRE_FLAG_H_
