// OCCLUDE_ASSERT: the one check of internal invariants (conditions the code itself guarantees,
// never user input: bad files, options and config keys get clear errors that are always
// compiled in). Active when NDEBUG is not defined: in Debug builds and in CI's sanitizer lane
// (-O1 without NDEBUG); compiled out in Release, where the condition is not evaluated.
// A failed assertion prints the file, line, condition and message on stderr and aborts.
//
// In io because io is the bottom of the dependency chain: every target of the project sees it.
#pragma once

namespace occlude::detail {
/// Prints "occlude: internal error: FILE:LINE: assertion `CONDITION` failed: MESSAGE" and aborts.
[[noreturn]] void AssertionFailed(const char* file, int line, const char* condition,
                                  const char* message);
}  // namespace occlude::detail

#ifdef NDEBUG
// Not evaluated, but its names count as used (no unused-variable warnings in Release).
#define OCCLUDE_ASSERT(condition, message) static_cast<void>(sizeof(!(condition)))
#else
/// Checks an internal invariant; `message` (a string literal) says what it means.
#define OCCLUDE_ASSERT(condition, message) \
  ((condition) ? static_cast<void>(0)      \
               : ::occlude::detail::AssertionFailed(__FILE__, __LINE__, #condition, message))
#endif
