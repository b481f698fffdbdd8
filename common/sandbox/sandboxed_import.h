#pragma once
// Importing model files nobody vouches for (uploads, files named on
// hapticctl's command line) in a child process: the haptic-import worker,
// which limits its own CPU time, memory and stack, reads the one file, then
// can open no file, socket or program (seccomp) before a reader parses it.
// A crash, a hang or a limit hit there costs the child, never the caller.

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "common/model/import.h"

namespace hs {

/// What the worker may use.
struct SandboxLimits {
  /// CPU time, seconds (RLIMIT_CPU).
  double cpu_s = 30;
  /// Wall time before the worker is killed, seconds.
  double wall_s = 60;
  /// Address space, bytes (RLIMIT_AS).
  int64_t memory_bytes = int64_t{4} << 30;
  /// Stack, bytes (RLIMIT_STACK): a file nested deeper than this holds
  /// crashes the worker instead of the caller.
  int64_t stack_bytes = int64_t{8} << 20;
};

/// ImportModel(path, options), run in the worker. Errors as ImportModel,
/// with the file named; also INVALID_ARGUMENT naming the file when the
/// worker crashes ("the importer crashed (SIGSEGV)"), runs out of CPU or
/// wall time or memory, or refers to other files (they are not read);
/// UNAVAILABLE when the worker cannot be started.
absl::StatusOr<ImportedModel> SandboxedImport(const std::string& path,
                                              const ImportOptions& options = {},
                                              const SandboxLimits& limits = {});

/// The worker binary: $HAPTIC_IMPORT_WORKER if set, else haptic-import
/// beside the running program, else the one the build made.
std::string ImportWorkerPath();

}  // namespace hs
