#pragma once
// The accuracy sweep's measured points, kept in the order they run, and
// their output: the Markdown table and the gnuplot data files.

#include <string>
#include <vector>

namespace hs::accuracy {

/// One measured point of one knob. Fields not measured stay negative.
struct Point {
  std::string family, label;
  /// Time per query (or per step check), microseconds.
  double median_us = 0, p99_us = 0;
  /// Worst |depth - reference depth| over the poses, metres, against the
  /// family's reference shape (analytic, or the finest imported mesh).
  double depth_error_m = -1;
  /// Worst angle of the normal from the reference normal, radians.
  double normal_error_rad = -1;
  /// Worst |depth - brute-force depth of the same mesh|, metres.
  double brute_error_m = -1;
  /// Median time of one brute-force reference, milliseconds.
  double brute_ms = -1;
  /// Tunnelling: fraction of passes missed.
  double missed = -1;
  /// Step length: worst depth reached before the contact was reported, and
  /// worst distance of the reported first touch from the true one, metres;
  /// median time of the step that reported it, microseconds.
  double overshoot_m = -1, first_touch_error_m = -1, contact_step_us = -1;
};

/// Adds `point`, or replaces the point of the same family and label (a
/// benchmark run again for more iterations).
void Record(const Point& point);

/// Sorts `us` and sets point.median_us and point.p99_us from it.
void SetPercentiles(std::vector<double>& us, Point& point);

/// Writes accuracy.md (every table), accuracy.dat (error against time, one
/// block per knob), families (the blocks' titles), tunnelling.dat and
/// step.dat into `dir`.
void WriteResults(const std::string& dir);

}  // namespace hs::accuracy
