#pragma once
// Records one scene's session (haptic-server --record-dir): its spec at
// the start and at every edit, the device poses each step applied, stream
// attach and detach, and every frame or its digest, into files of
// common/recording/record_file.h. The stepping thread only queues: a
// writer thread of its own turns the queue into records, syncs the file
// on a cadence and rolls it over at a size cap. A full queue skips the
// step (counted, and marked in the file by a gap), never stalls it.

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <boost/circular_buffer.hpp>

#include "absl/status/statusor.h"
#include "common/recording/record_file.h"
#include "haptics/v1/recording.pb.h"
#include "server/metrics.h"
#include "server/step_snapshot.h"

namespace hs {

struct RecordingOptions {
  /// Where recordings go; "" records nothing.
  std::string dir;
  /// Every scene, or only those whose spec asks (SceneSpec.record).
  bool all_scenes = true;
  haptics::v1::FrameRecording frames = haptics::v1::FRAME_RECORDING_FULL;
  /// The longest a written record waits for the disk (fdatasync), ms.
  int sync_ms = 100;
  /// A file past this many bytes rolls over to the session's next part.
  int64_t max_file_bytes = int64_t{1} << 30;
  /// Steps the queue holds for the writer: 256 ms at 1 kHz.
  int queue_steps = 256;
};

/// What a session starts from.
struct RecordedScene {
  std::string name;
  haptics::v1::SceneSpec spec;
  int64_t after_step = 0;
  double step_s = 0;
  std::string uploaded_models_dir;
};

class SessionRecorder {
 public:
  /// Creates the session's first file in options.dir and starts the
  /// writer. `metrics` outlives the recorder.
  static absl::StatusOr<std::unique_ptr<SessionRecorder>> Start(const RecordingOptions& options,
                                                                const RecordedScene& scene,
                                                                Metrics& metrics);
  /// Writes what is queued, the session's end, syncs and closes.
  ~SessionRecorder();
  SessionRecorder(const SessionRecorder&) = delete;
  SessionRecorder& operator=(const SessionRecorder&) = delete;

  /// Queues a step (its inputs, needs and frame). Never waits for the
  /// writer: with the queue full the step is skipped and counted.
  void RecordStep(std::shared_ptr<const StepSnapshot> snapshot);
  /// Queues an edit: the scene was rebuilt from `spec` after `after_step`.
  void RecordEdit(int64_t after_step, const haptics::v1::SceneSpec& spec, int64_t revision);
  /// Queues a stream's attach or detach after `after_step`.
  void RecordStream(int64_t after_step, bool attached, bool device, const std::string& tool,
                    EffectSet needs);

  /// The file written now.
  std::string path() const;
  /// Steps skipped so far.
  int64_t skipped_steps() const;

 private:
  struct Entry {
    std::shared_ptr<const StepSnapshot> step;    // a step, or
    std::unique_ptr<haptics::v1::Record> event;  // an edit, stream change or gap
  };

  SessionRecorder(const RecordingOptions& options, const RecordedScene& scene, Metrics& metrics,
                  RecordFileWriter file);
  void Push(Entry entry);
  // Queues an entry, growing the queue when it is full. Under mu_.
  void Enqueue(Entry entry);
  void Run();
  // Writes one entry's records; false once the disk refused.
  bool WriteEntry(const Entry& entry);
  bool Append(const haptics::v1::Record& record);
  // Syncs the file; false once the disk refused.
  bool Sync();
  // Says why recording stops (stderr) and stops it; returns false.
  bool Fail(const absl::Status& status);
  // Ends this file and starts the next part.
  bool RollOver();

  const RecordingOptions options_;
  Metrics& metrics_;

  mutable std::mutex mu_;
  std::condition_variable wake_;
  boost::circular_buffer<Entry> queue_;  // guarded by mu_
  int queued_steps_ = 0;                 // guarded by mu_
  // Steps skipped since the last one queued; guarded by mu_.
  std::optional<haptics::v1::RecordingGap> gap_;
  int64_t skipped_steps_ = 0;  // guarded by mu_
  bool stop_ = false;          // guarded by mu_

  // Writer thread only, but for path() (under mu_).
  RecordFileWriter file_;
  haptics::v1::RecordingStart start_;  // of the file written now
  int64_t last_step_ = 0;
  bool failed_ = false;
  haptics::v1::Record record_;  // reused from record to record
  std::thread writer_;
};

}  // namespace hs
