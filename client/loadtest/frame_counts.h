#pragma once
// What a stream's frames say over the load test's window, from the
// frames' own cumulative counters: each counter's growth from the
// window's first frame to its latest.

#include <cstdint>

#include "client/loadtest/load_report.h"
#include "haptics/v1/session_service.pb.h"

namespace hs::cli {

class FrameCounts {
 public:
  /// A frame received in the window.
  void Add(const haptics::v1::Frame& frame);
  /// Sets `report`'s frames, first and last step, and the growth of the
  /// dropped-frame, missed-step and tool-clash counters; frames_per_s over
  /// `window_s`.
  void Fill(StreamReport& report, double window_s) const;
  int64_t frames() const { return frames_; }

 private:
  // A value of the frames at the window's first frame and at its latest.
  template <typename T>
  struct Span {
    T first = 0, last = 0;
    void See(T value, bool first_frame) {
      if (first_frame) first = value;
      last = value;
    }
    T Grown() const { return last - first; }
  };
  int64_t frames_ = 0;
  Span<int64_t> step_, dropped_, missed_, missed_off_cpu_, clashes_;
  Span<double> clash_s_;
};

}  // namespace hs::cli
