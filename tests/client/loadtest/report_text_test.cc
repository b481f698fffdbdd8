#include "client/loadtest/report_text.h"

#include <gtest/gtest.h>

#include <sstream>

namespace hs::cli {
namespace {

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The text names the settings, has a row per device, the echo's lines only
// when it ran, and the server's CPU with its share per device.
TEST(ReportTextTest, Lines) {
  LoadReport r;
  r.clients = 2;
  r.rate_hz = 1000;
  r.scene = "loadtest-5";
  r.per_device.resize(2);
  r.server_cpu_percent = 30;
  r.server_cpu_percent_per_device = 15;
  r.server_cpu_source = "/proc/9/stat";
  std::ostringstream out;
  PrintLoadReport(r, out);
  const std::string text = out.str();
  EXPECT_TRUE(Has(text, "loadtest: 2 device(s) x 1000.000 Hz")) << text;
  EXPECT_TRUE(Has(text, "scene 'loadtest-5'")) << text;
  EXPECT_TRUE(Has(text, "  device 0")) << text;
  EXPECT_TRUE(Has(text, "  device 1")) << text;
  EXPECT_FALSE(Has(text, "echo (turns")) << text;
  EXPECT_TRUE(Has(text, "server 30.000, 15.000 per device (/proc/9/stat)")) << text;
  EXPECT_FALSE(Has(text, "hypervisor")) << text;              // unknown: -1
  EXPECT_FALSE(Has(text, "touch where they start")) << text;  // unknown: -1
  r.echo_run = true;
  r.machine_steal_ms = 2;
  std::ostringstream with_echo;
  PrintLoadReport(r, with_echo);
  EXPECT_TRUE(Has(with_echo.str(), "echo (turns with the devices)")) << with_echo.str();
  EXPECT_TRUE(Has(with_echo.str(), "hypervisor: 2.000 ms")) << with_echo.str();
  r.tools_touching_at_start = 3;
  std::ostringstream touching;
  PrintLoadReport(r, touching);
  EXPECT_TRUE(Has(touching.str(), "WARNING: 3 tool pairs touch where they start"))
      << touching.str();
}

}  // namespace
}  // namespace hs::cli
