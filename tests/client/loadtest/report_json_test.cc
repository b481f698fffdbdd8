#include "client/loadtest/report_json.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace hs::cli {
namespace {

// The JSON object holds the report's figures under their field names, in
// the order scripts have read them, the server's CPU per device beside
// its total.
TEST(ReportJsonTest, FieldsAndValues) {
  LoadReport r;
  r.scene = "loadtest-1";
  r.clients = 2;
  r.needs = {Effect::kForce, Effect::kFriction};
  r.per_device.resize(2);
  r.per_device[1].sent = 7;
  r.devices.rtt_ms.p999 = 1.25;
  r.server_cpu_percent = 30;
  r.server_cpu_percent_per_device = 15;
  r.server_cpu_source = "/proc/9/stat";
  const nlohmann::ordered_json json = nlohmann::ordered_json::parse(LoadReportJson(r));
  std::vector<std::string> keys;
  for (const auto& [key, value] : json.items()) keys.push_back(key);
  const std::vector<std::string> expected = {"scene",
                                             "triangles",
                                             "clients",
                                             "viewers",
                                             "rate_hz",
                                             "step_s",
                                             "duration_s",
                                             "needs",
                                             "planes",
                                             "load_average_1m",
                                             "devices",
                                             "per_device",
                                             "viewers_total",
                                             "echo_run",
                                             "echo",
                                             "echo_request_bytes",
                                             "echo_reply_bytes",
                                             "step_ms",
                                             "steps",
                                             "missed_steps",
                                             "missed_steps_off_cpu",
                                             "missed_fraction",
                                             "tools_meet",
                                             "tools_touching_at_start",
                                             "tool_clashes",
                                             "tool_clash_s",
                                             "p99_ratio",
                                             "p99_budget_ms",
                                             "server_cpu_percent",
                                             "server_cpu_percent_per_device",
                                             "server_cpu_source",
                                             "client_cpu_percent",
                                             "echo_phase_cpu_percent",
                                             "machine_steal_ms"};
  EXPECT_EQ(keys, expected);
  EXPECT_EQ(json["needs"], "force friction");
  EXPECT_EQ(json["per_device"].size(), 2u);
  EXPECT_EQ(json["per_device"][1]["sent"], 7);
  EXPECT_EQ(json["devices"]["rtt_ms"]["p99_9"], 1.25);
  EXPECT_EQ(json["server_cpu_percent_per_device"], 15);
  EXPECT_EQ(json["server_cpu_source"], "/proc/9/stat");
  EXPECT_EQ(json["tools_touching_at_start"], -1);  // not known
}

// A stream's object has its counts and its round-trip percentiles.
TEST(ReportJsonTest, StreamFields) {
  LoadReport r;
  r.echo.sent = 3;
  r.echo.rtt_ms = {.count = 3, .mean = 1, .p50 = 1, .p99 = 2, .p999 = 2, .max = 2};
  r.echo.tool_clash_s = 0.5;
  const nlohmann::json echo = nlohmann::json::parse(LoadReportJson(r))["echo"];
  EXPECT_EQ(echo["sent"], 3);
  EXPECT_EQ(echo["rtt_ms"]["count"], 3);
  EXPECT_EQ(echo["rtt_ms"]["p99"], 2);
  EXPECT_EQ(echo["tool_clash_s"], 0.5);
  for (const char* key :
       {"answered", "frames", "frames_per_s", "first_step", "last_step", "dropped_frames",
        "missed_steps", "missed_steps_off_cpu", "tool_clashes"}) {
    EXPECT_TRUE(echo.contains(key)) << key;
  }
}

}  // namespace
}  // namespace hs::cli
