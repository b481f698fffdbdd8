#include "client/inspect_command.h"

#include <memory>

#include <nlohmann/json.hpp>

#include "client/exit_codes.h"
#include "client/json_text.h"
#include "common/hds/mesh_report.h"
#include "common/model/import.h"
#include "common/sandbox/sandboxed_import.h"

namespace hs::cli {
namespace {

nlohmann::ordered_json Summary(const std::string& file, const ImportedModel& model) {
  const HapticObject& o = model.object;
  const MeshReport report = InspectMesh(o);
  const CleaningReport& c = model.cleaning;
  nlohmann::ordered_json materials = nlohmann::ordered_json::array();
  for (const Material& m : o.materials()) {
    materials.push_back({{"name", m.name},
                         {"stiffness_n_per_m", m.stiffness_n_per_m},
                         {"damping_ns_per_m", m.damping_ns_per_m},
                         {"static_friction", m.static_friction},
                         {"dynamic_friction", m.dynamic_friction}});
  }
  const auto& box = o.bounding_box();
  return {
      {"file", file},
      {"reader", model.reader},
      {"vertices", o.num_vertices()},
      {"edges", o.num_edges()},
      {"faces", o.num_faces()},
      {"materials", materials},
      {"bounding_box_m",
       {{"min", {box.min().x(), box.min().y(), box.min().z()}},
        {"max", {box.max().x(), box.max().y(), box.max().z()}}}},
      {"smallest_box_edge_m", o.smallest_box_edge()},
      {"closed", report.closed},
      {"consistently_oriented", report.consistently_oriented},
      {"euler_characteristic", report.euler_characteristic},
      {"connected_components", report.connected_components},
      {"boundary_edges", report.boundary_edges},
      {"non_manifold_edges", report.non_manifold_edges},
      {"degenerate_faces", report.degenerate_faces.size()},
      {"duplicate_vertices", report.duplicate_vertices},
      {"cleaning",
       {{"input_vertices", c.input_vertices},
        {"input_polygons", c.input_polygons},
        {"input_triangles", c.input_triangles},
        {"welded_vertices", c.welded_vertices},
        {"dropped_unreferenced_vertices", c.dropped_unreferenced_vertices},
        {"dropped_degenerate_triangles", c.dropped_degenerate_triangles},
        {"dropped_duplicate_triangles", c.dropped_duplicate_triangles}}},
  };
}

}  // namespace

int RunInspect(const InspectArgs& args, std::ostream& out, std::ostream& err) {
  ImportOptions options;
  options.unit_scale = args.unit_scale;
  options.weld_relative_tolerance = args.weld_relative_tolerance;
  // The file may come from anywhere: a reader that crashes or loops costs
  // the import worker, not this process.
  absl::StatusOr<ImportedModel> model = SandboxedImport(args.file, options);
  if (!model.ok()) {
    err << "hapticctl inspect: " << model.status().message() << "\n";
    return kExitFailure;
  }
  const nlohmann::ordered_json summary = Summary(args.file, *model);
  if (args.json) {
    out << summary.dump() << "\n";
  } else {
    PrintJsonAsText(summary, "", out);
  }
  return kExitOk;
}

void AddInspectCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<InspectArgs>();
  CLI::App* cmd = app.add_subcommand("inspect", "Print the HDS summary of a model file");
  cmd->add_option("file", args->file, "Model file (OBJ, STL, PLY, OFF, DXF, glTF, IV, WRL, ...)")
      ->required();
  cmd->add_option("--unit-scale", args->unit_scale, "Metres per file unit")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--weld-tolerance", args->weld_relative_tolerance,
                  "Weld distance relative to the bounding-box diagonal")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--json", args->json, "Print one JSON object");
  cmd->callback([args, &exit_code] { exit_code = RunInspect(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli
