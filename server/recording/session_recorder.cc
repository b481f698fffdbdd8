#include "server/recording/session_recorder.h"

#include <pthread.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <vector>

#include "absl/strings/str_cat.h"
#include "common/api/proto_convert.h"
#include "common/recording/recorded_step.h"
#include "common/recording/session_files.h"
#include "server/state/durable_file.h"

namespace hs {
namespace {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

int64_t UnixNanoseconds() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Room for edits and stream changes beside the steps.
constexpr int kEventRoom = 64;

}  // namespace

absl::StatusOr<std::unique_ptr<SessionRecorder>> SessionRecorder::Start(
    const RecordingOptions& options, const RecordedScene& scene, Metrics& metrics) {
  std::error_code error;
  std::filesystem::create_directories(options.dir, error);
  pb::RecordingStart start;
  start.set_scene(scene.name);
  *start.mutable_spec() = scene.spec;
  start.set_after_step(scene.after_step);
  start.set_start_unix_ns(UnixNanoseconds());
  start.set_part(0);
  start.set_frames(options.frames);
  start.set_step_s(scene.step_s);
  start.set_uploaded_models_dir(scene.uploaded_models_dir);
  const std::string path =
      (std::filesystem::path(options.dir) / SessionFileName(scene.name, start.start_unix_ns(), 0))
          .string();
  absl::StatusOr<RecordFileWriter> file = RecordFileWriter::Create(path);
  if (!file.ok()) return file.status();
  std::unique_ptr<SessionRecorder> recorder(
      new SessionRecorder(options, scene, metrics, std::move(*file)));
  recorder->start_ = std::move(start);
  pb::Record first;
  *first.mutable_start() = recorder->start_;
  if (!recorder->Append(first)) return absl::InternalError(absl::StrCat("cannot write ", path));
  // The file is there to stay: its name in the folder is on the disk too.
  if (absl::Status s = SyncFolder(options.dir); !s.ok()) return s;
  recorder->writer_ = std::thread([r = recorder.get()] { r->Run(); });
  return recorder;
}

SessionRecorder::SessionRecorder(const RecordingOptions& options, const RecordedScene& scene,
                                 Metrics& metrics, RecordFileWriter file)
    : options_(options),
      metrics_(metrics),
      queue_(options.queue_steps + kEventRoom),
      file_(std::move(file)),
      last_step_(scene.after_step) {}

SessionRecorder::~SessionRecorder() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  wake_.notify_one();
  if (writer_.joinable()) writer_.join();
}

void SessionRecorder::Push(Entry entry) {
  const bool is_step = entry.step != nullptr;
  bool skipped = false;
  {
    std::lock_guard lock(mu_);
    if (is_step && queued_steps_ >= options_.queue_steps) {
      if (!gap_) {
        gap_.emplace();
        gap_->set_first_step(entry.step->step);
      }
      gap_->set_steps(gap_->steps() + 1);
      ++skipped_steps_;
      skipped = true;
    } else {
      if (is_step && gap_) {
        auto record = std::make_unique<pb::Record>();
        *record->mutable_gap() = *gap_;
        gap_.reset();
        Enqueue({nullptr, std::move(record)});
      }
      queued_steps_ += is_step;
      Enqueue(std::move(entry));
    }
  }
  if (skipped) {
    metrics_.AddRecordingSkippedSteps(1);
  } else {
    wake_.notify_one();
  }
}

void SessionRecorder::Enqueue(Entry entry) {
  // Steps take at most queue_steps of the room; edits, stream changes and
  // gaps (rare, and a replay needs every edit) are never dropped: past the
  // room kept for them the queue grows rather than overwrite its oldest.
  if (queue_.full()) queue_.set_capacity(2 * queue_.capacity());
  queue_.push_back(std::move(entry));
}

void SessionRecorder::RecordStep(std::shared_ptr<const StepSnapshot> snapshot) {
  Push({std::move(snapshot), nullptr});
}

void SessionRecorder::RecordEdit(int64_t after_step, const pb::SceneSpec& spec, int64_t revision) {
  auto record = std::make_unique<pb::Record>();
  pb::SceneEdit* edit = record->mutable_edit();
  edit->set_after_step(after_step);
  *edit->mutable_spec() = spec;
  edit->set_revision(revision);
  Push({nullptr, std::move(record)});
}

void SessionRecorder::RecordStream(int64_t after_step, bool attached, bool device,
                                   const std::string& tool, EffectSet needs) {
  auto record = std::make_unique<pb::Record>();
  pb::StreamChange* change = record->mutable_stream();
  change->set_after_step(after_step);
  change->set_attached(attached);
  change->set_device(device);
  change->set_tool(tool);
  EffectsToProto(needs, change->mutable_needs());
  Push({nullptr, std::move(record)});
}

std::string SessionRecorder::path() const {
  std::lock_guard lock(mu_);
  return file_.path();
}

int64_t SessionRecorder::skipped_steps() const {
  std::lock_guard lock(mu_);
  return skipped_steps_;
}

bool SessionRecorder::Append(const pb::Record& record) {
  if (failed_) return false;
  const int64_t before = file_.bytes();
  if (absl::Status s = file_.Append(record); !s.ok()) return Fail(s);
  metrics_.AddRecordedBytes(file_.bytes() - before);
  return true;
}

bool SessionRecorder::Fail(const absl::Status& status) {
  std::cerr << "haptic-server: recording of scene '" << start_.scene()
            << "' stops: " << status.message() << "\n";
  failed_ = true;
  return false;
}

bool SessionRecorder::Sync() {
  if (failed_) return false;
  if (absl::Status s = file_.Sync(); !s.ok()) return Fail(s);
  return true;
}

bool SessionRecorder::RollOver() {
  record_.Clear();
  pb::RecordingEnd* end = record_.mutable_end();
  end->set_last_step(last_step_);
  end->set_end_unix_ns(UnixNanoseconds());
  end->set_rolled_over(true);
  if (!Append(record_) || !Sync()) return false;
  start_.set_part(start_.part() + 1);
  start_.set_after_step(last_step_);
  const std::string path = (std::filesystem::path(options_.dir) /
                            SessionFileName(start_.scene(), start_.start_unix_ns(), start_.part()))
                               .string();
  absl::StatusOr<RecordFileWriter> next = RecordFileWriter::Create(path);
  if (!next.ok()) return Fail(next.status());
  {
    std::lock_guard lock(mu_);
    file_ = std::move(*next);
  }
  record_.Clear();
  *record_.mutable_start() = start_;
  if (!Append(record_)) return false;
  if (absl::Status s = SyncFolder(options_.dir); !s.ok()) return Fail(s);
  return true;
}

bool SessionRecorder::WriteEntry(const Entry& entry) {
  if (file_.bytes() >= options_.max_file_bytes && !RollOver()) return false;
  if (entry.event) {
    if (entry.event->has_edit()) *start_.mutable_spec() = entry.event->edit().spec();
    return Append(*entry.event);
  }
  const StepSnapshot& s = *entry.step;
  for (const AppliedInput& applied : s.inputs) {
    record_.Clear();
    pb::DeviceInput* input = record_.mutable_input();
    input->set_step(s.step);
    input->set_tool((*s.names)[applied.tool]);
    ExactPoseToProto(applied.X_WD, input->mutable_device_pose());
    input->set_sequence(applied.stamp.sequence);
    input->set_device_time_ns(applied.stamp.device_time_ns);
    input->set_seat(applied.seat);
    input->set_model_stale(applied.model.stale);
    input->set_validity_radius_m(applied.model.validity_radius_m);
    input->set_surface_only(applied.model.surface_only);
    if (!Append(record_)) return false;
  }
  record_.Clear();
  FillRecordedFrame(s.step, s.time_s, s.frame, *s.names, s.needs, options_.frames,
                    record_.mutable_frame());
  last_step_ = s.step;
  return Append(record_);
}

void SessionRecorder::Run() {
  pthread_setname_np(pthread_self(), "scene-record");
  const auto cadence = std::chrono::milliseconds(options_.sync_ms);
  Clock::time_point next_sync = Clock::now() + cadence;
  std::vector<Entry> batch;
  bool stopping = false;
  bool unsynced = false;
  while (!stopping) {
    {
      std::unique_lock lock(mu_);
      wake_.wait_until(lock, next_sync, [this] { return stop_ || !queue_.empty(); });
      stopping = stop_;
      for (Entry& entry : queue_) batch.push_back(std::move(entry));
      queue_.clear();
      queued_steps_ = 0;
    }
    int64_t refused = 0;
    for (const Entry& entry : batch) {
      if (!WriteEntry(entry)) refused += entry.step != nullptr;
      unsynced = true;
    }
    batch.clear();
    if (refused > 0) {
      metrics_.AddRecordingSkippedSteps(refused);
      std::lock_guard lock(mu_);
      skipped_steps_ += refused;
    }
    if (unsynced && Clock::now() >= next_sync) {
      (void)Sync();
      unsynced = false;
      next_sync = Clock::now() + cadence;
    } else if (!unsynced) {
      next_sync = Clock::now() + cadence;
    }
  }
  record_.Clear();
  record_.mutable_end()->set_last_step(last_step_);
  record_.mutable_end()->set_end_unix_ns(UnixNanoseconds());
  if (Append(record_)) (void)Sync();
}

}  // namespace hs
