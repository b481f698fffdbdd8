#include "client/tool_path.h"

#include <fstream>

#include "client/pose_args.h"

namespace hs::cli {

absl::StatusOr<std::vector<Isometry3d>> ReadToolPath(const std::string& path) {
  std::vector<Isometry3d> poses;
  if (path.empty()) return poses;
  std::ifstream in(path);
  if (!in) return absl::NotFoundError(path + ": cannot open");
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    absl::StatusOr<Isometry3d> pose = ParsePose(line);
    if (!pose.ok()) {
      return absl::InvalidArgumentError(path + ":" + std::to_string(number) + ": " +
                                        std::string(pose.status().message()));
    }
    poses.push_back(*pose);
  }
  return poses;
}

}  // namespace hs::cli
