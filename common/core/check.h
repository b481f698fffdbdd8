#pragma once
// Always-on invariant checks. A failed check is a bug in this project, never
// bad input (bad input gets an absl::Status), so it aborts with file:line.

#include <cstdio>
#include <cstdlib>

/// Aborts with file:line and the condition text when `cond` is false, in every build type.
#define HS_CHECK(cond)                                                              \
  do {                                                                              \
    if (!(cond)) {                                                                  \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
      std::abort();                                                                 \
    }                                                                               \
  } while (false)
