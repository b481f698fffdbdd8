#pragma once
// Errors of the client SDK: no exception leaves the library. Calls that
// produce a value return a Result<T> (the value, or the Error); the others
// return an Error whose code is kOk on success. Codes and their names are
// gRPC's (a server's refusal keeps the server's code and message).

#include <optional>
#include <string>
#include <utility>

#include "haptics/export.h"

namespace haptics {

/// gRPC's status codes, same numbers.
enum class Code : int {
  kOk = 0,
  kCancelled = 1,
  kUnknown = 2,
  kInvalidArgument = 3,
  kDeadlineExceeded = 4,
  kNotFound = 5,
  kAlreadyExists = 6,
  kPermissionDenied = 7,
  kResourceExhausted = 8,
  kFailedPrecondition = 9,
  kAborted = 10,
  kOutOfRange = 11,
  kUnimplemented = 12,
  kInternal = 13,
  kUnavailable = 14,
  kDataLoss = 15,
  kUnauthenticated = 16,
};

/// "OK", "NOT_FOUND", "UNAVAILABLE", ...: gRPC's name of `code`.
HAPTICS_EXPORT const char* CodeName(Code code);

struct Error {
  Code code = Code::kOk;
  std::string message;

  bool ok() const { return code == Code::kOk; }
  /// "NOT_FOUND: no scene 'x'"; "OK" when ok().
  HAPTICS_EXPORT std::string ToString() const;
};

/// A value or the Error that kept it from being made.
template <typename T>
class Result {
 public:
  Result(T value) : value_(std::move(value)) {}
  /// An error whose code is kOk is taken as kUnknown: a Result without a
  /// value is never ok().
  Result(Error error) : error_(std::move(error)) {
    if (error_.ok()) error_.code = Code::kUnknown;
  }

  bool ok() const { return value_.has_value(); }
  /// kOk when ok().
  const Error& error() const { return error_; }
  /// Only when ok().
  T& value() & { return *value_; }
  const T& value() const& { return *value_; }
  T&& value() && { return std::move(*value_); }
  T& operator*() & { return *value_; }
  const T& operator*() const& { return *value_; }
  T&& operator*() && { return std::move(*value_); }
  T* operator->() { return &*value_; }
  const T* operator->() const { return &*value_; }

 private:
  std::optional<T> value_;
  Error error_;
};

}  // namespace haptics
