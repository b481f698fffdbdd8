// Exercise files: checked against their scene, every region turned into the
// world frame through its object's pose, and each bad field refused by name.

#include "common/api/exercise_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include "google/protobuf/text_format.h"
#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// The organ turned a quarter about z and lifted 0.04 m: its object frame's
// (0.1, 0, 0) is the world's (0, 0.1, 0.04).
constexpr char kScene[] = R"pb(
  name: "duo"
  step_s: 0.001
  objects {
    name: "organ"
    kind: OBJECT_KIND_FIXED
    model { procedural { box { size_m { x: 0.2 y: 0.2 z: 0.05 } } } }
    pose {
      position_m { z: 0.04 }
      orientation { w: 0.7071067811865476 z: 0.7071067811865476 }
    }
  }
  objects {
    name: "probe"
    kind: OBJECT_KIND_TOOL
    model { procedural { box { size_m { x: 0.02 y: 0.02 z: 0.02 } } } }
    pose { position_m { x: 0.1 z: 0.1 } }
  }
)pb";

constexpr char kExercise[] = R"pb(
  name: "two points"
  tool: "probe"
  targets {
    name: "east"
    object: "organ"
    sphere {
      center_m { x: 0.1 }
      radius_m: 0.015
    }
    min_force_n: 0.5
    max_force_n: 3
    hold_s: 0.3
  }
  targets {
    object: "organ"
    sphere {
      center_m { y: 0.1 }
      radius_m: 0.02
    }
  }
  forbidden {
    object: "organ"
    sphere {
      center_m { x: -0.1 }
      radius_m: 0.01
    }
  }
  forbidden { object: "organ" }
  force_limits { object: "organ" limit_n: 3 }
  time_limit_s: 20
)pb";

template <class Message>
Message Parse(const char* text) {
  Message m;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &m));
  return m;
}

// Objects' regions in the world frame through their object's pose (a quarter
// turn about z and a lift, so x goes to y); unnamed targets numbered from 1;
// max force 0 is no bound; a forbidden object without a sphere is all of it;
// the tool's home is its place in the scene; no weights is the defaults.
TEST(ExerciseFileTest, RegionsInTheWorldFrame) {
  const absl::StatusOr<Exercise> e =
      ExerciseFromSpec(Parse<pb::ExerciseSpec>(kExercise), Parse<pb::SceneSpec>(kScene));
  ASSERT_TRUE(e.ok()) << e.status();
  EXPECT_EQ(e->name, "two points");
  EXPECT_EQ(e->tool, "probe");
  ASSERT_TRUE(e->tool_home_W.has_value());
  EXPECT_EQ(*e->tool_home_W, Vector3d(0.1, 0, 0.1));
  ASSERT_EQ(e->targets.size(), 2u);
  EXPECT_EQ(e->targets[0].name, "east");
  EXPECT_EQ(e->targets[0].object, "organ");
  EXPECT_TRUE(e->targets[0].region.center_W.isApprox(Vector3d(0, 0.1, 0.04), 1e-12))
      << e->targets[0].region.center_W.transpose();
  EXPECT_EQ(e->targets[0].region.radius_m, 0.015);
  EXPECT_EQ(e->targets[0].min_force_n, 0.5);
  EXPECT_EQ(e->targets[0].max_force_n, 3);
  EXPECT_EQ(e->targets[0].hold_s, 0.3);
  EXPECT_EQ(e->targets[1].name, "target 2");
  EXPECT_TRUE(e->targets[1].region.center_W.isApprox(Vector3d(-0.1, 0, 0.04), 1e-12))
      << e->targets[1].region.center_W.transpose();
  EXPECT_EQ(e->targets[1].max_force_n, std::numeric_limits<double>::infinity());
  ASSERT_EQ(e->forbidden.size(), 2u);
  ASSERT_TRUE(e->forbidden[0].region.has_value());
  EXPECT_TRUE(e->forbidden[0].region->center_W.isApprox(Vector3d(0, -0.1, 0.04), 1e-12));
  EXPECT_FALSE(e->forbidden[1].region.has_value());
  ASSERT_EQ(e->force_limits.size(), 1u);
  EXPECT_EQ(e->force_limits[0].object, "organ");
  EXPECT_EQ(e->force_limits[0].limit_n, 3);
  EXPECT_EQ(e->time_limit_s, 20);
  const ScoreWeights defaults;
  EXPECT_EQ(e->weights.targets, defaults.targets);
  EXPECT_EQ(e->weights.smoothness, defaults.smoothness);
}

// Weights given are taken as given.
TEST(ExerciseFileTest, GivenWeightsAreTaken) {
  pb::ExerciseSpec spec = Parse<pb::ExerciseSpec>(kExercise);
  spec.mutable_weights()->set_targets(1);
  spec.mutable_weights()->set_force(2);
  const absl::StatusOr<Exercise> e = ExerciseFromSpec(spec, Parse<pb::SceneSpec>(kScene));
  ASSERT_TRUE(e.ok()) << e.status();
  EXPECT_EQ(e->weights.targets, 1);
  EXPECT_EQ(e->weights.force, 2);
  EXPECT_EQ(e->weights.time, 0);
  EXPECT_EQ(e->weights.smoothness, 0);
}

struct BadSpec {
  std::string field;  // what the error must name
  std::function<void(pb::ExerciseSpec&)> spoil;
};

