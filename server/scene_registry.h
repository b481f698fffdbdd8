#pragma once
// The scenes a server holds, by name, with the server's limits. Every
// change builds a new scene from an edited spec and swaps it in only when
// it builds and fits the limits, so a rejected request changes nothing.

#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "server/caller_quotas.h"
#include "server/metrics.h"
#include "server/model_store.h"
#include "server/scene_runner.h"
#include "server/state/scene_catalogue.h"

namespace hs {

/// What one server accepts at most (RESOURCE_EXHAUSTED past these).
struct ServerLimits {
  int max_scenes = 16;
  int max_objects_per_scene = 256;
  int64_t max_triangles_per_scene = 2'000'000;
  /// Open Interact and Watch streams over all scenes.
  int max_clients = 64;
  int64_t max_model_bytes = int64_t{256} << 20;
  int max_models = 64;
  /// A scene's spec, serialized, bytes: it comes back in every SceneInfo
  /// (vertex moves and materials add to it).
  int64_t max_spec_bytes = int64_t{1} << 20;
  /// Vertex moves in one UpdateObject request.
  int max_vertex_moves_per_request = 10'000;
  /// The step lengths a scene may have, seconds (INVALID_ARGUMENT
  /// outside): one thread per scene must keep up with its rate.
  double min_step_s = 1e-4;
  double max_step_s = 1.0;
  /// Threads that step one scene's tools at once (Scene::SetThreads), in
  /// [1, 64]: its runner thread and up to this many - 1 workers.
  int threads_per_scene = 1;
  /// SCHED_FIFO priority (1..99) of those threads; 0: the default
  /// scheduler. A scene whose step outlasts its period then holds its
  /// cores, so it is the operator's choice (haptic-server
  /// --realtime-priority), checked when the server starts.
  int realtime_priority = 0;
  /// A device silent this long (seconds, 0: never) loses its tool
  /// (RunnerOptions::device_timeout_s).
  double device_timeout_s = 2.0;
  /// What each caller may hold at once.
  CallerLimits per_caller;
};

class SceneRegistry {
 public:
  using Deadline = std::chrono::system_clock::time_point;
  using SpecEdit = std::function<absl::Status(haptics::v1::SceneSpec&)>;

  /// Uploaded models live in `model_dir`. With a `catalogue`, scenes
  /// created or changed are kept in it before the change is acknowledged
  /// (RestoreScenes starts them again); without, they live in memory.
  /// With a `recording` dir, every scene started records its session.
  SceneRegistry(const ServerLimits& limits, std::string model_dir, Metrics& metrics,
                std::unique_ptr<SceneCatalogue> catalogue = nullptr,
                RecordingOptions recording = {});
  ~SceneRegistry();

  /// Builds and starts a scene. `base_dir` resolves relative model paths
  /// (made absolute in the kept spec). INVALID_ARGUMENT for a bad spec,
  /// ALREADY_EXISTS for a taken name, RESOURCE_EXHAUSTED past the limits,
  /// DEADLINE_EXCEEDED when building outlasted `deadline`, UNAVAILABLE
  /// when the catalogue cannot keep it (nothing kept). `keep`: false for a
  /// scene of a --scene file, which is read again at each start (an edit
  /// over the API keeps it from then on).
  absl::StatusOr<RunnerInfo> Create(haptics::v1::SceneSpec spec, const std::string& base_dir,
                                    Deadline deadline = Deadline::max(), bool keep = true);
  /// Loads the model store (ModelStore::Load), then starts every scene of
  /// the catalogue, as of its last kept change. FAILED_PRECONDITION
  /// naming the file when a model's content is missing or damaged, or
  /// naming the catalogue and the scene when one does not start (a spec
  /// this server refuses): the server must not start on half its state.
  absl::Status RestoreScenes();
  /// Applies `edit` to scene `name`'s spec and swaps in the rebuilt scene
  /// (kept in the catalogue first). NOT_FOUND for an unknown scene; else as
  /// `edit`, Create and SceneRunner::Replace.
  absl::StatusOr<RunnerInfo> Edit(const std::string& name, const SpecEdit& edit,
                                  Deadline deadline = Deadline::max());
  /// Stops scene `name` (its streams end with UNAVAILABLE) and forgets it
  /// in the catalogue. NOT_FOUND; UNAVAILABLE when the catalogue cannot.
  absl::Status Delete(const std::string& name);
  /// Deletes uploaded model `id`. FAILED_PRECONDITION naming a scene that
  /// uses it (no scene can start using it meanwhile); NOT_FOUND.
  absl::Status DeleteModel(const std::string& id);

  /// NOT_FOUND for an unknown scene.
  absl::StatusOr<std::shared_ptr<SceneRunner>> Find(const std::string& name) const;
  /// Every scene, by name.
  std::vector<std::shared_ptr<SceneRunner>> List() const;

  /// Stops every scene with `status`, each after a final frame.
  void StopAll(const absl::Status& status);

  /// Counts a new stream; RESOURCE_EXHAUSTED past max_clients.
  absl::Status AddClient();
  void RemoveClient();

  ModelStore& models() { return models_; }
  CallerQuotas& quotas() { return quotas_; }
  const ServerLimits& limits() const { return limits_; }
  Metrics& metrics() { return metrics_; }

 private:
  absl::StatusOr<LoadedScene> BuildChecked(const haptics::v1::SceneSpec& spec,
                                           const std::string& base_dir, Deadline deadline);

  const ServerLimits limits_;
  Metrics& metrics_;
  ModelStore models_;
  CallerQuotas quotas_;
  std::unique_ptr<SceneCatalogue> catalogue_;  // null: scenes in memory only
  const RecordingOptions recording_;
  // Changes run one at a time (builds included); lookups only take mu_.
  std::mutex edit_mu_;
  mutable std::mutex mu_;
  std::map<std::string, std::shared_ptr<SceneRunner>> scenes_;
  bool stopped_ = false;
  std::atomic<int> clients_{0};
};

}  // namespace hs
