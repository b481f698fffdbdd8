#pragma once
// Parsing the numbers users type on the command line: vectors "x,y,z" and
// poses "x,y,z,rx,ry,rz" (translation in metres, then a rotation vector:
// axis times angle in radians).

#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/status/statusor.h"
#include "common/core/types.h"

namespace hs::cli {

/// Exactly `count` comma-separated finite numbers. INVALID_ARGUMENT
/// otherwise.
absl::StatusOr<std::vector<double>> ParseNumbers(std::string_view text, size_t count);

/// Three comma-separated finite numbers. INVALID_ARGUMENT otherwise.
absl::StatusOr<Vector3d> ParseVector3(std::string_view text);

/// Six comma-separated finite numbers: translation, then rotation vector.
/// INVALID_ARGUMENT otherwise.
absl::StatusOr<Isometry3d> ParsePose(std::string_view text);

/// "ID:x,y,z": a vertex id and its new position. INVALID_ARGUMENT otherwise.
absl::StatusOr<std::pair<int, Vector3d>> ParseVertexMove(std::string_view text);

/// A CLI11 check that runs `parse` on each value of an option, so that a
/// malformed value is a command-line error (exit kExitUsage) with
/// `parse`'s message, before anything runs.
CLI::Validator ValueCheck(std::string description,
                          std::function<absl::Status(const std::string&)> parse);
/// ValueCheck of ParseNumbers(count), ParseVector3, ParsePose, ParseVertexMove.
CLI::Validator NumbersValue(size_t count);
CLI::Validator Vector3Value();
CLI::Validator PoseValue();
CLI::Validator VertexMoveValue();

/// The pose with translation `p_m` (metres) and rotation `rotation_vector`
/// (axis times angle, radians).
Isometry3d PoseFromNumbers(const Vector3d& p_m, const Vector3d& rotation_vector);

}  // namespace hs::cli
