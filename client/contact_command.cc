#include "client/contact_command.h"

#include <memory>

#include "client/contact_json.h"
#include "client/exit_codes.h"
#include "client/pose_args.h"
#include "common/contact/contact_query.h"
#include "common/model/import.h"

namespace hs::cli {
namespace {

// Query tolerances up to this (relative) fit the collision models built here.
constexpr double kMaxRelativeTolerance = 1e-6;

absl::StatusOr<ContactSet> Compute(const ContactArgs& args) {
  ImportOptions import;
  import.unit_scale = args.unit_scale;
  absl::StatusOr<ImportedModel> moving = ImportModel(args.moving_file, import);
  if (!moving.ok()) return moving.status();
  absl::StatusOr<ImportedModel> fixed = ImportModel(args.fixed_file, import);
  if (!fixed.ok()) return fixed.status();
  absl::StatusOr<Isometry3d> X_WM = ParsePose(args.pose_moving);
  if (!X_WM.ok()) return X_WM.status();
  absl::StatusOr<Isometry3d> X_WF = ParsePose(args.pose_fixed);
  if (!X_WF.ok()) return X_WF.status();
  absl::StatusOr<Vector3d> direction = ParseVector3(args.direction);
  if (!direction.ok()) return direction.status();
  absl::StatusOr<BvType> bv = ParseBvType(args.bv);
  if (!bv.ok()) return bv.status();
  if (!(args.relative_tolerance >= 0 && args.relative_tolerance <= kMaxRelativeTolerance)) {
    return absl::InvalidArgumentError("--tolerance must be in [0, 1e-6]");
  }
  auto margin = [](const HapticObject& o) {
    return kMaxRelativeTolerance * o.bounding_box().diagonal().norm();
  };
  const CollisionModel moving_model(moving->object, *bv, margin(moving->object));
  const CollisionModel fixed_model(fixed->object, *bv, margin(fixed->object));
  ContactQuery query;
  query.direction_W = *direction;
  query.method = args.method == "paper" ? ContactMethod::kPaper2d : ContactMethod::kSweep3d;
  query.relative_tolerance = args.relative_tolerance;
  query.continuous = args.continuous;
  return ComputeContact({&moving->object, &moving_model, *X_WM},
                        {&fixed->object, &fixed_model, *X_WF}, query);
}

void PrintText(const ContactSet& set, std::ostream& out) {
  out << "colliding: " << (set.colliding ? "yes" : "no") << "\n";
  if (!set.colliding) return;
  out << "penetrating: " << (set.penetrating ? "yes" : "no") << "\n"
      << "depth_m: " << set.depth_m << "\n"
      << "reversing_vector_W_m: " << set.reversing_vector_W.transpose() << "\n"
      << "normal_W: " << set.normal_W.transpose() << "\n"
      << "moving: " << FeatureKindName(set.moving.kind) << " (" << set.moving.vertices.size()
      << " vertices, " << set.moving.edges.size() << " edges, " << set.moving.faces.size()
      << " faces)\n"
      << "fixed: " << FeatureKindName(set.fixed.kind) << " (" << set.fixed.vertices.size()
      << " vertices, " << set.fixed.edges.size() << " edges, " << set.fixed.faces.size()
      << " faces)\n"
      << "points: " << set.points.size() << "\n";
  if (set.time_of_impact) out << "time_of_impact: " << *set.time_of_impact << "\n";
  if (set.singular_case) out << "singular case: yes\n";
  if (set.fallback) out << "fallback: yes\n";
}

}  // namespace

int RunContact(const ContactArgs& args, std::ostream& out, std::ostream& err) {
  absl::StatusOr<ContactSet> set = Compute(args);
  if (!set.ok()) {
    err << "hapticctl contact: " << set.status().message() << "\n";
    return kExitFailure;
  }
  if (args.json) {
    out << ContactSetToJson(*set).dump() << "\n";
  } else {
    PrintText(*set, out);
  }
  return kExitOk;
}

void AddContactCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ContactArgs>();
  CLI::App* cmd = app.add_subcommand("contact", "Contact set of a moving and a fixed model");
  cmd->add_option("moving", args->moving_file, "Model file of the moving object")->required();
  cmd->add_option("fixed", args->fixed_file, "Model file of the fixed object")->required();
  cmd->add_option("--pose-moving", args->pose_moving,
                  "x,y,z,rx,ry,rz: translation (m) and rotation vector (rad)")
      ->check(PoseValue());
  cmd->add_option("--pose-fixed", args->pose_fixed, "x,y,z,rx,ry,rz of the fixed object")
      ->check(PoseValue());
  cmd->add_option("--direction", args->direction, "dx,dy,dz: motion of the moving object")
      ->required()
      ->check(Vector3Value());
  cmd->add_option("--method", args->method, "paper (2D projections) or 3d (exact sweep)")
      ->check(CLI::IsMember({"paper", "3d"}));
  cmd->add_option("--bv", args->bv, "Bounding volume: obbrss, obb, rss, kios, aabb")
      ->check(CLI::IsMember({"obbrss", "obb", "rss", "kios", "aabb"}));
  cmd->add_option(
      "--tolerance", args->relative_tolerance,
      "Touching tolerance relative to the pair's size, the sum of the box diagonals (<= 1e-6)");
  cmd->add_option("--unit-scale", args->unit_scale, "Metres per file unit")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--continuous", args->continuous,
                "The direction is the whole last step (m): find contact along it");
  cmd->add_flag("--json", args->json, "Print one JSON object");
  cmd->callback([args, &exit_code] { exit_code = RunContact(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli
