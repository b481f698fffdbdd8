#include "client/simulate_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "client/exit_codes.h"
#include "common/core/types.h"
#include "tests/common/scratch_dir.h"
#include "tests/common/test_data_dir.h"

namespace hs::cli {
namespace {

const std::string kScenes = hs::ScenesDir();

std::vector<nlohmann::json> Lines(const std::string& text) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

SimulateArgs DemoArgs() {
  return {.scene_file = kScenes + "/probe_on_torus.textproto",
          .steps = 60,
          .tool_paths = {kScenes + "/press_and_slide.csv"},
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
                      .tool_paths = {kScenes + "/" + path + ".csv"},
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
                    .tool_paths = {},
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

// The demo scene with a second probe, "stylus", 0.2 m west of the first
// (over the organ's west side), written to a scratch folder; and a path
// pressing each straight down 1.5 cm over 60 steps from its home.
struct TwoTools {
  TwoTools() {
    const std::filesystem::path dir = ScratchDir("two_tools");
    std::ifstream demo(kScenes + "/probe_on_torus.textproto");
    std::ostringstream text;
    text << demo.rdbuf() << R"(objects { name: "stylus" kind: OBJECT_KIND_TOOL)"
         << R"( model { procedural { box { size_m { x: 0.02 y: 0.02 z: 0.02 } } } })"
         << R"( pose { position_m { x: -0.1 z: 0.1 } } })";
    scene = (dir / "two_tools.textproto").string();
    std::ofstream(scene) << text.str();
    probe = Press(dir / "probe.csv", 0.1);
    stylus = Press(dir / "stylus.csv", -0.1);
  }
  static std::string Press(const std::filesystem::path& file, double x) {
    std::ofstream out(file);
    for (int i = 0; i <= 60; ++i) out << x << ",0," << 0.1 - 0.015 * i / 60 << ",0,0,0\n";
    return file.string();
  }
  std::string scene, probe, stylus;
};

// Each tool follows its own path (TOOL=FILE; the bare form is the first
// tool's): both devices are where their files put them, and both press
// the organ.
TEST(SimulateCommandTest, EachToolAlongItsOwnPath) {
  const TwoTools files;
  std::ostringstream out, err;
  SimulateArgs args{.scene_file = files.scene,
                    .steps = 61,
                    .tool_paths = {files.probe, "stylus=" + files.stylus},
                    .needs = {},
                    .json = true};
  ASSERT_EQ(RunSimulate(args, out, err), kExitOk) << err.str();
  const auto lines = Lines(out.str());
  ASSERT_EQ(lines.size(), 62u);
  const auto& last = lines[60]["tools"];
  ASSERT_EQ(last.size(), 2u);
  for (const auto& tool : last) {
    SCOPED_TRACE(tool.dump());
    const double x = tool["tool"] == "probe" ? 0.1 : -0.1;
    EXPECT_EQ(tool["device_position_W_m"][0].get<double>(), x);
    EXPECT_NEAR(tool["device_position_W_m"][2].get<double>(), 0.085, 1e-12);
    ASSERT_FALSE(tool["contacts"].empty());
    EXPECT_EQ(tool["contacts"][0]["object"], "organ");
    EXPECT_GT(tool["force_W_n"][2].get<double>(), 0);
  }
}

// A path for an object that is not a tool, for no object, or two paths
// for one tool: refused, naming it.
TEST(SimulateCommandTest, ToolPathsNameTheirTools) {
  const TwoTools files;
  auto run = [&](std::vector<std::string> paths) {
    std::ostringstream out, err;
    SimulateArgs args{.scene_file = files.scene, .steps = 1, .tool_paths = std::move(paths)};
    EXPECT_EQ(RunSimulate(args, out, err), kExitFailure);
    return err.str();
  };
  EXPECT_NE(run({"organ=" + files.probe}).find("'organ' is not a tool"), std::string::npos);
  EXPECT_NE(run({"stylsu=" + files.stylus}).find("no tool named 'stylsu'"), std::string::npos);
  EXPECT_NE(run({files.probe, "probe=" + files.stylus}).find("'probe' has two paths"),
            std::string::npos);
}

// Bad files and names fail with a message.
TEST(SimulateCommandTest, BadInputFails) {
  std::ostringstream out, err;
  SimulateArgs args = DemoArgs();
  args.tool_paths = {hs::TestDataDir() + "/cube.obj"};
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
