#include "client/loadtest/report_json.h"

#include "client/needs_args.h"
#include "nlohmann/json.hpp"

namespace hs::cli {
namespace {

nlohmann::ordered_json PercentilesJson(const Percentiles& p) {
  return {{"count", p.count}, {"mean", p.mean},  {"p50", p.p50},
          {"p99", p.p99},     {"p99_9", p.p999}, {"max", p.max}};
}

nlohmann::ordered_json StreamJson(const StreamReport& r) {
  return {{"rtt_ms", PercentilesJson(r.rtt_ms)},
          {"sent", r.sent},
          {"answered", r.answered},
          {"frames", r.frames},
          {"frames_per_s", r.frames_per_s},
          {"first_step", r.first_step},
          {"last_step", r.last_step},
          {"dropped_frames", r.dropped_frames},
          {"missed_steps", r.missed_steps},
          {"missed_steps_off_cpu", r.missed_steps_off_cpu},
          {"tool_clashes", r.tool_clashes},
          {"tool_clash_s", r.tool_clash_s}};
}

}  // namespace

std::string LoadReportJson(const LoadReport& r) {
  nlohmann::ordered_json per_device = nlohmann::ordered_json::array();
  for (const StreamReport& d : r.per_device) per_device.push_back(StreamJson(d));
  nlohmann::ordered_json json = {{"scene", r.scene},
                                 {"triangles", r.triangles},
                                 {"clients", r.clients},
                                 {"viewers", r.viewers},
                                 {"rate_hz", r.rate_hz},
                                 {"step_s", r.step_s},
                                 {"duration_s", r.duration_s},
                                 {"needs", NeedsNames(r.needs)},
                                 {"planes", r.planes},
                                 {"load_average_1m", r.load_average_1m},
                                 {"devices", StreamJson(r.devices)},
                                 {"per_device", per_device},
                                 {"viewers_total", StreamJson(r.viewers_total)},
                                 {"echo_run", r.echo_run},
                                 {"echo", StreamJson(r.echo)},
                                 {"echo_request_bytes", r.echo_request_bytes},
                                 {"echo_reply_bytes", r.echo_reply_bytes},
                                 {"step_ms", PercentilesJson(r.step_ms)},
                                 {"steps", r.steps},
                                 {"missed_steps", r.missed_steps},
                                 {"missed_steps_off_cpu", r.missed_steps_off_cpu},
                                 {"missed_fraction", r.missed_fraction},
                                 {"tools_meet", r.tools_meet},
                                 {"tools_touching_at_start", r.tools_touching_at_start},
                                 {"tool_clashes", r.tool_clashes},
                                 {"tool_clash_s", r.tool_clash_s},
                                 {"p99_ratio", r.p99_ratio},
                                 {"p99_budget_ms", r.p99_budget_ms},
                                 {"server_cpu_percent", r.server_cpu_percent},
                                 {"server_cpu_percent_per_device", r.server_cpu_percent_per_device},
                                 {"server_cpu_source", r.server_cpu_source},
                                 {"client_cpu_percent", r.client_cpu_percent},
                                 {"echo_phase_cpu_percent", r.echo_phase_cpu_percent},
                                 {"machine_steal_ms", r.machine_steal_ms}};
  return json.dump();
}

}  // namespace hs::cli
