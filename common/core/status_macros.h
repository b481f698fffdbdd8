#pragma once
// absl::Status plumbing. Abseil 20220623 ships no public macros for this.

#include "absl/status/status.h"
#include "absl/status/statusor.h"

#define HS_STATUS_CONCAT_INNER(a, b) a##b
#define HS_STATUS_CONCAT(a, b) HS_STATUS_CONCAT_INNER(a, b)

/// Returns the status from the enclosing function when `expr` is not OK.
#define HS_RETURN_IF_ERROR(expr)                              \
  do {                                                        \
    if (absl::Status hs_status_ = (expr); !hs_status_.ok()) { \
      return hs_status_;                                      \
    }                                                         \
  } while (false)

/// Declares or assigns `lhs` from a StatusOr, returning its status when not OK.
#define HS_ASSIGN_OR_RETURN(lhs, expr) \
  HS_ASSIGN_OR_RETURN_IMPL(HS_STATUS_CONCAT(hs_statusor_, __LINE__), lhs, expr)
#define HS_ASSIGN_OR_RETURN_IMPL(tmp, lhs, expr) \
  auto tmp = (expr);                             \
  if (!tmp.ok()) return tmp.status();            \
  lhs = std::move(tmp).value()
