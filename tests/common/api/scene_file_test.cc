#include "common/api/scene_file.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/common/scratch_dir.h"
#include "tests/common/test_data_dir.h"

namespace hs {
namespace {

const std::string kScenes = hs::ScenesDir();

haptics::v1::SceneSpec Parse(const std::string& text) {
  haptics::v1::SceneSpec spec;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &spec)) << text;
  return spec;
}

// A box floor and a cube tool, as text; `extra` is appended to the tool.
std::string TwoObjects(const std::string& tool_extra = "", const std::string& scene_extra = "") {
  return R"(
    objects { name: "floor" kind: OBJECT_KIND_FIXED
              model { procedural { box { size_m { x: 1 y: 1 z: 0.1 } } } } }
    objects { name: "probe" kind: OBJECT_KIND_TOOL
              model { procedural { box { size_m { x: 0.02 y: 0.02 z: 0.02 } } } } )" +
         tool_extra + "}\n" + scene_extra;
}

// The bundled demo scene loads: its objects, names and tool, found by name.
TEST(SceneFileTest, BundledDemoSceneLoads) {
  absl::StatusOr<LoadedScene> loaded = LoadSceneFile(kScenes + "/probe_on_torus.textproto");
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  EXPECT_EQ(loaded->names, (std::vector<std::string>{"table", "organ", "probe"}));
  EXPECT_EQ(loaded->tools, (std::vector<ObjectId>{2}));
  EXPECT_DOUBLE_EQ(loaded->scene->options().step_s, 0.001);
  // Tools are found by name; an object that is no tool, or no object, is not one.
  EXPECT_EQ(FindTool(*loaded, "probe"), 2);
  EXPECT_EQ(FindTool(*loaded, "organ"), -1);
  EXPECT_EQ(FindTool(*loaded, "stylus"), -1);
}

// Model files are found relative to the scene file, with unit scale and
// material overrides by face group.
TEST(SceneFileTest, ModelFileWithMaterialOverride) {
  const std::filesystem::path dir = ScratchDir("scene_file_test");
  std::filesystem::copy_file(hs::TestDataDir() + "/cube.iv", dir / "cube.iv",
                             std::filesystem::copy_options::overwrite_existing);
  const auto spec = Parse(R"(
    objects { name: "cube" kind: OBJECT_KIND_FIXED model { path: "cube.iv" unit_scale: 0.01 }
              materials { face_group: "rubber" material { stiffness_n_per_m: 50 } } })");
  absl::StatusOr<LoadedScene> loaded = BuildScene(spec, dir.string());
  ASSERT_TRUE(loaded.ok()) << loaded.status();
}

