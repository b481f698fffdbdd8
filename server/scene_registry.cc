#include "server/scene_registry.h"

#include "absl/strings/str_cat.h"
#include "common/api/names.h"
#include "common/core/status_macros.h"
#include "server/spec_edit.h"
#include "server/thread_priority.h"

namespace hs {

namespace pb = haptics::v1;

SceneRegistry::SceneRegistry(const ServerLimits& limits, std::string model_dir, Metrics& metrics,
                             std::unique_ptr<SceneCatalogue> catalogue, RecordingOptions recording)
    : limits_(limits),
      metrics_(metrics),
      models_(std::move(model_dir), limits.max_models),
      quotas_(limits.per_caller),
      catalogue_(std::move(catalogue)),
      recording_(std::move(recording)) {}

SceneRegistry::~SceneRegistry() { StopAll(absl::UnavailableError("the server is stopping")); }

absl::StatusOr<LoadedScene> SceneRegistry::BuildChecked(const pb::SceneSpec& spec,
                                                        const std::string& base_dir,
                                                        Deadline deadline) {
  // The spec comes back whole in every SceneInfo: bounded, it always fits
  // a reply (vertex moves would grow it without end).
  if (spec.ByteSizeLong() > static_cast<size_t>(limits_.max_spec_bytes)) {
    return absl::ResourceExhaustedError(absl::StrCat("the scene's spec would take ",
                                                     spec.ByteSizeLong(), " bytes; at most ",
                                                     limits_.max_spec_bytes));
  }
  if (spec.objects_size() > limits_.max_objects_per_scene) {
    return absl::ResourceExhaustedError(
        absl::StrCat("at most ", limits_.max_objects_per_scene, " objects per scene"));
  }
  HS_ASSIGN_OR_RETURN(LoadedScene loaded, BuildScene(spec, BuildPaths{base_dir, models_.dir()}));
  std::function<void()> on_worker_start;
  if (const int priority = limits_.realtime_priority; priority != 0) {
    on_worker_start = [priority] { (void)SetRealtimePriority(priority); };  // as SceneRunner
  }
  HS_RETURN_IF_ERROR(loaded.scene->SetThreads(limits_.threads_per_scene, on_worker_start));
  const double step_s = loaded.scene->options().step_s;
  if (!(step_s >= limits_.min_step_s && step_s <= limits_.max_step_s)) {
    return absl::InvalidArgumentError(absl::StrCat("step_s: ", step_s, " is outside [",
                                                   limits_.min_step_s, ", ", limits_.max_step_s,
                                                   "] on this server"));
  }
  if (loaded.triangles > limits_.max_triangles_per_scene) {
    return absl::ResourceExhaustedError(
        absl::StrCat(loaded.triangles, " triangles; at most ", limits_.max_triangles_per_scene));
  }
  if (std::chrono::system_clock::now() > deadline) {
    return absl::DeadlineExceededError("the deadline passed while building the scene");
  }
  return loaded;
}

absl::StatusOr<RunnerInfo> SceneRegistry::Create(pb::SceneSpec spec, const std::string& base_dir,
                                                 Deadline deadline, bool keep) {
  std::lock_guard edit(edit_mu_);
  HS_RETURN_IF_ERROR(ValidateName(spec.name()));
  {
    std::lock_guard lock(mu_);
    if (stopped_) return absl::UnavailableError("the server is stopping");
    if (scenes_.count(spec.name())) {
      return absl::AlreadyExistsError(absl::StrCat("scene '", spec.name(), "' exists"));
    }
    if (static_cast<int>(scenes_.size()) >= limits_.max_scenes) {
      return absl::ResourceExhaustedError(absl::StrCat("at most ", limits_.max_scenes, " scenes"));
    }
  }
  AbsoluteModelPaths(base_dir, spec);
  HS_ASSIGN_OR_RETURN(LoadedScene loaded, BuildChecked(spec, base_dir, deadline));
  if (spec.record() && recording_.dir.empty()) {
    return absl::FailedPreconditionError(
        "record: this server keeps no recordings (it was started without --record-dir)");
  }
  std::unique_ptr<SessionRecorder> recorder;
  if (!recording_.dir.empty() && (recording_.all_scenes || spec.record())) {
    absl::StatusOr<std::unique_ptr<SessionRecorder>> started = SessionRecorder::Start(
        recording_, {spec.name(), spec, 0, loaded.scene->options().step_s, models_.dir()},
        metrics_);
    if (!started.ok()) {
      return absl::UnavailableError(
          absl::StrCat("cannot record the scene: ", started.status().message()));
    }
    recorder = *std::move(started);
  }
  if (keep && catalogue_) HS_RETURN_IF_ERROR(catalogue_->Put(spec));
  auto runner =
      std::make_shared<SceneRunner>(spec, std::move(loaded), metrics_,
                                    RunnerOptions{.realtime_priority = limits_.realtime_priority,
                                                  .device_timeout_s = limits_.device_timeout_s},
                                    std::move(recorder));
  std::lock_guard lock(mu_);
  scenes_[spec.name()] = runner;
  return runner->Info();
}

absl::StatusOr<RunnerInfo> SceneRegistry::Edit(const std::string& name, const SpecEdit& edit,
                                               Deadline deadline) {
  std::lock_guard lock(edit_mu_);
  HS_ASSIGN_OR_RETURN(std::shared_ptr<SceneRunner> runner, Find(name));
  pb::SceneSpec spec = runner->spec();
  HS_RETURN_IF_ERROR(edit(spec));
  if (spec.name() != name) return absl::InvalidArgumentError("a scene cannot be renamed");
  HS_ASSIGN_OR_RETURN(LoadedScene loaded, BuildChecked(spec, "", deadline));
  if (!catalogue_) {
    HS_RETURN_IF_ERROR(runner->Replace(std::move(spec), std::move(loaded)));
    return runner->Info();
  }
  // Kept first, so that nothing is acknowledged that a crash would lose;
  // a swap that fails puts the old spec back.
  const pb::SceneSpec before = runner->spec();
  HS_RETURN_IF_ERROR(catalogue_->Put(spec));
  if (absl::Status s = runner->Replace(std::move(spec), std::move(loaded)); !s.ok()) {
    (void)catalogue_->Put(before);
    return s;
  }
  return runner->Info();
}

absl::Status SceneRegistry::Delete(const std::string& name) {
  std::shared_ptr<SceneRunner> runner;
  {
    std::lock_guard edit(edit_mu_);
    std::lock_guard lock(mu_);
    const auto it = scenes_.find(name);
    if (it == scenes_.end()) return absl::NotFoundError(absl::StrCat("no scene '", name, "'"));
    if (catalogue_) HS_RETURN_IF_ERROR(catalogue_->Remove(name));
    runner = std::move(it->second);
    scenes_.erase(it);
  }
  runner->Stop(absl::UnavailableError(absl::StrCat("scene '", name, "' was deleted")));
  return absl::OkStatus();
}

absl::Status SceneRegistry::RestoreScenes() {
  HS_RETURN_IF_ERROR(models_.Load());
  if (!catalogue_) return absl::OkStatus();
  HS_ASSIGN_OR_RETURN(std::vector<pb::SceneSpec> specs, catalogue_->LoadAll());
  for (pb::SceneSpec& spec : specs) {
    const std::string name = spec.name();
    absl::StatusOr<RunnerInfo> started =
        Create(std::move(spec), "", Deadline::max(), /*keep=*/false);
    if (!started.ok()) {
      return absl::FailedPreconditionError(
          absl::StrCat("scene '", name, "' of ", catalogue_->path(),
                       " does not start: ", started.status().message()));
    }
  }
  return absl::OkStatus();
}

absl::Status SceneRegistry::DeleteModel(const std::string& id) {
  std::lock_guard edit(edit_mu_);  // no scene is built or changed meanwhile
  for (const std::shared_ptr<SceneRunner>& runner : List()) {
    const pb::SceneSpec spec = runner->spec();
    for (const pb::SceneObject& o : spec.objects()) {
      if (o.model().uploaded_model_id() == id) {
        return absl::FailedPreconditionError(absl::StrCat(
            "model '", id, "' is used by object '", o.name(), "' of scene '", spec.name(), "'"));
      }
    }
  }
  return models_.Delete(id);
}

absl::StatusOr<std::shared_ptr<SceneRunner>> SceneRegistry::Find(const std::string& name) const {
  std::lock_guard lock(mu_);
  const auto it = scenes_.find(name);
  if (it == scenes_.end()) return absl::NotFoundError(absl::StrCat("no scene '", name, "'"));
  return it->second;
}

std::vector<std::shared_ptr<SceneRunner>> SceneRegistry::List() const {
  std::lock_guard lock(mu_);
  std::vector<std::shared_ptr<SceneRunner>> out;
  for (const auto& [name, runner] : scenes_) out.push_back(runner);
  return out;
}

void SceneRegistry::StopAll(const absl::Status& status) {
  std::map<std::string, std::shared_ptr<SceneRunner>> scenes;
  {
    std::lock_guard lock(mu_);
    stopped_ = true;
    scenes.swap(scenes_);
  }
  for (auto& [name, runner] : scenes) runner->Stop(status);
}

absl::Status SceneRegistry::AddClient() {
  if (clients_.fetch_add(1) >= limits_.max_clients) {
    clients_.fetch_sub(1);
    return absl::ResourceExhaustedError(absl::StrCat("at most ", limits_.max_clients, " clients"));
  }
  return absl::OkStatus();
}

void SceneRegistry::RemoveClient() { clients_.fetch_sub(1); }

}  // namespace hs
