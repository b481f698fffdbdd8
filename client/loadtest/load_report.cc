#include "client/loadtest/load_report.h"

#include <algorithm>
#include <utility>

namespace hs::cli {
namespace {

// Percent of one core over a kind's turns; -1 when it had none.
double Percent(double cpu_s, double wall_s) { return wall_s > 0 ? 100 * cpu_s / wall_s : -1; }

}  // namespace

StreamReport Pool(const std::vector<StreamReport>& each, std::vector<double>& pooled_rtt_ms,
                  double window_s) {
  StreamReport total;
  for (const StreamReport& r : each) {
    total.sent += r.sent;
    total.answered += r.answered;
    total.frames += r.frames;
    total.dropped_frames += r.dropped_frames;
    total.missed_steps = std::max(total.missed_steps, r.missed_steps);
    total.missed_steps_off_cpu = std::max(total.missed_steps_off_cpu, r.missed_steps_off_cpu);
  }
  if (!each.empty()) {
    total.first_step = each.front().first_step;
    total.last_step = each.front().last_step;
  }
  total.frames_per_s = static_cast<double>(total.frames) / window_s;
  total.rtt_ms = Summarize(pooled_rtt_ms);
  return total;
}

void SetDeviceFigures(std::vector<StreamReport> each, std::vector<double>& pooled_rtt_ms,
                      std::vector<double>& step_ms, double window_s, LoadReport& report) {
  report.devices = Pool(each, pooled_rtt_ms, window_s);
  report.step_ms = Summarize(step_ms);
  const StreamReport& first = each.front();
  report.steps = first.frames > 0 ? first.last_step - first.first_step + 1 : 0;
  report.missed_steps = first.missed_steps;
  report.missed_steps_off_cpu = first.missed_steps_off_cpu;
  report.tool_clashes = first.tool_clashes;
  report.tool_clash_s = first.tool_clash_s;
  report.missed_fraction =
      static_cast<double>(report.missed_steps) /
      static_cast<double>(std::max<int64_t>(1, report.steps + report.missed_steps));
  report.per_device = std::move(each);
}

void SetEchoFigures(const std::vector<StreamReport>& each, std::vector<double>& pooled_rtt_ms,
                    const std::vector<int64_t>& reply_bytes, double window_s, LoadReport& report) {
  report.echo_run = true;
  int64_t reply_sum = 0;
  for (const int64_t bytes : reply_bytes) reply_sum += bytes;
  report.echo_reply_bytes =
      reply_bytes.empty() ? 0 : reply_sum / static_cast<int64_t>(reply_bytes.size());
  report.echo = Pool(each, pooled_rtt_ms, window_s);
  if (report.echo.rtt_ms.p99 > 0) {
    report.p99_ratio = report.devices.rtt_ms.p99 / report.echo.rtt_ms.p99;
  }
  report.p99_budget_ms = 1.5 * report.echo.rtt_ms.p99 + report.step_ms.p99;
}

void SetCpuFigures(const TurnTotals& cpu, const std::string& server_source, bool echo_run,
                   LoadReport& report) {
  report.client_cpu_percent = Percent(cpu.client_s[0], cpu.wall_s[0]);
  if (echo_run) report.echo_phase_cpu_percent = Percent(cpu.client_s[1], cpu.wall_s[1]);
  if (cpu.server_s[0] && cpu.wall_s[0] > 0) {
    report.server_cpu_percent = Percent(*cpu.server_s[0], cpu.wall_s[0]);
    report.server_cpu_percent_per_device = report.server_cpu_percent / report.clients;
    report.server_cpu_source = server_source;
  } else {
    report.server_cpu_percent = -1;
    report.server_cpu_percent_per_device = -1;
    report.server_cpu_source = "unknown (" + server_source + ")";
  }
}

}  // namespace hs::cli
