#include "tests/bench/accuracy_results.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

namespace hs::accuracy {
namespace {

std::vector<Point>& Results() {
  static std::vector<Point> results;
  return results;
}

// A table cell: "-" for what was not measured.
std::string Cell(double value) {
  if (value < 0) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

}  // namespace

void Record(const Point& point) {
  for (Point& p : Results()) {
    if (p.family == point.family && p.label == point.label) {
      p = point;
      return;
    }
  }
  Results().push_back(point);
}

void SetPercentiles(std::vector<double>& us, Point& point) {
  if (us.empty()) return;
  std::sort(us.begin(), us.end());
  point.median_us = us[us.size() / 2];
  point.p99_us = us[std::min(us.size() - 1, us.size() * 99 / 100)];
}

void WriteResults(const std::string& dir) {
  std::ofstream table(dir + "/accuracy.md");
  std::ofstream data(dir + "/accuracy.dat");
  std::ofstream tunnel(dir + "/tunnelling.dat");
  std::ofstream step(dir + "/step.dat");
  std::ofstream families(dir + "/families");  // block titles for gnuplot
  table << "| knob | point | median us | p99 us | depth error m | normal error rad | error vs "
           "brute force m | brute force ms |\n"
           "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  std::string family;
  for (const Point& p : Results()) {
    if (p.missed >= 0 || p.overshoot_m >= 0) continue;
    table << "| " << p.family << " | " << p.label << " | " << Cell(p.median_us) << " | "
          << Cell(p.p99_us) << " | " << Cell(p.depth_error_m) << " | " << Cell(p.normal_error_rad)
          << " | " << Cell(p.brute_error_m) << " | " << Cell(p.brute_ms) << " |\n";
    // gnuplot: one block per knob, two blank lines between blocks; errors
    // of 0 floored so that a log scale shows them; a reference shape's own
    // point has no error to plot.
    if (p.depth_error_m < 0) continue;
    if (p.family != family) {
      if (!family.empty()) data << "\n\n";
      families << '"' << p.family << "\" ";
    }
    family = p.family;
    data << '"' << p.family << "\" \"" << p.label << "\" " << p.median_us << ' '
         << std::max(p.depth_error_m, 1e-16) << ' ' << std::max(p.brute_error_m, 1e-16) << '\n';
  }
  table << "\n| step check | median us per step | p99 us | contact step median us | depth "
           "error m | error vs brute force m | overshoot m | first-touch error m |\n"
           "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const Point& p : Results()) {
    if (p.overshoot_m < 0) continue;
    table << "| " << p.label << " | " << Cell(p.median_us) << " | " << Cell(p.p99_us) << " | "
          << Cell(p.contact_step_us) << " | " << Cell(p.depth_error_m) << " | "
          << Cell(p.brute_error_m) << " | " << Cell(p.overshoot_m) << " | "
          << Cell(p.first_touch_error_m) << " |\n";
    step << '"' << p.label << "\" " << p.contact_step_us << ' ' << std::max(p.overshoot_m, 1e-16)
         << ' ' << std::max(p.first_touch_error_m, 1e-16) << '\n';
  }
  table << "\n| tunnelling | median us per step | p99 us | passes missed |\n"
           "| --- | --- | --- | --- |\n";
  for (const Point& p : Results()) {
    if (p.missed < 0) continue;
    table << "| " << p.label << " | " << Cell(p.median_us) << " | " << Cell(p.p99_us) << " | "
          << 100 * p.missed << "% |\n";
    tunnel << '"' << p.label << "\" " << p.median_us << ' ' << 100 * p.missed << '\n';
  }
}

}  // namespace hs::accuracy
