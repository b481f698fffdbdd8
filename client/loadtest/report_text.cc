#include "client/loadtest/report_text.h"

#include <iomanip>
#include <string>

#include "client/needs_args.h"

namespace hs::cli {
namespace {

void PrintRow(const std::string& name, const StreamReport& r, std::ostream& out) {
  const Percentiles& p = r.rtt_ms;
  out << "  " << std::left << std::setw(12) << name << std::right << std::setw(9) << p.count
      << std::setw(9) << p.p50 << std::setw(9) << p.p99 << std::setw(9) << p.p999 << std::setw(9)
      << p.max << std::setw(10) << r.frames_per_s << std::setw(9) << r.dropped_frames << "\n";
}

}  // namespace

void PrintLoadReport(const LoadReport& r, std::ostream& out) {
  out << std::fixed << std::setprecision(3);
  out << "loadtest: " << r.clients << " device(s) x " << r.rate_hz << " Hz for " << r.duration_s
      << " s, " << r.viewers << " viewer(s), scene '" << r.scene << "' (" << r.triangles
      << " triangles, steps of " << r.step_s * 1e3 << " ms); devices need: " << NeedsNames(r.needs)
      << (r.planes ? " (local model with planes)" : "") << "; load average " << r.load_average_1m
      << " at start\n";
  out << "round trip, ms      count      p50      p99    p99.9      max  frames/s  dropped\n";
  PrintRow("devices", r.devices, out);
  for (size_t i = 0; i < r.per_device.size(); ++i) {
    PrintRow("  device " + std::to_string(i), r.per_device[i], out);
  }
  if (r.echo_run) PrintRow("echo", r.echo, out);
  out << "poses: " << r.devices.sent << " sent, " << r.devices.answered
      << " answered; frames: " << r.devices.frames << " to devices, " << r.viewers_total.frames
      << " to viewers (" << r.viewers_total.dropped_frames << " dropped)\n";
  out << "scene: " << r.steps << " steps, " << r.missed_steps << " missed ("
      << 100 * r.missed_fraction << "%; " << r.missed_steps_off_cpu
      << " with the stepping thread off the CPU); step time ms p50 " << r.step_ms.p50 << ", p99 "
      << r.step_ms.p99 << ", max " << r.step_ms.max << "\n";
  out << "tools " << (r.tools_meet ? "meet in pairs" : "apart") << ": " << r.tool_clashes
      << " clashes, touching " << r.tool_clash_s << " s\n";
  if (r.tools_touching_at_start > 0) {
    out << "WARNING: " << r.tools_touching_at_start
        << " tool pairs touch where they start: every step computes their contacts (fewer "
           "clients fit the scene apart)\n";
  }
  if (r.echo_run) {
    out << "echo (turns with the devices): " << r.echo_request_bytes << " B requests, "
        << r.echo_reply_bytes << " B replies; p99 ratio devices/echo " << r.p99_ratio
        << "; budget 1.5 x echo p99 + step p99 = " << r.p99_budget_ms
        << " ms: " << (r.devices.rtt_ms.p99 <= r.p99_budget_ms ? "met" : "not met") << "\n";
  }
  out << "cpu, % of one core: server " << r.server_cpu_percent << ", "
      << r.server_cpu_percent_per_device << " per device (" << r.server_cpu_source
      << "), hapticctl " << r.client_cpu_percent << " during devices, " << r.echo_phase_cpu_percent
      << " during echo (echo server included)\n";
  if (r.machine_steal_ms >= 0) {
    out << "hypervisor: " << r.machine_steal_ms
        << " ms of CPU taken from this machine in the run\n";
  }
}

}  // namespace hs::cli
