#include "client/simulate_command.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "client/exit_codes.h"
#include "common/core/types.h"

namespace hs::cli {
namespace {

const std::string kScenes = std::string(HS_TEST_DATA_DIR) + "/../../scenes";

std::vector<nlohmann::json> Lines(const std::string& text) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

SimulateArgs DemoArgs() {
  return {.scene_file = kScenes + "/probe_on_torus.textproto",
          .steps = 60,
          .tool_path = kScenes + "/press_and_slide.csv",
          .needs = {},
          .json = true};
}

// The bundled demo prints one frame per step, in order, touching the organ
// and pushing the probe back up, then the stage statistics; and the same
// run again prints exactly the same frames (determinism; the statistics
// hold wall times, which differ).
TEST(SimulateCommandTest, DemoSceneFramesAndDeterminism) {
  std::ostringstream out, again, err;
  ASSERT_EQ(RunSimulate(DemoArgs(), out, err), kExitOk) << err.str();
  ASSERT_EQ(RunSimulate(DemoArgs(), again, err), kExitOk) << err.str();
  const auto lines = Lines(out.str());
  const auto lines_again = Lines(again.str());
  ASSERT_EQ(lines.size(), lines_again.size());
  for (size_t i = 0; i + 1 < lines.size(); ++i) EXPECT_EQ(lines[i].dump(), lines_again[i].dump());
  ASSERT_EQ(lines.size(), 61u);
  int touching = 0;
  for (int i = 0; i < 60; ++i) {
    EXPECT_EQ(lines[i]["step"], i + 1);
    const auto& tool = lines[i]["tools"][0];
    if (!tool["contacts"].empty()) {
      ++touching;
      EXPECT_EQ(tool["contacts"][0]["object"], "organ");
      EXPECT_GT(tool["force_W_n"][2].get<double>(), 0);
    }
  }
  EXPECT_GT(touching, 30);
  EXPECT_EQ(lines[60]["stage_stats"]["collision"]["runs"], 60);
}

// A consumer that needs only collision gets no contact-set runs.
TEST(SimulateCommandTest, NeedsLimitTheStages) {
  std::ostringstream out, err;
  SimulateArgs args = DemoArgs();
  args.needs = {"collision"};
  ASSERT_EQ(RunSimulate(args, out, err), kExitOk) << err.str();
  const auto stats = Lines(out.str()).back()["stage_stats"];
  EXPECT_EQ(stats["contact_set"]["runs"], 0);
  EXPECT_EQ(stats["force"]["runs"], 0);
  EXPECT_EQ(stats["collision"]["runs"], 60);
}

// Every bundled demo scene runs its device path, touches, and renders a
// force that resists the device's last motion.
TEST(SimulateCommandTest, EveryBundledDemoResistsItsPath) {
  const std::pair<std::string, std::string> demos[] = {
      {"probe_on_torus", "press_and_slide"},
      {"peg_in_hole", "peg_in_hole"},
      {"linked_rings", "linked_rings"},
      {"fine_organ", "fine_organ"},
  };
  for (const auto& [scene, path] : demos) {
    SCOPED_TRACE(scene);
    std::ostringstream out, err;
    SimulateArgs args{.scene_file = kScenes + "/" + scene + ".textproto",
                      .steps = 80,
                      .tool_path = kScenes + "/" + path + ".csv",
                      .needs = {},
                      .json = true};
    ASSERT_EQ(RunSimulate(args, out, err), kExitOk) << err.str();
    const auto lines = Lines(out.str());
    ASSERT_EQ(lines.size(), 81u);
    // The last two frames with a device move give the last motion.
    int last = 79;
    auto position = [&](int i) {
      const auto& p = lines[i]["tools"][0]["device_position_W_m"];
      return Vector3d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    };
    while (last > 0 && position(last) == position(last - 1)) --last;
    const Vector3d motion = position(last) - position(last - 1);
    const auto& f = lines[last]["tools"][0]["force_W_n"];
    const Vector3d force(f[0].get<double>(), f[1].get<double>(), f[2].get<double>());
    EXPECT_FALSE(lines[last]["tools"][0]["contacts"].empty());
    EXPECT_LT(force.dot(motion), 0) << force.transpose() << " vs " << motion.transpose();
  }
}

// Free bodies are printed each step: the 50,000-triangle demo's pebble,
// resting on the table, stays on it (its bottom within 1e-6 m of the top,
// z = 0) and reports its contact.
TEST(SimulateCommandTest, FreeBodyFrames) {
  std::ostringstream out, err;
  SimulateArgs args{.scene_file = kScenes + "/fine_organ.textproto",
                    .steps = 20,
                    .tool_path = "",
                    .needs = {},
                    .json = true};
  ASSERT_EQ(RunSimulate(args, out, err), kExitOk) << err.str();
  const auto lines = Lines(out.str());
  ASSERT_EQ(lines.size(), 21u);
  for (int i = 0; i < 20; ++i) {
    const auto& bodies = lines[i]["bodies"];
    ASSERT_EQ(bodies.size(), 1u);
    EXPECT_EQ(bodies[0]["body"], "pebble");
    EXPECT_NEAR(bodies[0]["position_W_m"][2].get<double>(), 0.015, 1e-6);
    EXPECT_EQ(bodies[0]["contacts"], 1);
  }
  EXPECT_EQ(lines[20]["stage_stats"]["free_body_motion"]["runs"], 20);
}

// Bad files and names fail with a message.
TEST(SimulateCommandTest, BadInputFails) {
  std::ostringstream out, err;
  SimulateArgs args = DemoArgs();
  args.tool_path = std::string(HS_TEST_DATA_DIR) + "/cube.obj";
  EXPECT_EQ(RunSimulate(args, out, err), kExitFailure);
  args = DemoArgs();
  args.needs = {"gravity"};
  EXPECT_EQ(RunSimulate(args, out, err), kExitFailure);
  args = DemoArgs();
  args.scene_file = "/missing.textproto";
  EXPECT_EQ(RunSimulate(args, out, err), kExitFailure);
  EXPECT_NE(err.str().find("gravity"), std::string::npos);
}

}  // namespace
}  // namespace hs::cli
