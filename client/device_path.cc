#include "client/device_path.h"

#include <cmath>
#include <fstream>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/strip.h"
#include "client/pose_args.h"
#include "client/tool_path.h"
#include "nlohmann/json.hpp"

namespace hs::cli {
namespace {

// {"scene": "NAME"} with no pose: the header line of a JSON lines path.
bool IsHeader(const nlohmann::json& entry) {
  return entry.is_object() && !entry.contains("pose") && entry.contains("scene") &&
         entry["scene"].is_string();
}

absl::StatusOr<std::vector<TimedPose>> ReadJsonLines(const std::string& path, double rate_hz) {
  std::ifstream in(path);
  if (!in) return absl::NotFoundError(path + ": cannot open");
  std::vector<TimedPose> poses;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    const nlohmann::json entry = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (poses.empty() && IsHeader(entry)) continue;
    if (!entry.is_object() || !entry.contains("pose") || !entry["pose"].is_array() ||
        entry["pose"].size() != 6) {
      return absl::InvalidArgumentError(where + R"(expected {"t_s": T, "pose": [x,y,z,rx,ry,rz]})");
    }
    double n[6];
    for (int i = 0; i < 6; ++i) {
      if (!entry["pose"][i].is_number() || !std::isfinite(n[i] = entry["pose"][i].get<double>())) {
        return absl::InvalidArgumentError(where + "pose numbers must be finite");
      }
    }
    TimedPose pose;
    pose.t_s = static_cast<double>(poses.size()) / rate_hz;
    if (entry.contains("t_s")) {
      if (!entry["t_s"].is_number()) return absl::InvalidArgumentError(where + "t_s: not a number");
      pose.t_s = entry["t_s"].get<double>();
    }
    if (!std::isfinite(pose.t_s) || (!poses.empty() && pose.t_s < poses.back().t_s)) {
      return absl::InvalidArgumentError(where + "times must be finite and not decrease");
    }
    pose.X_WD = PoseFromNumbers(Vector3d(n[0], n[1], n[2]), Vector3d(n[3], n[4], n[5]));
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace

absl::StatusOr<std::vector<TimedPose>> ReadDevicePath(const std::string& path, double rate_hz) {
  if (absl::EndsWith(path, ".jsonl")) return ReadJsonLines(path, rate_hz);
  absl::StatusOr<std::vector<Isometry3d>> csv = ReadToolPath(path);
  if (!csv.ok()) return csv.status();
  std::vector<TimedPose> poses(csv->size());
  for (size_t i = 0; i < poses.size(); ++i) {
    poses[i] = {static_cast<double>(i) / rate_hz, (*csv)[i]};
  }
  return poses;
}

absl::StatusOr<std::string> DevicePathScene(const std::string& path) {
  std::ifstream in(path);
  if (!in) return absl::NotFoundError(path + ": cannot open");
  const bool json_lines = absl::EndsWith(path, ".jsonl");
  constexpr absl::string_view kCsvHeader = "# scene:";
  for (std::string line; std::getline(in, line);) {
    const absl::string_view text = absl::StripAsciiWhitespace(line);
    if (text.empty()) continue;
    if (json_lines) {
      const nlohmann::json entry = nlohmann::json::parse(std::string(text), nullptr, false);
      return IsHeader(entry) ? entry["scene"].get<std::string>() : "";
    }
    if (absl::StartsWith(text, kCsvHeader)) {
      return std::string(absl::StripAsciiWhitespace(text.substr(kCsvHeader.size())));
    }
    if (!absl::StartsWith(text, "#")) return "";
  }
  return "";
}

absl::StatusOr<Motion> ParseMotion(const std::string& name) {
  if (name == "press") return Motion::kPress;
  if (name == "sweep") return Motion::kSweep;
  return absl::InvalidArgumentError("unknown motion '" + name + "' (press, sweep)");
}

Vector3d MotionOffset(Motion motion, double t_s, const MotionParams& params) {
  const double t = t_s + params.phase_s;
  if (motion == Motion::kPress) {
    return params.press_direction * params.depth_m * 0.5 * (1 - std::cos(2 * M_PI * t));
  }
  const double down = params.depth_m * std::min(1.0, std::max(0.0, t / 0.25));
  return Vector3d(params.amplitude_m * std::sin(M_PI * t), 0, -down);
}

std::vector<TimedPose> MotionPath(Motion motion, const Isometry3d& start, double rate_hz,
                                  double duration_s, const MotionParams& params) {
  const auto count = static_cast<size_t>(std::llround(duration_s * rate_hz));
  std::vector<TimedPose> poses(count);
  for (size_t i = 0; i < count; ++i) {
    poses[i].t_s = static_cast<double>(i) / rate_hz;
    poses[i].X_WD = start;
    poses[i].X_WD.translation() += MotionOffset(motion, poses[i].t_s, params);
  }
  return poses;
}

}  // namespace hs::cli
