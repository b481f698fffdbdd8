#include "common/recording/recording_summary.h"

namespace hs {

absl::StatusOr<RecordingSummary> SummarizeRecording(const std::string& file) {
  absl::StatusOr<RecordedSession> session = ReadSession(file);
  if (!session.ok()) return session.status();
  RecordingSummary summary;
  summary.files = session->files;
  const haptics::v1::RecordingStart& start = session->records.front().start();
  summary.scene = start.scene();
  summary.start_unix_ns = start.start_unix_ns();
  summary.step_s = start.step_s();
  summary.frames = start.frames() == haptics::v1::FRAME_RECORDING_DIGEST ? "digest" : "full";
  for (const haptics::v1::Record& record : session->records) {
    switch (record.kind_case()) {
      case haptics::v1::Record::kFrame:
        if (summary.steps == 0) summary.first_step = record.frame().step();
        summary.last_step = record.frame().step();
        ++summary.steps;
        break;
      case haptics::v1::Record::kInput:
        ++summary.inputs;
        break;
      case haptics::v1::Record::kEdit:
        ++summary.edits;
        break;
      case haptics::v1::Record::kStream:
        if (record.stream().attached()) {
          if (record.stream().device()) {
            ++summary.device_streams;
            summary.device_tools.insert(record.stream().tool());
          } else {
            ++summary.viewer_streams;
          }
        }
        break;
      case haptics::v1::Record::kGap:
        ++summary.gaps;
        summary.gap_steps += record.gap().steps();
        break;
      case haptics::v1::Record::kEnd:
        summary.ended = !record.end().rolled_over();
        break;
      default:
        break;
    }
  }
  summary.duration_s = static_cast<double>(summary.steps) * summary.step_s;
  return summary;
}

}  // namespace hs
