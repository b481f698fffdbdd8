// `hapticctl drive --operator` against an in-process server: the summary's
// figures under their names, the trace file, a reference run before a
// lossy link, and failures as exit statuses.

#include "client/remote/remote_drive.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "client/exit_codes.h"
#include "nlohmann/json.hpp"
#include "tests/common/scratch_dir.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

const std::vector<std::string> kKeys = {"mode",
                                        "operator",
                                        "latency_ms",
                                        "jitter_ms",
                                        "loss",
                                        "stall_prob",
                                        "stall_ms",
                                        "seed",
                                        "pose_rate_hz",
                                        "frame_rate_hz",
                                        "ticks",
                                        "reference_force_rms_n",
                                        "energy_j",
                                        "max_force_step_n",
                                        "max_force_n",
                                        "penetration_p99_m",
                                        "penetration_max_m",
                                        "force_rms_error_n",
                                        "uplink_mean_ms",
                                        "downlink_mean_ms",
                                        "round_trip_p50_ms",
                                        "round_trip_p99_ms",
                                        "poses_lost",
                                        "frames_lost",
                                        "poses_stalled",
                                        "frames_stalled",
                                        "models_rejected",
                                        "models_restarted",
                                        "beyond_validity_ticks",
                                        "passivity_ticks",
                                        "passivity_dissipated_j"};

class RemoteDriveTest : public ::testing::Test {
 protected:
  RemoteDriveTest() {
    server_.Create(hs::testing::SmallScene("s"));
    args_.scene = "s";
    args_.tool = "probe";
    args_.json = true;
    // The probe's bottom is 3 cm above the table: a 6 cm press meets it.
    args_.run.hand.depth_m = 0.06;
  }
  int Drive() {
    out_.str("");
    err_.str("");
    return RunRemoteDrive(args_, server_.channel(), nullptr, start_, out_, err_);
  }

  hs::testing::TestServer server_;
  RemoteDriveArgs args_;
  const Isometry3d start_ = Isometry3d(Eigen::Translation3d(0, 0, 0.05));
  std::ostringstream out_, err_;
};

// An ideal link: one JSON object with every figure under its name, the
// options echoed, 800 ticks for 0.8 s at 1 kHz, a force felt from the
// table, nothing lost and no reference (so no force error); the trace has
// a header and one line per tick, at its time.
TEST_F(RemoteDriveTest, IdealLinkSummaryAndTrace) {
  args_.duration_s = 0.8;
  args_.trace_path = (ScratchDir("remote_drive") / "trace.csv").string();
  ASSERT_EQ(Drive(), kExitOk) << err_.str();
  const nlohmann::json summary = nlohmann::json::parse(out_.str());
  std::vector<std::string> keys;
  for (const auto& [key, value] : summary.items()) keys.push_back(key);
  std::vector<std::string> sorted_keys = kKeys;
  std::sort(sorted_keys.begin(), sorted_keys.end());
  EXPECT_EQ(keys, sorted_keys);  // nlohmann::json keeps its keys sorted
  EXPECT_EQ(summary["mode"], "local_model");
  EXPECT_EQ(summary["operator"], "press");
  EXPECT_EQ(summary["pose_rate_hz"], RemoteRunOptions{}.pose_rate_hz);   // the SDK device's
  EXPECT_EQ(summary["frame_rate_hz"], RemoteRunOptions{}.pose_rate_hz);  // as poses go
  EXPECT_EQ(summary["ticks"], 800);
  EXPECT_GT(summary["max_force_n"].get<double>(), 0);
  EXPECT_EQ(summary["force_rms_error_n"], 0);
  EXPECT_EQ(summary["poses_lost"], 0);
  EXPECT_EQ(summary["frames_lost"], 0);
  std::ifstream trace(args_.trace_path);
  std::string line;
  ASSERT_TRUE(std::getline(trace, line));
  EXPECT_EQ(line, "t_s,fx_n,fy_n,fz_n,x_m,y_m,z_m");
  int rows = 0;
  while (std::getline(trace, line)) {
    EXPECT_NEAR(std::stod(line.substr(0, line.find(','))), rows * 1e-3, 1e-12) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 800);
}

// A lossy, late link runs an ideal reference first: the force error
// against it is above 0, lost poses are counted, and the link is echoed;
// without --json each figure is a "key: value" line.
TEST_F(RemoteDriveTest, LossyLinkAgainstAReference) {
  args_.duration_s = 0.6;
  args_.json = false;
  args_.run.local_model = false;
  args_.run.link = {.latency_ms = 5, .loss = 0.2, .seed = 7};
  args_.run.pose_rate_hz = 500;
  args_.frame_rate_hz = 500;
  ASSERT_EQ(Drive(), kExitOk) << err_.str();
  std::istringstream lines(out_.str());
  std::string line;
  std::map<std::string, std::string> figures;
  while (std::getline(lines, line)) {
    const size_t colon = line.find(": ");
    ASSERT_NE(colon, std::string::npos) << line;
    figures[line.substr(0, colon)] = line.substr(colon + 2);
  }
  EXPECT_EQ(figures.size(), kKeys.size());
  EXPECT_EQ(figures["mode"], "\"server_force\"");
  EXPECT_EQ(std::stod(figures["latency_ms"]), 5);
  EXPECT_EQ(std::stod(figures["loss"]), 0.2);
  EXPECT_EQ(figures["seed"], "7");
  EXPECT_EQ(std::stod(figures["pose_rate_hz"]), 500);
  EXPECT_EQ(std::stod(figures["frame_rate_hz"]), 500);
  EXPECT_GT(std::stod(figures["force_rms_error_n"]), 0);
  EXPECT_GT(std::stoi(figures["poses_lost"]), 0);
}

// An unknown tool is NOT_FOUND's exit status, reported for "drive"; a trace
// that cannot be written fails after the run.
TEST_F(RemoteDriveTest, Failures) {
  args_.duration_s = 0.05;
  args_.tool = "nope";
  EXPECT_EQ(Drive(), kExitNotFound);
  EXPECT_NE(err_.str().find("drive"), std::string::npos) << err_.str();
  args_.tool = "probe";
  args_.trace_path = (ScratchDir("remote_drive_bad") / "no" / "such" / "trace.csv").string();
  EXPECT_EQ(Drive(), kExitFailure);
  EXPECT_NE(err_.str().find("cannot write"), std::string::npos) << err_.str();
}

}  // namespace
}  // namespace hs::cli
