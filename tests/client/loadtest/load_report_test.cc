#include "client/loadtest/load_report.h"

#include <gtest/gtest.h>

namespace hs::cli {
namespace {

StreamReport Stream(int64_t sent, int64_t frames, int64_t dropped, int64_t first, int64_t last,
                    int64_t missed) {
  StreamReport r;
  r.sent = sent;
  r.answered = sent;
  r.frames = frames;
  r.dropped_frames = dropped;
  r.first_step = first;
  r.last_step = last;
  r.missed_steps = missed;
  r.missed_steps_off_cpu = missed / 2;
  return r;
}

// Pooling sums the counts, keeps the most missed steps any stream saw
// (they share one scene) and the first stream's steps, and takes the
// percentiles of every stream's round trips together.
TEST(LoadReportTest, PoolSumsCountsAndPoolsRoundTrips) {
  const std::vector<StreamReport> each = {Stream(10, 8, 2, 5, 14, 3), Stream(20, 9, 1, 6, 15, 4)};
  std::vector<double> rtt = {4, 1, 3, 2};
  const StreamReport total = Pool(each, rtt, 2.0);
  EXPECT_EQ(total.sent, 30);
  EXPECT_EQ(total.answered, 30);
  EXPECT_EQ(total.frames, 17);
  EXPECT_EQ(total.dropped_frames, 3);
  EXPECT_EQ(total.missed_steps, 4);
  EXPECT_EQ(total.missed_steps_off_cpu, 2);
  EXPECT_EQ(total.first_step, 5);
  EXPECT_EQ(total.last_step, 14);
  EXPECT_DOUBLE_EQ(total.frames_per_s, 8.5);
  EXPECT_EQ(total.rtt_ms.count, 4);
  EXPECT_DOUBLE_EQ(total.rtt_ms.mean, 2.5);
  EXPECT_DOUBLE_EQ(total.rtt_ms.max, 4);
}

// The scene's figures are device 0's: steps run = its step range, the
// missed fraction missed / (run + missed); every device is kept.
TEST(LoadReportTest, DeviceFiguresFromDeviceZero) {
  LoadReport report;
  std::vector<double> rtt = {1, 2};
  std::vector<double> step_ms = {0.2, 0.1};
  StreamReport first = Stream(10, 8, 2, 1, 100, 25);
  first.tool_clashes = 3;
  first.tool_clash_s = 0.5;
  SetDeviceFigures({first, Stream(10, 9, 1, 2, 101, 30)}, rtt, step_ms, 1.0, report);
  EXPECT_EQ(report.per_device.size(), 2u);
  EXPECT_EQ(report.devices.sent, 20);
  EXPECT_EQ(report.steps, 100);
  EXPECT_EQ(report.missed_steps, 25);
  EXPECT_EQ(report.missed_steps_off_cpu, 12);
  EXPECT_EQ(report.tool_clashes, 3);
  EXPECT_DOUBLE_EQ(report.tool_clash_s, 0.5);
  EXPECT_DOUBLE_EQ(report.missed_fraction, 25.0 / 125.0);
  EXPECT_DOUBLE_EQ(report.step_ms.max, 0.2);
}

// The echo's figures: its mean reply size over the streams, the p99 ratio
// devices / echo and the budget 1.5 x echo p99 + step p99.
TEST(LoadReportTest, EchoFiguresAgainstTheDevices) {
  LoadReport report;
  report.devices.rtt_ms.p99 = 3;
  report.step_ms.p99 = 0.5;
  std::vector<double> rtt = {2, 2, 2};
  SetEchoFigures({Stream(3, 3, 0, 0, 0, 0)}, rtt, {100, 201}, 1.0, report);
  EXPECT_TRUE(report.echo_run);
  EXPECT_EQ(report.echo_reply_bytes, 150);
  EXPECT_DOUBLE_EQ(report.echo.rtt_ms.p99, 2);
  EXPECT_DOUBLE_EQ(report.p99_ratio, 1.5);
  EXPECT_DOUBLE_EQ(report.p99_budget_ms, 3.5);
}

// CPU in % of one core over each kind's turns; the server's is also
// divided among the devices, and says where it was read.
TEST(LoadReportTest, CpuPercentAndPerDevice) {
  LoadReport report;
  report.clients = 4;
  TurnTotals cpu;
  cpu.wall_s[0] = 2;
  cpu.wall_s[1] = 4;
  cpu.server_s[0] = 1.2;
  cpu.client_s[0] = 0.5;
  cpu.client_s[1] = 1;
  SetCpuFigures(cpu, "/proc/7/stat", /*echo_run=*/true, report);
  EXPECT_DOUBLE_EQ(report.server_cpu_percent, 60);
  EXPECT_DOUBLE_EQ(report.server_cpu_percent_per_device, 15);
  EXPECT_EQ(report.server_cpu_source, "/proc/7/stat");
  EXPECT_DOUBLE_EQ(report.client_cpu_percent, 25);
  EXPECT_DOUBLE_EQ(report.echo_phase_cpu_percent, 25);
}

// A server reading that failed makes its figures unknown (-1), saying
// where they were to come from; no echo leaves its CPU figure at 0.
TEST(LoadReportTest, UnknownServerCpu) {
  LoadReport report;
  report.clients = 2;
  TurnTotals cpu;
  cpu.wall_s[0] = 1;
  cpu.server_s[0].reset();
  SetCpuFigures(cpu, "/proc/7/stat", /*echo_run=*/false, report);
  EXPECT_EQ(report.server_cpu_percent, -1);
  EXPECT_EQ(report.server_cpu_percent_per_device, -1);
  EXPECT_EQ(report.server_cpu_source, "unknown (/proc/7/stat)");
  EXPECT_EQ(report.echo_phase_cpu_percent, 0);
}

}  // namespace
}  // namespace hs::cli
