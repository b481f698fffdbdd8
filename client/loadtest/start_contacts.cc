#include "client/loadtest/start_contacts.h"

#include "absl/algorithm/container.h"
#include "common/api/scene_file.h"

namespace hs::cli {

int ToolPairsTouchingAtStart(const haptics::v1::SceneSpec& spec, const std::string& base_dir) {
  absl::StatusOr<LoadedScene> loaded = BuildScene(spec, base_dir);
  if (!loaded.ok()) return -1;
  const StepFrame& frame = loaded->scene->Step();
  return static_cast<int>(
      absl::c_count_if(frame.clashes, [](const ToolClash& clash) { return clash.touching; }));
}

}  // namespace hs::cli
