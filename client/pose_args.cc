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

absl::StatusOr<std::pair<int, Vector3d>> ParseVertexMove(std::string_view text) {
  const size_t colon = text.find(':');
  int id = 0;
  if (colon == std::string_view::npos ||
      !absl::SimpleAtoi(absl::string_view(text.data(), colon), &id)) {
    return absl::InvalidArgumentError(absl::StrCat("'", std::string(text), "': expected ID:x,y,z"));
  }
  absl::StatusOr<Vector3d> p = ParseVector3(text.substr(colon + 1));
  if (!p.ok()) return p.status();
  return std::pair{id, *p};
}

CLI::Validator ValueCheck(std::string description,
                          std::function<absl::Status(const std::string&)> parse) {
  return CLI::Validator(
      [parse = std::move(parse)](std::string& value) -> std::string {
        const absl::Status status = parse(value);
        return status.ok() ? "" : std::string(status.message());
      },
      std::move(description));
}

CLI::Validator NumbersValue(size_t count) {
  return ValueCheck(absl::StrCat(count, " NUMBERS"), [count](const std::string& text) {
    return ParseNumbers(text, count).status();
  });
}
CLI::Validator Vector3Value() {
  return ValueCheck("X,Y,Z", [](const std::string& text) { return ParseVector3(text).status(); });
}
CLI::Validator PoseValue() {
  return ValueCheck("X,Y,Z,RX,RY,RZ", [](const std::string& text) { return ParsePose(text).status(); });
}
CLI::Validator VertexMoveValue() {
  return ValueCheck("ID:X,Y,Z",
                    [](const std::string& text) { return ParseVertexMove(text).status(); });
}

Isometry3d PoseFromNumbers(const Vector3d& p_m, const Vector3d& rotation_vector) {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = p_m;
  const double angle = rotation_vector.norm();
  if (angle > 0) X.linear() = Eigen::AngleAxisd(angle, rotation_vector / angle).toRotationMatrix();
  return X;
}

}  // namespace hs::cli
