// A run's report folder: report.json (the exercise, the summary as
// SummaryJson has it, the attempts' scores), the plots drawn by gnuplot,
// and report.html holding them inline.

#include "client/training/report.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "client/training/score_output.h"
#include "nlohmann/json.hpp"
#include "tests/common/scratch_dir.h"

namespace hs::cli {
namespace {

namespace fs = std::filesystem;

std::string Read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

bool IsPng(const fs::path& path) { return Read(path).rfind("\x89PNG\r\n\x1a\n", 0) == 0; }

// A two-target exercise with a forbidden ball and a force limit, and a run
// along x scoring `score`.
struct ReportedRun {
  Exercise exercise;
  std::vector<TracePoint> trace;
  ScoreSummary summary;

  explicit ReportedRun(double score) {
    exercise.name = "two points";
    exercise.tool = "probe";
    exercise.targets = {
        {.name = "east", .object = "organ", .region = {Vector3d(0.1, 0, 0), 0.01}},
        {.name = "west", .object = "organ", .region = {Vector3d(-0.1, 0, 0), 0.01}}};
    exercise.forbidden = {{.object = "organ", .region = Ball{Vector3d(0, 0.1, 0), 0.02}},
                          {.object = "table"}};
    exercise.force_limits = {{"organ", 3}};
    for (int i = 0; i <= 100; ++i) {
      trace.push_back({.t_s = 0.01 * i,
                       .force_n = 0.02 * i,
                       .limit_n = i < 50 ? 0.0 : 3.0,
                       .p_WD = Vector3d(0.1 - 0.002 * i, 0, 0.01)});
    }
    summary.score = score;
    summary.completed = true;
    summary.duration_s = 1;
    summary.targets_reached = 2;
    summary.targets = 2;
    summary.target_results = {{.name = "east", .reached = true}, {.name = "west", .reached = true}};
  }
  ReportInput Input(std::vector<std::string> compare = {}) const {
    return {.exercise = &exercise,
            .scene = "duo",
            .summary = summary,
            .trace = &trace,
            .ended = "done",
            .compare = std::move(compare)};
  }
};

// report.json names the exercise, tool, scene and ending, the time written
// (between the call's start and end), every summary field as SummaryJson
// writes it and this run's score as its only attempt; force.png and path.png
// are PNGs, there is no attempts.png, and report.html has the plots inline.
TEST(ReportTest, WritesJsonPlotsAndHtml) {
  const ReportedRun run(72.5);
  const fs::path dir = ScratchDir("report") / "made" / "here";
  const auto before = std::chrono::system_clock::now();
  ASSERT_TRUE(WriteReport(dir.string(), run.Input()).ok());
  const auto after = std::chrono::system_clock::now();
  const nlohmann::json report = nlohmann::json::parse(Read(dir / "report.json"));
  EXPECT_EQ(report["exercise"], "two points");
  EXPECT_EQ(report["tool"], "probe");
  EXPECT_EQ(report["scene"], "duo");
  EXPECT_EQ(report["ended"], "done");
  const auto unix_s = [](auto t) {
    return std::chrono::duration_cast<std::chrono::seconds>(t.time_since_epoch()).count();
  };
  EXPECT_GE(report["written_unix_s"].get<int64_t>(), unix_s(before));
  EXPECT_LE(report["written_unix_s"].get<int64_t>(), unix_s(after));
  const nlohmann::ordered_json summary = SummaryJson(run.summary);
  for (const auto& [key, value] : summary.items()) {
    EXPECT_EQ(nlohmann::json(report[key]), nlohmann::json(value)) << key;
  }
  EXPECT_EQ(report["attempt_scores"], nlohmann::json::array({72.5}));
  EXPECT_TRUE(IsPng(dir / "force.png"));
  EXPECT_TRUE(IsPng(dir / "path.png"));
  EXPECT_FALSE(fs::exists(dir / "attempts.png"));
  const std::string html = Read(dir / "report.html");
  EXPECT_NE(html.find("two points"), std::string::npos);
  size_t images = 0;
  for (size_t at = html.find("data:image/png;base64,"); at != std::string::npos;
       at = html.find("data:image/png;base64,", at + 1)) {
    ++images;
  }
  EXPECT_EQ(images, 2u);
}

// Earlier reports' folders add their scores before this run's, oldest
// first, and an attempts plot; a report is read back as the next one's
// earlier attempt.
TEST(ReportTest, EarlierAttemptsComeFirst) {
  const fs::path root = ScratchDir("report_attempts");
  ASSERT_TRUE(WriteReport((root / "first").string(), ReportedRun(40).Input()).ok());
  ASSERT_TRUE(WriteReport((root / "second").string(), ReportedRun(60.5).Input()).ok());
  ASSERT_TRUE(
      WriteReport((root / "third").string(),
                  ReportedRun(80).Input({(root / "first").string(), (root / "second").string()}))
          .ok());
  const nlohmann::json report = nlohmann::json::parse(Read(root / "third" / "report.json"));
  EXPECT_EQ(report["attempt_scores"], nlohmann::json::array({40, 60.5, 80}));
  EXPECT_TRUE(IsPng(root / "third" / "attempts.png"));
  const std::string html = Read(root / "third" / "report.html");
  EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);
}

// A compared folder without a report.json with a score is INVALID_ARGUMENT
// naming it, and nothing is written.
TEST(ReportTest, EarlierFolderWithoutReportIsRefused) {
  const fs::path root = ScratchDir("report_refused");
  fs::create_directories(root / "scoreless");
  std::ofstream(root / "scoreless" / "report.json") << R"({"score": "high"})";
  for (const std::string earlier : {(root / "empty").string(), (root / "scoreless").string()}) {
    const fs::path dir = root / "out";
    const absl::Status status = WriteReport(dir.string(), ReportedRun(50).Input({earlier}));
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << status;
    EXPECT_NE(status.message().find(earlier), std::string::npos) << status;
    EXPECT_FALSE(fs::exists(dir));
  }
}

// Without gnuplot the report is INTERNAL and report.html is not written.
// PATH is pointed at an empty folder for the call; the shell that found no
// gnuplot may close the pipe before the script is written, which must not
// kill the process (SIGPIPE keeps its default action here).
TEST(ReportTest, NoGnuplotIsInternal) {
  const fs::path root = ScratchDir("report_no_gnuplot");
  const std::string path = std::getenv("PATH");
  ASSERT_EQ(setenv("PATH", root.c_str(), 1), 0);
  const absl::Status status = WriteReport((root / "out").string(), ReportedRun(50).Input());
  ASSERT_EQ(setenv("PATH", path.c_str(), 1), 0);
  EXPECT_EQ(status.code(), absl::StatusCode::kInternal) << status;
  EXPECT_FALSE(fs::exists(root / "out" / "report.html"));
}

}  // namespace
}  // namespace hs::cli
