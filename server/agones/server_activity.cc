#include "server/agones/server_activity.h"

namespace hs {

ServerActivity ActivityOf(const SceneRegistry& registry, const std::string& scene) {
  ServerActivity activity{.scene = scene};
  for (const std::shared_ptr<SceneRunner>& runner : registry.List()) {
    if (activity.scene.empty()) activity.scene = runner->name();
    const StreamRegistry::Counts counts = runner->stream_counts();
    activity.devices += counts.devices;
    activity.viewers += counts.viewers;
    activity.devices_joined += counts.devices_joined;
    activity.viewers_joined += counts.viewers_joined;
  }
  return activity;
}

}  // namespace hs
