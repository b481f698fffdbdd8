#pragma once
// How large a remote device's local contact model must be: the validity
// radius that covers where the hand can go before the next model arrives.
//
// A model is taken at the device pose of a frame's step and reaches the
// device a round trip later, and the next comes with a later frame: a hand
// at speed v is about v * (round trip + the time between the frames that
// bring models, `model_period_s` at most) from the pose of the model it
// renders, and the safety factor covers the rest. The sizer keeps the peak speed
// and the peak round trip of the last window (two half-windows, so a peak
// is forgotten between one and two windows after it: a stall of the link
// is remembered that long), and wants that distance times a safety
// factor, quantized upward to a ladder of steps 2^(1/4) apart so that the
// server does not search again for every small change, within the cap.
// Eigen only, and nothing allocated: it runs in the device's own loops.

#include "common/core/types.h"

namespace hs {

struct ValiditySizerOptions {
  /// How long a peak speed or round trip is remembered, seconds.
  double window_s = 1.0;
  /// The longest between two frames that bring models, seconds.
  double model_period_s = 0.05;
  /// The factor over the distance the hand can travel.
  double safety = 1.5;
  /// The speed a hand is taken to reach at once from rest, metres a
  /// second: a hand still for a while may move the next moment, and the
  /// model then in flight must hold it.
  double least_speed_m_per_s = 0.1;
  /// The least and the most radius wanted, metres (the server clamps too).
  double min_m = 1e-3;
  double max_m = 0.1;
};

class ValiditySizer {
 public:
  explicit ValiditySizer(const ValiditySizerOptions& options = {});

  /// The device was at `p_W` (world frame, metres) at `t_s` (seconds, any
  /// epoch, not decreasing). Non-finite samples are ignored.
  void AddDevicePosition(double t_s, const Vector3d& p_W);
  /// A frame applying a pose sent `round_trip_s` ago arrived at `t_s`.
  /// Non-finite or negative samples are ignored.
  void AddRoundTrip(double t_s, double round_trip_s);

  /// The radius to ask for, metres: max_m while no round trip or speed is
  /// known (the first model must hold whatever the link turns out to be),
  /// else within [min_m, max_m] on the ladder min_m * 2^(k/4) (max_m
  /// itself when the ladder passes it).
  double WantedRadius() const;

  /// The peaks the radius comes from (metres a second, seconds).
  double peak_speed_m_per_s() const;
  double peak_round_trip_s() const;

 private:
  // A running maximum over two half-windows: the current and the last.
  struct WindowedPeak {
    double current = -1;
    double last = -1;
    double current_start_s = 0;
    bool started = false;
    void Add(double t_s, double value, double half_window_s);
    double Peak() const;
  };

  ValiditySizerOptions options_;
  WindowedPeak speed_;
  WindowedPeak round_trip_;
  Vector3d last_p_W_ = Vector3d::Zero();
  double last_t_s_ = 0;
  bool has_last_ = false;
};

}  // namespace hs
