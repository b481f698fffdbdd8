#include "client/viewer/page_message.h"

#include <cmath>

#include "nlohmann/json.hpp"

namespace hs::cli {
namespace {

using nlohmann::json;

absl::Status Bad(const std::string& what) {
  return absl::InvalidArgumentError("page message: " + what);
}

// Three or four finite numbers under `key`.
absl::StatusOr<Eigen::VectorXd> Numbers(const json& message, const char* key, int count) {
  const auto it = message.find(key);
  if (it == message.end() || !it->is_array() || static_cast<int>(it->size()) != count) {
    return Bad(std::string("'") + key + "' must be an array of " + std::to_string(count) +
               " numbers");
  }
  Eigen::VectorXd out(count);
  for (int i = 0; i < count; ++i) {
    const json& x = (*it)[i];
    if (!x.is_number() || !std::isfinite(x.get<double>())) {
      return Bad(std::string("'") + key + "' must hold finite numbers");
    }
    out[i] = x.get<double>();
  }
  return out;
}

absl::StatusOr<Isometry3d> Pose(const json& message) {
  absl::StatusOr<Eigen::VectorXd> p = Numbers(message, "p", 3);
  if (!p.ok()) return p.status();
  absl::StatusOr<Eigen::VectorXd> q = Numbers(message, "q", 4);
  if (!q.ok()) return q.status();
  if (p->norm() > kMaxPagePositionM) return Bad("'p' is too far from the origin");
  if (std::abs(q->norm() - 1) > 1e-3) return Bad("'q' must be a unit quaternion [w, x, y, z]");
  Isometry3d X = Isometry3d::Identity();
  X.linear() =
      Eigen::Quaterniond((*q)[0], (*q)[1], (*q)[2], (*q)[3]).normalized().toRotationMatrix();
  X.translation() = p->head<3>();
  return X;
}

}  // namespace

absl::StatusOr<PageMessage> ParsePageMessage(std::string_view text) {
  const json message = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!message.is_object()) return Bad("not a JSON object");
  const auto type = message.find("type");
  const auto tool = message.find("tool");
  if (type == message.end() || !type->is_string()) return Bad("no 'type'");
  if (tool == message.end() || !tool->is_string() || tool->get<std::string>().empty() ||
      tool->get<std::string>().size() > 256) {
    return Bad("'tool' must be a tool's name");
  }
  const std::string kind = *type;
  const size_t fields = kind == "pose" ? 4 : 2;
  if (message.size() != fields) return Bad("unexpected fields for '" + kind + "'");
  if (kind == "take") return TakeTool{*tool};
  if (kind == "release") return ReleaseTool{*tool};
  if (kind == "pose") {
    absl::StatusOr<Isometry3d> X = Pose(message);
    if (!X.ok()) return X.status();
    return MoveTool{*tool, *X};
  }
  return Bad("unknown type '" + kind + "'");
}

}  // namespace hs::cli
