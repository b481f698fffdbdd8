#include "client/haptic_loop/validity_sizer.h"

#include <algorithm>
#include <cmath>

namespace hs {

void ValiditySizer::WindowedPeak::Add(double t_s, double value, double half_window_s) {
  if (!started) {
    started = true;
    current_start_s = t_s;
  }
  if (t_s - current_start_s >= 2 * half_window_s) {
    // Quiet for a whole window: both halves are out of it.
    last = -1;
    current = -1;
    current_start_s = t_s;
  } else if (t_s - current_start_s >= half_window_s) {
    last = current;
    current = -1;
    current_start_s += half_window_s;
  }
  current = std::max(current, value);
}

double ValiditySizer::WindowedPeak::Peak() const { return std::max(current, last); }

ValiditySizer::ValiditySizer(const ValiditySizerOptions& options) : options_(options) {}

void ValiditySizer::AddDevicePosition(double t_s, const Vector3d& p_W) {
  if (!std::isfinite(t_s) || !p_W.allFinite()) return;
  if (has_last_ && t_s > last_t_s_) {
    speed_.Add(t_s, (p_W - last_p_W_).norm() / (t_s - last_t_s_), options_.window_s / 2);
  }
  if (!has_last_ || t_s > last_t_s_) {
    last_p_W_ = p_W;
    last_t_s_ = t_s;
    has_last_ = true;
  }
}

void ValiditySizer::AddRoundTrip(double t_s, double round_trip_s) {
  if (!std::isfinite(t_s) || !std::isfinite(round_trip_s) || round_trip_s < 0) return;
  round_trip_.Add(t_s, round_trip_s, options_.window_s / 2);
}

double ValiditySizer::peak_speed_m_per_s() const { return std::max(speed_.Peak(), 0.0); }

double ValiditySizer::peak_round_trip_s() const { return std::max(round_trip_.Peak(), 0.0); }

double ValiditySizer::WantedRadius() const {
  // A device that does not know its link or its hand yet assumes the worst.
  if (speed_.Peak() < 0 || round_trip_.Peak() < 0) return options_.max_m;
  const double speed = std::max(peak_speed_m_per_s(), options_.least_speed_m_per_s);
  const double travel_m = speed * (peak_round_trip_s() + options_.model_period_s) * options_.safety;
  if (!(travel_m > options_.min_m)) return options_.min_m;
  // The ladder's next rung at or above the travel: steps of 2^(1/4).
  const double rung = std::ceil(4 * std::log2(travel_m / options_.min_m) - 1e-9);
  return std::min(options_.min_m * std::exp2(rung / 4), options_.max_m);
}

}  // namespace hs
