#include "client/pose_args.h"

#include <cmath>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"

namespace hs::cli {

absl::StatusOr<std::vector<double>> ParseNumbers(std::string_view text, size_t count) {
  const std::vector<absl::string_view> parts =
      absl::StrSplit(absl::string_view(text.data(), text.size()), ',');
  if (parts.size() != count) {
    return absl::InvalidArgumentError(
        absl::StrCat("'", std::string(text), "': expected ", count, " comma-separated numbers"));
  }
  std::vector<double> numbers;
  for (absl::string_view part : parts) {
    double value;
    if (!absl::SimpleAtod(part, &value) || !std::isfinite(value)) {
      return absl::InvalidArgumentError(
          absl::StrCat("'", std::string(part), "' is not a finite number"));
    }
    numbers.push_back(value);
  }
  return numbers;
}

absl::StatusOr<Vector3d> ParseVector3(std::string_view text) {
  absl::StatusOr<std::vector<double>> n = ParseNumbers(text, 3);
  if (!n.ok()) return n.status();
  return Vector3d((*n)[0], (*n)[1], (*n)[2]);
}

absl::StatusOr<Isometry3d> ParsePose(std::string_view text) {
  absl::StatusOr<std::vector<double>> n = ParseNumbers(text, 6);
  if (!n.ok()) return n.status();
  return PoseFromNumbers(Vector3d((*n)[0], (*n)[1], (*n)[2]), Vector3d((*n)[3], (*n)[4], (*n)[5]));
}

Isometry3d PoseFromNumbers(const Vector3d& p_m, const Vector3d& rotation_vector) {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = p_m;
  const double angle = rotation_vector.norm();
  if (angle > 0) X.linear() = Eigen::AngleAxisd(angle, rotation_vector / angle).toRotationMatrix();
  return X;
}

}  // namespace hs::cli
