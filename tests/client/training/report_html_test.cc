// report.html's text for a known run: figures rounded with their units,
// the date in UTC, names as they are, HTML-escaped.

#include "client/training/report_html.h"

#include <gtest/gtest.h>

namespace hs::cli {
namespace {

// 2026-11-27 14:03:30 UTC.
const auto kWritten = std::chrono::system_clock::time_point(std::chrono::seconds(1795788210));

// The date reads in UTC, to the minute.
TEST(ReportHtmlTest, DateIsUtcToTheMinute) {
  // By the calendar: 2026-11-27 is day 20,784 after 1970-01-01, and
  // 14:03:30 is 50,610 s into it.
  EXPECT_EQ(1795788210, 20784 * 86400 + 50610);
  EXPECT_EQ(UtcMinute(kWritten), "2026-11-27 14:03 UTC");
}

// A run of 91.04 points with a jerk of 9.3099 m/s^3 reads "Score 91.0 /
// 100" and "9.3 m/s³"; every figure has its unit; the tool and scene,
// which hold HTML's special characters, are escaped and not quoted.
TEST(ReportHtmlTest, FiguresAreRoundedWithUnits) {
  Exercise exercise;
  exercise.name = "three points";
  exercise.tool = "probe <A&B>";
  ScoreSummary s;
  s.score = 91.04;
  s.completed = true;
  s.duration_s = 5.6234;
  s.targets_reached = 3;
  s.targets = 3;
  s.path_length_m = 0.37915;
  s.economy = 1.25201;
  s.max_force_n = 1.20991;
  s.excess_impulse_ns = 0.01234;
  s.forbidden_contacts = 1;
  s.jerk_rms = 9.3099;
  s.target_results = {
      {.name = "crest", .reached = true, .reached_at_s = 1.2345, .max_force_n = 1.5}};
  s.forbidden_list = {
      {.object = "table", .start_s = 2.004, .duration_s = 0.05, .max_force_n = 2.104}};
  const std::vector<TracePoint> trace;
  const std::string html = ReportHtml({.exercise = &exercise,
                                       .scene = "probe \"on\" torus",
                                       .summary = s,
                                       .trace = &trace,
                                       .ended = "done"},
                                      kWritten, {});
  for (const char* expected : {
           "<b>probe &lt;A&amp;B&gt;</b> in scene <b>probe &quot;on&quot; torus</b>, "
           "2026-11-27 14:03 UTC; ended: done",
           "<h2>Score 91.0 / 100</h2>",
           "<th>Duration</th><td>5.62 s</td>",
           "<th>Targets reached</th><td>3 of 3</td>",
           "<th>Path length</th><td>0.38 m</td>",
           "<td>1.25</td>",
           "<th>Largest force</th><td>1.21 N</td>",
           "<th>Time over a force limit</th><td>0.00 s</td>",
           "<th>Impulse beyond the limit</th><td>0.012 N&middot;s</td>",
           "<th>Forbidden contacts</th><td>1</td>",
           "<th>Jerk (rms)</th><td>9.3 m/s&sup3;</td>",
           "<td>crest</td><td>yes</td><td>1.23 s</td><td>1.50 N</td>",
           "<p>table at 2.00 s for 0.05 s, up to 2.10 N</p>",
       }) {
    EXPECT_NE(html.find(expected), std::string::npos) << expected << "\nin\n" << html;
  }
  EXPECT_EQ(html.find("written_unix_s"), std::string::npos);
  EXPECT_EQ(html.find("\"probe"), std::string::npos) << "a name in JSON quotes";
}

}  // namespace
}  // namespace hs::cli
