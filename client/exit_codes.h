#pragma once
// Exit statuses of hapticctl that scripts can rely on. Commands that talk
// to a server map the gRPC status they got (server_call.h: ExitCodeFor).

namespace hs::cli {

/// The command did what was asked.
inline constexpr int kExitOk = 0;
/// The command ran but failed: bad file, server error without a more
/// specific status below (INTERNAL, UNKNOWN, CANCELLED, ...).
inline constexpr int kExitFailure = 1;
/// The command line itself was wrong (unknown flag, missing argument,
/// value out of range).
inline constexpr int kExitUsage = 2;
/// The server could not be reached, went away (UNAVAILABLE: not
/// listening, shutting down, scene deleted under a stream) or did not
/// answer in time (DEADLINE_EXCEEDED).
inline constexpr int kExitUnavailable = 3;
/// The server refused the request: INVALID_ARGUMENT, ALREADY_EXISTS,
/// FAILED_PRECONDITION, RESOURCE_EXHAUSTED, PERMISSION_DENIED,
/// UNAUTHENTICATED, OUT_OF_RANGE, UNIMPLEMENTED.
inline constexpr int kExitRefused = 4;
/// The server does not have the scene, object, tool or model (NOT_FOUND).
inline constexpr int kExitNotFound = 5;
/// `health`: the server answered but is not SERVING.
inline constexpr int kExitNotServing = 6;
/// `replay`: the recording replayed, and a frame differs from the
/// recorded one (or steps could not be re-run).
inline constexpr int kExitDiverged = 7;

}  // namespace hs::cli