// Each bad field is INVALID_ARGUMENT naming it.
TEST(ExerciseFileTest, BadFieldsAreNamed) {
  const double nan = std::nan("");
  const BadSpec bad[] = {
      {"tool", [](pb::ExerciseSpec& s) { s.set_tool("hand"); }},
      {"tool", [](pb::ExerciseSpec& s) { s.set_tool("organ"); }},
      {"targets", [](pb::ExerciseSpec& s) { s.clear_targets(); }},
      {"targets[1].object", [](pb::ExerciseSpec& s) { s.mutable_targets(1)->set_object("liver"); }},
      {"targets[0].object", [](pb::ExerciseSpec& s) { s.mutable_targets(0)->set_object("probe"); }},
      {"targets[0].sphere.radius_m",
       [](pb::ExerciseSpec& s) { s.mutable_targets(0)->mutable_sphere()->set_radius_m(0); }},
      {"targets[0].sphere.radius_m",
       [](pb::ExerciseSpec& s) { s.mutable_targets(0)->mutable_sphere()->set_radius_m(-1); }},
      {"targets[0].sphere.center_m",
       [&](pb::ExerciseSpec& s) {
         s.mutable_targets(0)->mutable_sphere()->mutable_center_m()->set_x(nan);
       }},
      {"targets[0].min_force_n",
       [&](pb::ExerciseSpec& s) { s.mutable_targets(0)->set_min_force_n(nan); }},
      {"targets[0].max_force_n",
       [](pb::ExerciseSpec& s) { s.mutable_targets(0)->set_max_force_n(0.5); }},
      {"targets[0].max_force_n",
       [](pb::ExerciseSpec& s) { s.mutable_targets(0)->set_max_force_n(-1); }},
      {"targets[0].hold_s", [](pb::ExerciseSpec& s) { s.mutable_targets(0)->set_hold_s(-0.1); }},
      {"forbidden[1].object",
       [](pb::ExerciseSpec& s) { s.mutable_forbidden(1)->set_object("probe"); }},
      {"forbidden[0].sphere.radius_m",
       [](pb::ExerciseSpec& s) { s.mutable_forbidden(0)->mutable_sphere()->set_radius_m(0); }},
      {"force_limits[0].object",
       [](pb::ExerciseSpec& s) { s.mutable_force_limits(0)->set_object("liver"); }},
      {"force_limits[0].limit_n",
       [](pb::ExerciseSpec& s) { s.mutable_force_limits(0)->set_limit_n(0); }},
      {"time_limit_s", [](pb::ExerciseSpec& s) { s.set_time_limit_s(0); }},
      {"time_limit_s",
       [](pb::ExerciseSpec& s) { s.set_time_limit_s(std::numeric_limits<double>::infinity()); }},
      {"weights", [](pb::ExerciseSpec& s) { s.mutable_weights()->set_economy(-1); }},
  };
  const pb::SceneSpec scene = Parse<pb::SceneSpec>(kScene);
  for (const BadSpec& b : bad) {
    pb::ExerciseSpec spec = Parse<pb::ExerciseSpec>(kExercise);
    b.spoil(spec);
    const absl::Status status = ExerciseFromSpec(spec, scene).status();
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << b.field << ": " << status;
    EXPECT_NE(status.message().find(b.field), std::string::npos) << b.field << ": " << status;
  }
}

std::string Write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

// A file names its scene relative to its own folder; what is loaded is the
// spec, the scene file's resolved path, its spec and the exercise.
TEST(ExerciseFileTest, LoadsTheSceneBesideTheFile) {
  const std::filesystem::path root = ScratchDir("exercise_file");
  std::filesystem::create_directories(root / "scenes");
  std::filesystem::create_directories(root / "exercises");
  Write(root / "scenes" / "duo.textproto", kScene);
  const std::string path =
      Write(root / "exercises" / "two.textproto",
            std::string(kExercise) + "scene_file: \"../scenes/duo.textproto\"");
  const absl::StatusOr<LoadedExercise> loaded = LoadExerciseFile(path);
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  EXPECT_EQ(loaded->scene_file, (root / "scenes" / "duo.textproto").string());
  EXPECT_EQ(loaded->scene.name(), "duo");
  EXPECT_EQ(loaded->spec.name(), "two points");
  EXPECT_EQ(loaded->exercise.targets.size(), 2u);
}

// Errors name the exercise file: no scene file named, a scene file that is
// not there, an exercise its scene refutes.
TEST(ExerciseFileTest, ErrorsNameTheFile) {
  const std::filesystem::path root = ScratchDir("exercise_file_errors");
  Write(root / "duo.textproto", kScene);
  const std::string none = Write(root / "none.textproto", kExercise);
  const absl::Status no_scene = LoadExerciseFile(none).status();
  EXPECT_EQ(no_scene.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(no_scene.message().find(none), std::string::npos) << no_scene;
  EXPECT_NE(no_scene.message().find("scene_file"), std::string::npos) << no_scene;
  const std::string missing =
      Write(root / "missing.textproto", std::string(kExercise) + "scene_file: \"gone.textproto\"");
  EXPECT_EQ(LoadExerciseFile(missing).status().code(), absl::StatusCode::kNotFound);
  std::string organ_as_tool = std::string(kExercise) + "scene_file: \"duo.textproto\"";
  const std::string probe = "tool: \"probe\"";
  organ_as_tool.replace(organ_as_tool.find(probe), probe.size(), "tool: \"organ\"");
  const std::string wrong_tool = Write(root / "wrong_tool.textproto", organ_as_tool);
  const absl::Status refuted = LoadExerciseFile(wrong_tool).status();
  EXPECT_EQ(refuted.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(refuted.message().find(wrong_tool), std::string::npos) << refuted;
  EXPECT_NE(refuted.message().find("tool"), std::string::npos) << refuted;
}

}  // namespace
}  // namespace hs