// A free body loads with its mass and start velocity, the scene's gravity
// applies, and it moves when stepped: 1 kg given, dropping from rest under
// gravity (0, 0, -2) it has v = -2 dt after one step.
TEST(SceneFileTest, FreeBodyLoadsAndFalls) {
  const auto spec = Parse(TwoObjects("", R"(
    gravity_m_per_s2 { z: -2 }
    effects: EFFECT_FREE_BODY_MOTION effects: EFFECT_COLLISION
    objects { name: "ball" kind: OBJECT_KIND_FREE
              model { procedural { sphere { radius_m: 0.01 subdivisions: 1 } } }
              pose { position_m { z: 0.5 } }
              free_body { mass_kg: 1 velocity_m_per_s { x: 0.5 } } })"));
  absl::StatusOr<LoadedScene> loaded = BuildScene(spec, ".");
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  EXPECT_EQ(loaded->scene->options().gravity_W, Vector3d(0, 0, -2));
  const StepFrame& frame = loaded->scene->Step();
  ASSERT_EQ(frame.bodies.size(), 1u);
  EXPECT_EQ(loaded->names[frame.bodies[0].body], "ball");
  EXPECT_NEAR(frame.bodies[0].v_W.z(), -2 * 0.001, 1e-15);
  EXPECT_NEAR(frame.bodies[0].v_W.x(), 0.5, 1e-15);
  EXPECT_TRUE(frame.stages_run.Has(Effect::kFreeBodyMotion));
}

// Every bad field is rejected with INVALID_ARGUMENT naming where it is.
TEST(SceneFileTest, RejectsBadSpecs) {
  const std::pair<std::string, std::string> cases[] = {
      {TwoObjects("pose { position_m { x: nan } }"), "position_m"},
      {TwoObjects("pose { orientation { w: 2 } }"), "unit quaternion"},
      {TwoObjects(R"(materials { face_group: "bone" material {} })"), "no face group"},
      {TwoObjects(R"(materials { material { static_friction: 0.1 dynamic_friction: 0.5 } })"),
       "dynamic_friction"},
      {TwoObjects("", "step_s: -1"), "step_s"},
      {TwoObjects("", "relative_tolerance: 0.1"), "relative_tolerance"},
      {TwoObjects("", "effects: EFFECT_UNSPECIFIED"), "effect"},
      {TwoObjects("", "gravity_m_per_s2 { z: inf }"), "gravity_m_per_s2"},
      {TwoObjects("free_body { mass_kg: 1 }"), "only for OBJECT_KIND_FREE"},
      {R"(objects { name: "a" kind: OBJECT_KIND_FREE free_body { mass_kg: -1 }
                    model { procedural { box { size_m { x: 1 y: 1 z: 1 } } } } })",
       "free_body.mass_kg"},
      {R"(objects { name: "a" kind: OBJECT_KIND_FREE
                    free_body { velocity_m_per_s { y: nan } }
                    model { procedural { box { size_m { x: 1 y: 1 z: 1 } } } } })",
       "velocity_m_per_s"},
      {R"(objects { name: "a" kind: OBJECT_KIND_FIXED model { procedural { box {} } } })",
       "size_m"},
      {R"(objects { name: "a" model { procedural { box { size_m { x: 1 y: 1 z: 1 } } } } })",
       "kind"},
      {R"(objects { name: "a" kind: OBJECT_KIND_FIXED model { path: "/missing.obj" } })",
       "missing.obj"},
      {R"(objects { name: "a" kind: OBJECT_KIND_FIXED
                    model { procedural { torus { major_radius_m: 1 minor_radius_m: 2
                                                 major_segments: 8 minor_segments: 8 } } } })",
       "torus"},
      {TwoObjects() + R"(objects { name: "probe" kind: OBJECT_KIND_FIXED
                    model { procedural { sphere { radius_m: 1 } } } })",
       "unique"},
  };
  for (const auto& [text, expected] : cases) {
    SCOPED_TRACE(text);
    const absl::StatusOr<LoadedScene> loaded = BuildScene(Parse(text), ".");
    ASSERT_FALSE(loaded.ok());
    EXPECT_EQ(loaded.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(loaded.status().message().find(expected), std::string::npos)
        << loaded.status().message();
  }
}

// A model under 1 nm across is refused, however it got so small (its size,
// its unit scale, vertex moves): the contact methods hold from there up
// (ScalesLinearly in sweep_method_test and paper_method_test) and gave an
// infinite depth far below it. One just over the limit loads.
TEST(SceneFileTest, RefusesModelsUnderANanometreAcross) {
  // A box of side `side` (times `unit_scale`), then the object's `extra`.
  const auto speck = [](const std::string& side, const std::string& unit_scale = "1",
                        const std::string& extra = "") {
    return R"(objects { name: "speck" kind: OBJECT_KIND_FIXED
                        model { unit_scale: )" +
           unit_scale + " procedural { box { size_m { x: " + side + " y: " + side + " z: " + side +
           " } } } } " + extra + " }";
  };
  // Every corner of a 1 mm box moved to within 1e-12 m of the origin.
  std::string gathered;
  for (int v = 0; v < 8; ++v) {
    gathered += "vertex_moves { vertex_id: " + std::to_string(v) +
                " position_m { x: " + std::to_string(v % 2) + "e-12 } } ";
  }
  for (const std::string& text :
       {speck("5e-10"), speck("1e-60"), speck("0.5", "1e-9"), speck("1e-3", "1", gathered),
        std::string(R"(objects { name: "speck" kind: OBJECT_KIND_FIXED
                                 model { procedural { sphere { radius_m: 1e-60 } } } })")}) {
    SCOPED_TRACE(text);
    const absl::StatusOr<LoadedScene> loaded = BuildScene(Parse(text), ".");
    ASSERT_FALSE(loaded.ok());
    EXPECT_EQ(loaded.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(loaded.status().message().find("'speck'.model: is "), std::string::npos)
        << loaded.status().message();
    EXPECT_NE(loaded.status().message().find("under the 1e-09 m a contact query takes"),
              std::string::npos)
        << loaded.status().message();
  }
  EXPECT_TRUE(BuildScene(Parse(speck("1e-9")), ".").ok());
  EXPECT_TRUE(BuildScene(Parse(speck("1", "1e-9")), ".").ok());
}

// A file that is not a SceneSpec, or not there, fails with the file named.
TEST(SceneFileTest, UnreadableFiles) {
  EXPECT_EQ(ReadSceneFile("/missing.textproto").status().code(), absl::StatusCode::kNotFound);
  const std::string garbage = hs::TestDataDir() + "/garbage.obj";
  const auto status = ReadSceneFile(garbage).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("garbage.obj"), std::string::npos);
}

}  // namespace
}  // namespace hs
