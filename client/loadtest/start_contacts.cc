#include "client/loadtest/start_contacts.h"

#include "common/api/scene_file.h"

namespace hs::cli {

int ToolPairsTouchingAtStart(const haptics::v1::SceneSpec& spec, const std::string& base_dir) {
  absl::StatusOr<LoadedScene> loaded = BuildScene(spec, base_dir);
  if (!loaded.ok()) return -1;
  const StepFrame& frame = loaded->scene->Step();
  int touching = 0;
  for (const ToolClash& clash : frame.clashes) touching += clash.touching ? 1 : 0;
  return touching;
}

}  // namespace hs::cli
