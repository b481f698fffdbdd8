#pragma once
// A viewer of a running scene: its frames, with the parts asked for, to a
// callback on the Watcher's own thread, or the newest one on demand.

#include <functional>
#include <memory>

#include "haptics/error.h"
#include "haptics/export.h"
#include "haptics/frame.h"

namespace haptics {

struct WatchOptions {
  bool poses = true;
  bool contacts = true;
  bool forces = true;
  bool local_model = false;
  /// Frames a second wanted; 0: every step.
  double frame_rate_hz = 0;
  /// Called with each frame on the Watcher's thread; may be empty.
  std::function<void(const Frame&)> on_frame;
  /// Watch gives up after this long without the first frame, seconds;
  /// <= 0: the session's connect timeout.
  double open_timeout_s = 0;
};

class HAPTICS_EXPORT Watcher {
 public:
  class Impl;
  explicit Watcher(std::unique_ptr<Impl> impl);
  /// Ends the stream and joins its thread.
  ~Watcher();
  Watcher(const Watcher&) = delete;
  Watcher& operator=(const Watcher&) = delete;

  /// The newest frame; false (and `out` untouched) before the first.
  bool Latest(Frame* out) const;
  /// Frames received so far.
  int64_t frames() const;
  /// Whether the stream ended, and why (kOk while it runs or after Close).
  bool ended() const;
  Error status() const;
  /// Ends the stream now (the destructor does it too).
  void Close();

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace haptics
