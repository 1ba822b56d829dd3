// The failure path of OCCLUDE_ASSERT (occlude/assert.h).
#include "occlude/assert.h"

#include <cstdio>
#include <cstdlib>

namespace occlude::detail {

void AssertionFailed(const char* file, int line, const char* condition, const char* message) {
  std::fprintf(stderr, "occlude: internal error: %s:%d: assertion `%s` failed: %s\n", file, line,
               condition, message);
  std::fflush(stderr);
  std::abort();
}

}  // namespace occlude::detail
